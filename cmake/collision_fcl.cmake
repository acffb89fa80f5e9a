# FCL adapter (include/nonsmooth_sim/collision_fcl): the narrow phase of the shape pairs without a
# closed form, by FCL. A library of its own so that the core stays Eigen-only; `simulate`, the
# node, the fuzz targets and the benchmarks register its pairs into their scenes' collision tables
# (RegisterFclPairs). Its tests (test/collision_fcl) are in cmake/tests.cmake.

file(GLOB NONSMOOTH_SIM_COLLISION_FCL_SOURCES CONFIGURE_DEPENDS
     ${PROJECT_SOURCE_DIR}/src/collision_fcl/*.cpp)
add_library(nonsmooth_sim_collision_fcl STATIC ${NONSMOOTH_SIM_COLLISION_FCL_SOURCES})
target_include_directories(nonsmooth_sim_collision_fcl PUBLIC ${PROJECT_SOURCE_DIR}/include)
target_link_libraries(nonsmooth_sim_collision_fcl PUBLIC nonsmooth_sim_core fcl)
set_target_properties(nonsmooth_sim_collision_fcl PROPERTIES POSITION_INDEPENDENT_CODE ON)
