// A progress bar on stderr for runs longer than a second; silent when stderr is not a terminal.
#ifndef NONSMOOTH_SIM_SIMULATE_PROGRESS_H_
#define NONSMOOTH_SIM_SIMULATE_PROGRESS_H_

#include <chrono>

namespace nonsmooth_sim::simulate {

class ProgressBar {
 public:
  /// `enabled` false (e.g. --quiet) keeps it silent; it is also silent if stderr is no terminal.
  ProgressBar(long total_steps, double duration, bool enabled);
  /// Cheap to call every step: looks at the clock every kCheckInterval steps only.
  void Update(long step) {
    if (active_ && step % kCheckInterval == 0) Draw(step);
  }
  /// Clears the bar if it was drawn.
  void Finish();

 private:
  static constexpr long kCheckInterval = 4096;
  void Draw(long step);
  long total_steps_;
  double duration_;
  bool active_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace nonsmooth_sim::simulate

#endif  // NONSMOOTH_SIM_SIMULATE_PROGRESS_H_
