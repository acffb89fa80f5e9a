# catkin first (catkin_lint: no target before find_package(catkin) and catkin_package()): the
# messages and services, what a dependent package gets, and where binaries go
# (<build>/devel/lib/nonsmooth_sim, the rosrun/roslaunch location). Included from CMakeLists.txt
# before any target when NONSMOOTH_SIM_WITH_ROS is ON. Debian's ROS lives in /usr (docs/building.md).

# Gotcha: pyenv's python3 first on PATH has no catkin_pkg; use Debian's. A default only: another
# python with catkin_pkg and genpy is chosen with cmake -DPYTHON_EXECUTABLE=... -DPython3_EXECUTABLE=...
set(PYTHON_EXECUTABLE /usr/bin/python3 CACHE FILEPATH "python3 with catkin_pkg, genmsg, genpy")
set(Python3_EXECUTABLE ${PYTHON_EXECUTABLE} CACHE FILEPATH "the same python for FindPython3")
# Gotcha: ctest captures the environment at the first configure; make the python path exist.
file(MAKE_DIRECTORY ${CMAKE_BINARY_DIR}/devel/lib/python3/dist-packages)

# The node's dependencies (package.xml: depend); the tests' (rostest, tf2_ros) further down.
find_package(catkin REQUIRED COMPONENTS
  roscpp std_msgs std_srvs geometry_msgs visualization_msgs rosgraph_msgs tf2_msgs
  diagnostic_msgs diagnostic_updater message_generation)

# ---------------------------------------------------------------------------------------------
# Messages and services (generated headers: <build>/devel/include/nonsmooth_sim/).
add_message_files(DIRECTORY msg FILES
  BodyInfo.msg ContactInfo.msg ContactInfoArray.msg ContactSteps.msg ModelState.msg
  SimulationState.msg)
# the world services' types have the names, fields and field types of gazebo_msgs (ROS 1)
add_service_files(DIRECTORY srv FILES
  ApplyBodyWrench.srv BodyRequest.srv DeleteModel.srv GetFrictionSet.srv GetModelProperties.srv
  GetModelState.srv GetSimulationState.srv GetSolverProperties.srv GetWorldProperties.srv
  ResetState.srv SetFrictionSet.srv SetModelState.srv SetSolverProperties.srv SpawnModel.srv
  StepSimulation.srv)
generate_messages(DEPENDENCIES std_msgs geometry_msgs)

# What a package that depends on this one gets: the headers, the libraries (core, scene loader, world,
# FCL pairs, the node's library) and the message headers.
catkin_package(
  INCLUDE_DIRS include
  LIBRARIES nonsmooth_sim_ros nonsmooth_sim_world nonsmooth_sim_collision_fcl nonsmooth_sim_scene_io nonsmooth_sim_mesh nonsmooth_sim_core
  CATKIN_DEPENDS roscpp message_runtime std_msgs std_srvs geometry_msgs visualization_msgs
                 rosgraph_msgs tf2_msgs diagnostic_msgs diagnostic_updater
  DEPENDS EIGEN3 urdfdom)
include_directories(SYSTEM ${catkin_INCLUDE_DIRS})

set(NONSMOOTH_SIM_BIN_DIR ${CATKIN_DEVEL_PREFIX}/${CATKIN_PACKAGE_BIN_DESTINATION})
