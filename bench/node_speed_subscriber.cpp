// node_speed_subscriber: the subscriber of scripts/node-speed. Subscribes to /tf and
// /nonsmooth_sim/contacts with queues large enough that nothing is dropped (every message is
// deserialized, as in a real consumer), counts what arrives and prints the counts on shutdown
// (SIGINT): "received tf <n> contacts <m>". Not a test and not a Google Benchmark.
#include <ros/ros.h>
#include <tf2_msgs/TFMessage.h>

#include <atomic>
#include <cstdio>

#include "nonsmooth_sim/ContactInfoArray.h"

namespace {

// messages: 8 s at 1 kHz of sim time is 8000 per topic; a queue this large never drops
constexpr uint32_t kQueueSize = 1000000;

std::atomic<long> tf_count{0};
std::atomic<long> contacts_count{0};

void OnTf(const tf2_msgs::TFMessage::ConstPtr&) { ++tf_count; }
void OnContacts(const nonsmooth_sim::ContactInfoArray::ConstPtr&) { ++contacts_count; }

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "node_speed_subscriber");
  ros::NodeHandle nh;
  ros::Subscriber tf = nh.subscribe("/tf", kQueueSize, OnTf);
  ros::Subscriber contacts = nh.subscribe("/nonsmooth_sim/contacts", kQueueSize, OnContacts);
  // callbacks on a thread of their own, as a separate consumer process would
  ros::AsyncSpinner spinner(1);
  spinner.start();
  ros::waitForShutdown();
  std::printf("received tf %ld contacts %ld\n", tf_count.load(), contacts_count.load());
  return 0;
}
