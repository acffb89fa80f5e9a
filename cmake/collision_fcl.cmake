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

nonsmooth_sim_add_gtests(DIR test/collision_fcl LIBRARIES nonsmooth_sim_collision_fcl)

# the benchmarks time the FCL pairs next to the closed forms (bench/collision_bench.cpp)
if(TARGET nonsmooth_sim_bench)
  target_link_libraries(nonsmooth_sim_bench PRIVATE nonsmooth_sim_collision_fcl)
endif()
