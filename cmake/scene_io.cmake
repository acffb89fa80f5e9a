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
# Tests: every test/scene_io/*_test.cpp is one GoogleTest executable scene_io_<file> (the node
# has a urdf_scene_test of its own), ctest entries "scene_io.<Suite>.<Test>".
nonsmooth_sim_add_gtests(DIR test/scene_io PREFIX scene_io LIBRARIES nonsmooth_sim_scene_io)
