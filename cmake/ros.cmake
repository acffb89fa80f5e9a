# The ROS 1 node: its library, the executable, the node-speed subscriber, and (with
# CATKIN_ENABLE_TESTING) the tests of the ROS layer. Included from CMakeLists.txt after the
# libraries when NONSMOOTH_SIM_WITH_ROS is ON; cmake/catkin.cmake ran first.

# ---------------------------------------------------------------------------------------------
# The node: a library (URDF -> Scene, message conversion, the node class) and a tiny main.
add_library(nonsmooth_sim_ros STATIC
  src/node/conversions.cpp
  src/node/node_parameters.cpp
  src/node/node_services.cpp
  src/node/simulation_node.cpp
  src/node/world_services.cpp
  src/node/model_services.cpp
  src/node/master_calls.cpp)
# the message headers (<build>/devel/include) and catkin's come from include_directories() in
# cmake/catkin.cmake
target_include_directories(nonsmooth_sim_ros PUBLIC ${PROJECT_SOURCE_DIR}/include)
target_link_libraries(nonsmooth_sim_ros PUBLIC
  nonsmooth_sim_world nonsmooth_sim_core nonsmooth_sim_scene_io nonsmooth_sim_collision_fcl
  ${catkin_LIBRARIES})
add_dependencies(nonsmooth_sim_ros ${PROJECT_NAME}_generate_messages_cpp)

add_executable(nonsmooth_sim_node src/node/main.cpp)
target_link_libraries(nonsmooth_sim_node PRIVATE nonsmooth_sim_ros)
set_target_properties(nonsmooth_sim_node PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${NONSMOOTH_SIM_BIN_DIR})

# The counting subscriber of scripts/dev/node-speed (a measurement tool, not a test).
add_executable(node_speed_subscriber bench/node_speed_subscriber.cpp)
target_link_libraries(node_speed_subscriber PRIVATE ${catkin_LIBRARIES})
add_dependencies(node_speed_subscriber ${PROJECT_NAME}_generate_messages_cpp)
set_target_properties(node_speed_subscriber PROPERTIES
  RUNTIME_OUTPUT_DIRECTORY ${NONSMOOTH_SIM_BIN_DIR})

