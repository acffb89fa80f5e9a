# FCL adapter (include/nonsmooth_sim/collision_fcl): the narrow phase of the shape pairs without a
# closed form, by FCL. A library of its own so that the core stays Eigen-only; its tests are
# test/collision_fcl/*_test.cpp, one GoogleTest executable each, as the core tests. Included from
# CMakeLists.txt after the core, its tests and the benchmarks.
find_package(fcl REQUIRED)  # libfcl-dev (scripts/install-deps)

file(GLOB NONSMOOTH_SIM_COLLISION_FCL_SOURCES CONFIGURE_DEPENDS
     ${PROJECT_SOURCE_DIR}/src/collision_fcl/*.cpp)
add_library(nonsmooth_sim_collision_fcl STATIC ${NONSMOOTH_SIM_COLLISION_FCL_SOURCES})
target_include_directories(nonsmooth_sim_collision_fcl PUBLIC ${PROJECT_SOURCE_DIR}/include)
target_link_libraries(nonsmooth_sim_collision_fcl PUBLIC nonsmooth_sim_core fcl)
set_target_properties(nonsmooth_sim_collision_fcl PROPERTIES POSITION_INDEPENDENT_CODE ON)

file(GLOB NONSMOOTH_SIM_COLLISION_FCL_TESTS CONFIGURE_DEPENDS
     ${PROJECT_SOURCE_DIR}/test/collision_fcl/*_test.cpp)
foreach(test_source ${NONSMOOTH_SIM_COLLISION_FCL_TESTS})
  get_filename_component(test_name ${test_source} NAME_WE)
  add_executable(${test_name} EXCLUDE_FROM_ALL ${test_source})
  target_link_libraries(${test_name} PRIVATE nonsmooth_sim_collision_fcl GTest::gtest
                        GTest::gtest_main)
  target_compile_definitions(${test_name} PRIVATE
    NONSMOOTH_SIM_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
  set_target_properties(${test_name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/test_bin)
  add_dependencies(tests ${test_name})
  gtest_discover_tests(${test_name} DISCOVERY_MODE PRE_TEST DISCOVERY_TIMEOUT 60)
endforeach()

# the benchmarks time the FCL pairs next to the closed forms (bench/collision_bench.cpp)
if(TARGET nonsmooth_sim_bench)
  target_link_libraries(nonsmooth_sim_bench PRIVATE nonsmooth_sim_collision_fcl)
endif()
