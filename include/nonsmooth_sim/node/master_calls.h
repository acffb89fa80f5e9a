// Calls to the ROS master (parameters, advertising topics) made in order on a thread of their own,
// each waited for at most a timeout.
//
// roscpp's master calls block for as long as the master takes: a stopped or overloaded master
// would hold a service call (and the spawns and deletes queued behind it) for ever. Here the
// caller waits at most its timeout; a call that has not finished by then still runs, later, in
// the order it was queued, so that the master ends up as if each had been made in turn (a
// delete's parameter is removed after the spawn's was set). What a call uses it must own (capture
// by value), or outlive this object.
#ifndef NONSMOOTH_SIM_NODE_MASTER_CALLS_H_
#define NONSMOOTH_SIM_NODE_MASTER_CALLS_H_

#include <chrono>
#include <condition_variable>
#include <deque>
#include <functional>
#include <future>
#include <mutex>
#include <thread>

namespace nonsmooth_sim::node {

class MasterCalls {
 public:
  MasterCalls();
  /// Makes the calls still queued, then ends the thread (with the master stopped, it waits for it,
  /// as roscpp's own shutdown does).
  ~MasterCalls();
  MasterCalls(const MasterCalls&) = delete;
  MasterCalls& operator=(const MasterCalls&) = delete;

  /// Queues `call` behind the earlier ones and waits at most `timeout` for it. Returns true if it
  /// finished in time (an exception it threw is rethrown here), false if it is still queued or
  /// running.
  bool Run(std::function<void()> call, std::chrono::milliseconds timeout);

 private:
  void Serve();

  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<std::packaged_task<void()>> queue_;
  bool stop_ = false;
  std::thread thread_;  // last: started when the members above exist
};

}  // namespace nonsmooth_sim::node

#endif  // NONSMOOTH_SIM_NODE_MASTER_CALLS_H_