# ---------------------------------------------------------------------------------------------
# Tests of the ROS layer. Built by the `tests` target (catkin's test targets are not in `all`).
if(CATKIN_ENABLE_TESTING)
  # Every rostest gets a writable ROS_HOME, loopback networking and Debian's python first.
  set(NONSMOOTH_SIM_ROS_TEST_ENV
    "ROS_HOME=${CMAKE_BINARY_DIR}/ros_home"
    "ROS_IP=127.0.0.1"
    "PATH=/usr/bin:/bin:/usr/sbin:/sbin")
  file(MAKE_DIRECTORY ${CMAKE_BINARY_DIR}/ros_home)

  # test-only dependencies (package.xml: test_depend): rostest, and tf2_ros for a TF listener
  find_package(rostest REQUIRED)
  find_package(tf2_ros REQUIRED)

  # URDF conversion, initial conditions, message conversion and the master calls' queue: no
  # master needed.
  add_executable(node_conversion_test EXCLUDE_FROM_ALL
    test/node/conversions_test.cpp test/node/master_calls_test.cpp)
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
    target_link_libraries(${name} nonsmooth_sim_ros ${tf2_ros_LIBRARIES})
    target_include_directories(${name} SYSTEM PRIVATE ${tf2_ros_INCLUDE_DIRS})
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
  nonsmooth_sim_rostest(node_accuracy_test)
  nonsmooth_sim_rostest(node_services_test)
  nonsmooth_sim_rostest(node_inversion_test)
  nonsmooth_sim_rostest(node_bad_urdf_test)
  nonsmooth_sim_rostest(node_scene_test)
  nonsmooth_sim_rostest(node_diagnostics_test)
  nonsmooth_sim_rostest(node_world_test)
  nonsmooth_sim_rostest(node_spawn_test)
  nonsmooth_sim_rostest(node_fuzz_test)
  nonsmooth_sim_rostest(node_bounds_test)
  # the launch files with a model of the user's own: scene.launch, and tippe_top.launch with the
  # same test
  nonsmooth_sim_rostest(node_launch_model_test)
  nonsmooth_sim_rostest(node_fixed_links_test)
  add_rostest(test/node/node_launch_model_tippe.test DEPENDENCIES node_launch_model_test)
  set_tests_properties(_ctest_${PROJECT_NAME}_rostest_test_node_node_launch_model_tippe.test
    PROPERTIES ENVIRONMENT "${NONSMOOTH_SIM_ROS_TEST_ENV}" TIMEOUT 120)
  nonsmooth_sim_rostest(node_master_test)
  # the hammer stops sending after NONSMOOTH_SIM_HAMMER_SECONDS (60 s by default); longer runs by
  # option (docs/testing.md)
  set_tests_properties(_ctest_${PROJECT_NAME}_rostest_test_node_node_fuzz_test.test PROPERTIES
    TIMEOUT 1500)
  # two 100 000-step calls one after the other: minutes under the sanitizers
  set_tests_properties(_ctest_${PROJECT_NAME}_rostest_test_node_node_master_test.test PROPERTIES
    TIMEOUT 300)

  # A bag recorded through the launch file (scripts/record), checked topic by topic.
  add_test(NAME node_bag_record_test
    COMMAND ${CATKIN_ENV} /usr/bin/python3 ${PROJECT_SOURCE_DIR}/test/node/bag_record_test.py
            --build-dir ${CMAKE_BINARY_DIR})
  set_tests_properties(node_bag_record_test PROPERTIES
    ENVIRONMENT "${NONSMOOTH_SIM_ROS_TEST_ENV}" TIMEOUT 120)
  # A bag of a run with a spawn (scripts/spawn_tops) and a delete: the deleted top's TF stops.
  add_test(NAME node_bag_spawn_test
    COMMAND ${CATKIN_ENV} /usr/bin/python3 ${PROJECT_SOURCE_DIR}/test/node/bag_spawn_test.py
            --build-dir ${CMAKE_BINARY_DIR})
  set_tests_properties(node_bag_spawn_test PROPERTIES
    ENVIRONMENT "${NONSMOOTH_SIM_ROS_TEST_ENV}" TIMEOUT 120)
  # The README's "while it runs" commands, as a user copies them, against the launched node.
  add_test(NAME node_readme_commands_test
    COMMAND ${CATKIN_ENV} /usr/bin/python3 ${PROJECT_SOURCE_DIR}/test/docs/readme_commands_test.py
            --build-dir ${CMAKE_BINARY_DIR})
  set_tests_properties(node_readme_commands_test PROPERTIES
    ENVIRONMENT "${NONSMOOTH_SIM_ROS_TEST_ENV}" TIMEOUT 300)
endif()

# The install space and the devel space, used the ROS ways (rosrun, roslaunch), and the launch
# files' required/clear_params (test/install/install_test.py). Installs into a temporary prefix.
if(CATKIN_ENABLE_TESTING)
  add_test(NAME install_test
    COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/test/install/install_test.py
            --build-dir ${CMAKE_BINARY_DIR})
  set_tests_properties(install_test PROPERTIES TIMEOUT 600)
endif()

# Every parameter, service, topic and launch argument is in docs/ros.md (no ROS needed), and the
# package is catkin_lint clean (errors and warnings fail; notices are style).
if(CATKIN_ENABLE_TESTING)
  add_test(NAME ros_docs_test
    COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/test/docs/ros_docs_test.py)
  add_test(NAME catkin_lint_test
    COMMAND catkin_lint --strict ${PROJECT_SOURCE_DIR})
  set_tests_properties(catkin_lint_test PROPERTIES ENVIRONMENT "PATH=/usr/bin:/bin")
endif()
