# install(): what `cmake --install build` (or `catkin_make install`) puts into an install
# space (P = CMAKE_INSTALL_PREFIX, set at configure time: catkin writes it into P/setup.bash),
# laid out as catkin expects, so that `source P/setup.bash` then `rosrun nonsmooth_sim
# nonsmooth_sim_node` / `roslaunch nonsmooth_sim tippe_top.launch` work from it
# (test/install/install_test.py checks exactly that). Included last from CMakeLists.txt, with ROS.
#
#   P/lib/nonsmooth_sim/        nonsmooth_sim_node, simulate, node_speed_subscriber, the report scripts
#   P/lib/                      the static libraries (core, mesh, scene_io, collision_fcl, ros)
#   P/include/nonsmooth_sim/    the headers (and the generated message headers, by catkin)
#   P/share/nonsmooth_sim/      package.xml, launch/, urdf/, config/, meshes/ (msg/, srv/, cmake/ by catkin)

install(TARGETS simulate nonsmooth_sim_node node_speed_subscriber
  RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
install(TARGETS nonsmooth_sim_core nonsmooth_sim_mesh nonsmooth_sim_scene_io nonsmooth_sim_world nonsmooth_sim_collision_fcl nonsmooth_sim_ros
  ARCHIVE DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION}
  LIBRARY DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION})
install(DIRECTORY include/${PROJECT_NAME}/ DESTINATION ${CATKIN_PACKAGE_INCLUDE_DESTINATION}
  FILES_MATCHING PATTERN "*.h")
# the scenes, their initial states and meshes, launch files and the rviz configuration
install(DIRECTORY launch urdf config meshes DESTINATION ${CATKIN_PACKAGE_SHARE_DESTINATION})
# rosrun nonsmooth_sim scene_report.py ...; the shebang becomes the configured
# PYTHON_EXECUTABLE (default /usr/bin/python3; cmake -DPYTHON_EXECUTABLE=... to change)
catkin_install_python(PROGRAMS scripts/scene_report.py scripts/dev/tradeoff_report.py
  DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
# tradeoff_report.py's modules, next to it
install(DIRECTORY scripts/dev/tradeoff_study DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION}
  FILES_MATCHING PATTERN "*.py")
