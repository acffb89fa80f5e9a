# The ROS 1 layer: messages, services, the node, rostests. Included from CMakeLists.txt when
# NONSMOOTH_SIM_WITH_ROS is ON. Debian's ROS lives in /usr (see README, "Building").

# Gotcha: pyenv's python3 first on PATH has no catkin_pkg; use Debian's.
set(PYTHON_EXECUTABLE /usr/bin/python3 CACHE FILEPATH "")
set(Python3_EXECUTABLE /usr/bin/python3 CACHE FILEPATH "")
# Gotcha: ctest captures the environment at the first configure; make the python path exist.
file(MAKE_DIRECTORY ${CMAKE_BINARY_DIR}/devel/lib/python3/dist-packages)

find_package(catkin REQUIRED COMPONENTS
  roscpp rosbag rostest std_msgs std_srvs geometry_msgs visualization_msgs rosgraph_msgs
  tf2_msgs tf2_ros diagnostic_msgs diagnostic_updater message_generation)
find_package(urdfdom REQUIRED)
find_package(tinyxml2 REQUIRED)

# ---------------------------------------------------------------------------------------------
# Messages and services (generated headers: build/devel/include/nonsmooth_sim/).
add_message_files(DIRECTORY msg FILES
  BodyInfo.msg ContactInfo.msg ContactInfoArray.msg SimulationState.msg)
add_service_files(DIRECTORY srv FILES
  GetFrictionSet.srv GetSimulationState.srv GetSolverProperties.srv ResetState.srv
  SetFrictionSet.srv SetSolverProperties.srv StepSimulation.srv)
generate_messages(DEPENDENCIES std_msgs geometry_msgs)

catkin_package(
  INCLUDE_DIRS include
  CATKIN_DEPENDS roscpp message_runtime std_msgs std_srvs geometry_msgs visualization_msgs
                 rosgraph_msgs tf2_msgs diagnostic_msgs diagnostic_updater)

set(NONSMOOTH_SIM_BIN_DIR ${CATKIN_DEVEL_PREFIX}/${CATKIN_PACKAGE_BIN_DESTINATION})

# ---------------------------------------------------------------------------------------------
# The node: a library (URDF -> Scene, message conversion, the node class) and a tiny main.
add_library(nonsmooth_sim_ros STATIC
  src/node/conversions.cpp
  src/node/initial_conditions.cpp
  src/node/node_parameters.cpp
  src/node/node_services.cpp
  src/node/simulation_node.cpp)
target_include_directories(nonsmooth_sim_ros PUBLIC
  ${PROJECT_SOURCE_DIR}/include
  ${CATKIN_DEVEL_PREFIX}/${CATKIN_GLOBAL_INCLUDE_DESTINATION})
target_include_directories(nonsmooth_sim_ros SYSTEM PUBLIC ${catkin_INCLUDE_DIRS}
  ${urdfdom_INCLUDE_DIRS})
target_link_libraries(nonsmooth_sim_ros PUBLIC
  nonsmooth_sim_core nonsmooth_sim_scene_io ${catkin_LIBRARIES})
add_dependencies(nonsmooth_sim_ros ${PROJECT_NAME}_generate_messages_cpp)

add_executable(nonsmooth_sim_node src/node/main.cpp)
target_link_libraries(nonsmooth_sim_node PRIVATE nonsmooth_sim_ros)
set_target_properties(nonsmooth_sim_node PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${NONSMOOTH_SIM_BIN_DIR})

# The counting subscriber of scripts/node-speed (a measurement tool, not a test).
add_executable(node_speed_subscriber bench/node_speed_subscriber.cpp)
target_include_directories(node_speed_subscriber PRIVATE
  ${CATKIN_DEVEL_PREFIX}/${CATKIN_GLOBAL_INCLUDE_DESTINATION})
target_include_directories(node_speed_subscriber SYSTEM PRIVATE ${catkin_INCLUDE_DIRS})
target_link_libraries(node_speed_subscriber PRIVATE ${catkin_LIBRARIES})
add_dependencies(node_speed_subscriber ${PROJECT_NAME}_generate_messages_cpp)
set_target_properties(node_speed_subscriber PROPERTIES
  RUNTIME_OUTPUT_DIRECTORY ${NONSMOOTH_SIM_BIN_DIR})

# ---------------------------------------------------------------------------------------------
# Tests of the ROS layer. Built by the `tests` target (catkin's test targets are not in `all`).
# Every rostest gets a writable ROS_HOME, loopback networking and Debian's python first.
set(NONSMOOTH_SIM_ROS_TEST_ENV
  "ROS_HOME=${CMAKE_BINARY_DIR}/ros_home"
  "ROS_IP=127.0.0.1"
  "PATH=/usr/bin:$ENV{PATH}")
file(MAKE_DIRECTORY ${CMAKE_BINARY_DIR}/ros_home)

# URDF conversion, initial conditions and message conversion: no master needed.
find_package(GTest REQUIRED)
include(GoogleTest)
add_executable(node_conversion_test EXCLUDE_FROM_ALL
  test/node/initial_conditions_test.cpp
  test/node/conversions_test.cpp)
target_link_libraries(node_conversion_test PRIVATE nonsmooth_sim_ros GTest::gtest GTest::gtest_main)
target_compile_definitions(node_conversion_test PRIVATE
  NONSMOOTH_SIM_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
set_target_properties(node_conversion_test PROPERTIES
  RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/test_bin)
add_dependencies(tests node_conversion_test)
gtest_discover_tests(node_conversion_test DISCOVERY_MODE PRE_TEST DISCOVERY_TIMEOUT 60)

# rostests: a gtest node next to the node under test, started from the launch file.
function(nonsmooth_sim_rostest name)
  add_rostest_gtest(${name} test/node/${name}.test test/node/${name}.cpp)
  target_link_libraries(${name} nonsmooth_sim_ros)
  target_compile_definitions(${name} PRIVATE
    NONSMOOTH_SIM_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    NONSMOOTH_SIM_NODE_EXECUTABLE="${NONSMOOTH_SIM_BIN_DIR}/nonsmooth_sim_node")
  set_target_properties(${name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${NONSMOOTH_SIM_BIN_DIR})
  add_dependencies(${name} nonsmooth_sim_node)
  set_tests_properties(_ctest_${PROJECT_NAME}_rostest_test_node_${name}.test PROPERTIES
    ENVIRONMENT "${NONSMOOTH_SIM_ROS_TEST_ENV}" TIMEOUT 120)
endfunction()
nonsmooth_sim_rostest(node_running_test)
nonsmooth_sim_rostest(node_step_test)
nonsmooth_sim_rostest(node_services_test)
nonsmooth_sim_rostest(node_inversion_test)
nonsmooth_sim_rostest(node_bad_urdf_test)
nonsmooth_sim_rostest(node_scene_test)

# A bag recorded through the launch file (scripts/record), checked topic by topic.
add_test(NAME node_bag_record_test
  COMMAND ${CATKIN_ENV} /usr/bin/python3 ${PROJECT_SOURCE_DIR}/test/node/bag_record_test.py
          --build-dir ${CMAKE_BINARY_DIR})
set_tests_properties(node_bag_record_test PROPERTIES
  ENVIRONMENT "${NONSMOOTH_SIM_ROS_TEST_ENV}" TIMEOUT 120)
