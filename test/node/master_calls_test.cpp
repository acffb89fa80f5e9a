// MasterCalls (master_calls.h): calls run in the order queued, on one thread; the caller waits at
// most its timeout, and a call that is late still runs, in order; an exception reaches the caller
// that waited for it; the destructor makes the calls still queued.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

#include "nonsmooth_sim/node/master_calls.h"

namespace nonsmooth_sim::node {
namespace {

using std::chrono::milliseconds;

// A gate the test opens: a call that waits on it stands for a master that does not answer.
class Gate {
 public:
  void Wait() {
    std::unique_lock<std::mutex> lock(mutex_);
    cv_.wait(lock, [this] { return open_; });
  }
  void Open() {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      open_ = true;
    }
    cv_.notify_all();
  }

 private:
  std::mutex mutex_;
  std::condition_variable cv_;
  bool open_ = false;
};

TEST(MasterCalls, ALateCallReturnsFalseAndStillRunsInOrder) {
  auto gate = std::make_shared<Gate>();
  auto order = std::make_shared<std::vector<int>>();  // written by the calls' thread only
  auto done = std::make_shared<std::atomic<int>>(0);
  {
    MasterCalls calls;
    EXPECT_TRUE(calls.Run([order, done] { order->push_back(1); ++*done; }, milliseconds(5000)));
    const auto start = std::chrono::steady_clock::now();
    EXPECT_FALSE(calls.Run([gate, order, done] { gate->Wait(); order->push_back(2); ++*done; },
                           milliseconds(50)));
    EXPECT_GE(std::chrono::steady_clock::now() - start, milliseconds(50));
    // queued behind the late one: late too, though it would take no time
    EXPECT_FALSE(calls.Run([order, done] { order->push_back(3); ++*done; }, milliseconds(50)));
    EXPECT_EQ(done->load(), 1);
    gate->Open();
    EXPECT_TRUE(calls.Run([order, done] { order->push_back(4); ++*done; }, milliseconds(5000)));
    EXPECT_EQ(*order, (std::vector<int>{1, 2, 3, 4}));
  }
}

TEST(MasterCalls, AnExceptionReachesTheCallerThatWaited) {
  MasterCalls calls;
  EXPECT_THROW(calls.Run([] { throw std::invalid_argument("no"); }, milliseconds(5000)),
               std::invalid_argument);
  EXPECT_TRUE(calls.Run([] {}, milliseconds(5000))) << "the thread survives a throwing call";
}

TEST(MasterCalls, TheDestructorMakesTheQueuedCalls) {
  auto gate = std::make_shared<Gate>();
  auto done = std::make_shared<std::atomic<int>>(0);
  {
    MasterCalls calls;
    EXPECT_FALSE(calls.Run([gate, done] { gate->Wait(); ++*done; }, milliseconds(10)));
    EXPECT_FALSE(calls.Run([done] { ++*done; }, milliseconds(10)));
    gate->Open();
  }
  EXPECT_EQ(done->load(), 2);
}

}  // namespace
}  // namespace nonsmooth_sim::node
