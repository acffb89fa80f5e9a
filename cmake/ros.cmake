# The ROS 1 layer: messages, services, the node, rostests. Included from CMakeLists.txt when
# NONSMOOTH_SIM_WITH_ROS is ON. Debian's ROS lives in /usr (see README, "Building").

# Gotcha: pyenv's python3 first on PATH has no catkin_pkg; use Debian's.
set(PYTHON_EXECUTABLE /usr/bin/python3 CACHE FILEPATH "")
set(Python3_EXECUTABLE /usr/bin/python3 CACHE FILEPATH "")
# Gotcha: ctest captures the environment at the first configure; make the python path exist.
file(MAKE_DIRECTORY ${CMAKE_BINARY_DIR}/devel/lib/python3/dist-packages)

find_package(catkin REQUIRED COMPONENTS
  roscpp rosbag rostest std_msgs std_srvs geometry_msgs visualization_msgs rosgraph_msgs
  tf2_ros diagnostic_updater message_generation)

set(NONSMOOTH_SIM_BIN_DIR ${CATKIN_DEVEL_PREFIX}/${CATKIN_PACKAGE_BIN_DESTINATION})
catkin_package(CATKIN_DEPENDS roscpp)
