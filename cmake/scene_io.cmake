# Scene loader: URDF (urdfdom + TinyXML2) and YAML initial states (yaml-cpp) -> core Scene. No ROS:
# included from CMakeLists.txt right after the core library, with NONSMOOTH_SIM_WITH_ROS ON or OFF.
# Debian packages: liburdfdom-dev libtinyxml2-dev libyaml-cpp-dev (scripts/install-deps).
find_package(urdfdom REQUIRED)   # urdfdom::urdfdom_model, <urdf_parser/urdf_parser.h>
find_package(tinyxml2 REQUIRED)  # tinyxml2::tinyxml2
find_package(yaml-cpp REQUIRED)  # yaml-cpp

file(GLOB NONSMOOTH_SIM_SCENE_IO_SOURCES CONFIGURE_DEPENDS
  ${PROJECT_SOURCE_DIR}/src/scene_io/*.cpp)
add_library(nonsmooth_sim_scene_io STATIC ${NONSMOOTH_SIM_SCENE_IO_SOURCES})
target_include_directories(nonsmooth_sim_scene_io PUBLIC ${PROJECT_SOURCE_DIR}/include)
target_link_libraries(nonsmooth_sim_scene_io
  PUBLIC nonsmooth_sim_core
  PRIVATE urdfdom::urdfdom_model tinyxml2::tinyxml2 yaml-cpp)
set_target_properties(nonsmooth_sim_scene_io PROPERTIES POSITION_INDEPENDENT_CODE ON)

# ---------------------------------------------------------------------------------------------
# Tests: every test/scene_io/*_test.cpp is one GoogleTest executable, one ctest entry per TEST
# (the pattern of the core tests; the `tests` target builds them).
enable_testing()
find_package(GTest REQUIRED)
include(GoogleTest)
if(NOT TARGET tests)
  add_custom_target(tests)  # catkin reuses it when ROS is on
endif()
file(GLOB NONSMOOTH_SIM_SCENE_IO_TESTS CONFIGURE_DEPENDS
  ${PROJECT_SOURCE_DIR}/test/scene_io/*_test.cpp)
foreach(test_source ${NONSMOOTH_SIM_SCENE_IO_TESTS})
  get_filename_component(test_name ${test_source} NAME_WE)
  set(test_name scene_io_${test_name})  # urdf_scene_test is also a name of the node's tests
  add_executable(${test_name} EXCLUDE_FROM_ALL ${test_source})
  target_link_libraries(${test_name} PRIVATE nonsmooth_sim_scene_io GTest::gtest GTest::gtest_main)
  target_compile_definitions(${test_name} PRIVATE
    NONSMOOTH_SIM_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
  set_target_properties(${test_name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/test_bin)
  add_dependencies(tests ${test_name})
  gtest_discover_tests(${test_name} TEST_PREFIX "scene_io."
    DISCOVERY_MODE PRE_TEST DISCOVERY_TIMEOUT 60)
endforeach()
