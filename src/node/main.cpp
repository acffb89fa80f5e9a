// nonsmooth_sim_node: the simulator served to ROS. A bad parameter or URDF stops it at start-up
// with one error line and exit code 1 (also out of memory and any other exception).
#include <ros/ros.h>

#include <exception>
#include <new>

#include "nonsmooth_sim/collision_fcl/fcl_pairs.h"
#include "nonsmooth_sim/node/node_parameters.h"
#include "nonsmooth_sim/node/simulation_node.h"
#include "nonsmooth_sim/scene_io/one_line.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "nonsmooth_sim");
  ros::NodeHandle nh;
  ros::NodeHandle private_nh("~");
  try {
    using namespace nonsmooth_sim::node;
    NodeParameters parameters = ReadNodeParameters(nh, private_nh);
    // the scene's collision table (of the URDF and of every spawned model): the core's closed
    // forms, and FCL for the convex pairs without one (box–box, cylinder–box, ...)
    nonsmooth_sim::RegisterFclPairs(&parameters.scene.collision_table);
    UrdfScene urdf = SceneFromUrdf(parameters.urdf_xml, parameters.scene);
    SimulationNode node(nh, private_nh, std::move(parameters), std::move(urdf));
    // two spinner threads: a long ~step (it runs in chunks) does not hold up the other services
    ros::AsyncSpinner spinner(2);
    spinner.start();
    ros::waitForShutdown();
  } catch (const std::bad_alloc&) {
    ROS_FATAL_STREAM("out of memory at start-up (the scene needs more memory than the system "
                     "gives)");
    return 1;
  } catch (const std::exception& e) {
    ROS_FATAL_STREAM(nonsmooth_sim::scene_io::OneLine(e.what()));
    return 1;
  } catch (...) {
    ROS_FATAL_STREAM("internal error at start-up (an exception of unknown type)");
    return 1;
  }
  return 0;
}
