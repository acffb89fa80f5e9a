// node_speed_subscriber: the subscriber of scripts/dev/node-speed. Subscribes to /tf and
// /nonsmooth_sim/contacts with queues large enough that nothing is dropped (every message is
// deserialized, as in a real consumer), counts the samples (stamps, steps) that arrive and
// prints the counts on shutdown (SIGINT): "received tf <n> contacts <m>". Not a test and not a
// Google Benchmark.
#include <ros/ros.h>
#include <tf2_msgs/TFMessage.h>

#include <atomic>
#include <cstdio>

#include "nonsmooth_sim/ContactSteps.h"

namespace {

// messages: 8 s at 1 kHz of sim time is 8000 per topic; a queue this large never drops
constexpr uint32_t kQueueSize = 1000000;

std::atomic<long> tf_count{0};
std::atomic<long> contacts_count{0};

// counts samples, not messages: a /tf message carries several stamps (each stamp's transforms
// are consecutive), a ~contacts message several steps
void OnTf(const tf2_msgs::TFMessage::ConstPtr& m) {
  long stamps = 0;
  for (std::size_t i = 0; i < m->transforms.size(); ++i) {
    if (i == 0 || m->transforms[i].header.stamp != m->transforms[i - 1].header.stamp) ++stamps;
  }
  tf_count += stamps;
}
void OnContacts(const nonsmooth_sim::ContactSteps::ConstPtr& m) {
  contacts_count += static_cast<long>(m->steps.size());
}

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
