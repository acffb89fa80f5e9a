# The world library: models and their names, spawn and delete, the wrench schedule, placement and
# the one route to a start, over the core's Simulator (include/nonsmooth_sim/world, src/world).
# ROS-free (test/scene_io/ros_free_test checks its includes): used by the node, `simulate
# --schedule` and the service-sequence fuzz target. Its tests (test/world, "world.<Suite>.<Test>")
# are in cmake/tests.cmake.
file(GLOB NONSMOOTH_SIM_WORLD_SOURCES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/src/world/*.cpp)
add_library(nonsmooth_sim_world STATIC ${NONSMOOTH_SIM_WORLD_SOURCES})
target_include_directories(nonsmooth_sim_world PUBLIC ${PROJECT_SOURCE_DIR}/include)
target_link_libraries(nonsmooth_sim_world PUBLIC nonsmooth_sim_core nonsmooth_sim_scene_io)
set_target_properties(nonsmooth_sim_world PROPERTIES POSITION_INDEPENDENT_CODE ON)
