# GoogleTest executables of one test folder: every <dir>/*_test.cpp is one executable (named
# <prefix>_<file> with a PREFIX, else <file>) in <build>/test_bin, built by the `tests` target (not
# by `all`), linked to LIBRARIES, with NONSMOOTH_SIM_SOURCE_DIR defined; one ctest entry per TEST
# ("<prefix>.<Suite>.<Test>" with a PREFIX). Included first from CMakeLists.txt.
enable_testing()
include(CTest)
find_package(GTest REQUIRED)
include(GoogleTest)
if(NOT TARGET tests)
  add_custom_target(tests)  # catkin reuses it when ROS is on
endif()

function(nonsmooth_sim_add_gtests)
  cmake_parse_arguments(ARG "" "DIR;PREFIX" "LIBRARIES" ${ARGN})
  file(GLOB sources CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/${ARG_DIR}/*_test.cpp)
  foreach(source ${sources})
    get_filename_component(name ${source} NAME_WE)
    set(discover_prefix "")
    if(ARG_PREFIX)
      set(name ${ARG_PREFIX}_${name})
      set(discover_prefix TEST_PREFIX "${ARG_PREFIX}.")
    endif()
    add_executable(${name} EXCLUDE_FROM_ALL ${source})
    target_link_libraries(${name} PRIVATE ${ARG_LIBRARIES} GTest::gtest GTest::gtest_main)
    target_compile_definitions(${name} PRIVATE NONSMOOTH_SIM_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
    set_target_properties(${name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/test_bin)
    add_dependencies(tests ${name})
    gtest_discover_tests(${name} ${discover_prefix} DISCOVERY_MODE PRE_TEST DISCOVERY_TIMEOUT 60)
  endforeach()
endfunction()
