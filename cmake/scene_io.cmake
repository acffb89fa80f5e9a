# Scene loader: URDF (urdfdom + TinyXML2) and YAML initial states (yaml-cpp) -> core Scene. No ROS:
# included from CMakeLists.txt right after the core library, with NONSMOOTH_SIM_WITH_ROS ON or OFF.
# Debian packages: liburdfdom-dev libtinyxml2-dev libyaml-cpp-dev (scripts/install-deps); <mesh>
# through the mesh library (cmake/mesh.cmake). Its tests
# (test/scene_io, "scene_io.<Suite>.<Test>") are in cmake/tests.cmake.

file(GLOB NONSMOOTH_SIM_SCENE_IO_SOURCES CONFIGURE_DEPENDS
  ${PROJECT_SOURCE_DIR}/src/scene_io/*.cpp)
add_library(nonsmooth_sim_scene_io STATIC ${NONSMOOTH_SIM_SCENE_IO_SOURCES})
target_include_directories(nonsmooth_sim_scene_io PUBLIC ${PROJECT_SOURCE_DIR}/include)
target_link_libraries(nonsmooth_sim_scene_io
  PUBLIC nonsmooth_sim_core
  PRIVATE nonsmooth_sim_mesh urdfdom::urdfdom_model tinyxml2::tinyxml2 yaml-cpp)
set_target_properties(nonsmooth_sim_scene_io PROPERTIES POSITION_INDEPENDENT_CODE ON)
