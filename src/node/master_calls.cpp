// One thread, one queue: master_calls.h.
#include "nonsmooth_sim/node/master_calls.h"

#include <utility>

namespace nonsmooth_sim::node {

MasterCalls::MasterCalls() : thread_([this] { Serve(); }) {}

MasterCalls::~MasterCalls() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

bool MasterCalls::Run(std::function<void()> call, std::chrono::milliseconds timeout) {
  std::packaged_task<void()> task(std::move(call));
  std::future<void> done = task.get_future();
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    queue_.push_back(std::move(task));
  }
  wake_.notify_all();
  if (done.wait_for(timeout) != std::future_status::ready) return false;
  done.get();  // rethrows what the call threw
  return true;
}

void MasterCalls::Serve() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    wake_.wait(lock, [this] { return stop_ || !queue_.empty(); });
    if (queue_.empty()) return;  // stop_, and every call made
    std::packaged_task<void()> task = std::move(queue_.front());
    queue_.pop_front();
    lock.unlock();
    task();  // an exception is kept in the task's future
    lock.lock();
  }
}

}  // namespace nonsmooth_sim::node
