# Physics tests of the shipped scenes (urdf/*.urdf + config/*.yaml through the scene loader, stepped
# by the core Simulator): every test/scenes/*_test.cpp is one GoogleTest executable
# scenes_<name>, one ctest entry per TEST ("scenes.<Suite>.<Test>"), built by the `tests` target,
# the pattern of the core tests. Included from CMakeLists.txt after the core and the scene loader
# (cmake/scene_io.cmake: nonsmooth_sim_scene_io, which links nonsmooth_sim_core). The derivations
# and the numbers they check are in docs/scenes.md; each run is a few seconds in Release at most.
enable_testing()
find_package(GTest REQUIRED)
include(GoogleTest)
if(NOT TARGET tests)
  add_custom_target(tests)  # catkin defines it when ROS is on
endif()

file(GLOB NONSMOOTH_SIM_SCENE_TESTS CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/test/scenes/*_test.cpp)
foreach(test_source ${NONSMOOTH_SIM_SCENE_TESTS})
  get_filename_component(test_name ${test_source} NAME_WE)
  set(test_name scenes_${test_name})  # coin_test, die_test, ... may exist elsewhere one day
  add_executable(${test_name} EXCLUDE_FROM_ALL ${test_source})
  target_link_libraries(${test_name} PRIVATE nonsmooth_sim_scene_io nonsmooth_sim_core
                        GTest::gtest GTest::gtest_main)
  target_compile_definitions(${test_name} PRIVATE
    NONSMOOTH_SIM_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
  set_target_properties(${test_name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/test_bin)
  add_dependencies(tests ${test_name})
  gtest_discover_tests(${test_name} TEST_PREFIX "scenes."
    DISCOVERY_MODE PRE_TEST DISCOVERY_TIMEOUT 60)
endforeach()
