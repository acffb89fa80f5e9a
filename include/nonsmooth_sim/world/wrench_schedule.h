// The external wrenches of ~apply_body_wrench (and of a `simulate --schedule` file): each a force
// and torque on one body, constant over [start, end) of sim time, applied at a point fixed in the
// body. Before every step (or every interval the adaptive stepper advances) the schedule sets the
// core's external wrench of each body to the wrenches' part in [t, t + Δt]:
//
//   F_b = Σ_w φ_w F_w,   M_b = Σ_w φ_w (M_w + r_w × F_w),   φ_w = |[t, t+Δt] ∩ [start_w, end_w)| / Δt
//
// with the moment arm r_w = R(q_b) p_w from the centre of mass S to the point of application (p_w
// in body axes, turning with the body). The impulse over a step is thus exactly the wrench
// integrated over the requested interval: over the whole duration T, F·T.
#ifndef NONSMOOTH_SIM_WORLD_WRENCH_SCHEDULE_H_
#define NONSMOOTH_SIM_WORLD_WRENCH_SCHEDULE_H_

#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "nonsmooth_sim/core/simulator.h"

namespace nonsmooth_sim::world {

/// One scheduled wrench.
struct ExternalWrench {
  int body = 0;
  Eigen::Vector3d force = Eigen::Vector3d::Zero();          ///< world axes [N]
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();         ///< world axes [N m]
  Eigen::Vector3d point_in_body = Eigen::Vector3d::Zero();  ///< from S, body axes [m]
  double start = 0.0;                                       ///< [s] of sim time
  double end = 0.0;                                         ///< [s]; +inf: until cleared
};

class WrenchSchedule {
 public:
  /// |force| and |torque| of one wrench at most this [N], [N m].
  static constexpr double kMaxForce = 1e6;
  /// At most this many wrenches at once (a bound on the work per step).
  static constexpr std::size_t kMaxWrenches = 1000;

  /// Throws std::invalid_argument (and keeps the schedule) when kMaxWrenches are scheduled.
  void CheckRoom() const;
  /// Adds `wrench` (checked by the caller: World::ApplyWrench).
  void Add(const ExternalWrench& wrench);
  /// Drops the wrenches on `body`.
  void Clear(int body);
  /// Drops every wrench.
  void ClearAll();
  /// After bodies were removed: each wrench's body through the old → new map; those on a
  /// removed body (-1) are dropped.
  void Remap(const std::vector<int>& body_map);

  /// True when Apply must run before the next step: a wrench is scheduled, or the last Apply set
  /// a non-zero wrench that must be cleared.
  bool active() const { return active_; }
  const std::vector<ExternalWrench>& wrenches() const { return wrenches_; }

  /// Sets `sim`'s external wrenches for the next `interval` [s] (see the header comment) and
  /// drops the wrenches that end within it.
  void Apply(Simulator* sim, double interval);

 private:
  std::vector<ExternalWrench> wrenches_;
  bool active_ = false;
  std::vector<Eigen::Vector3d> force_, torque_;  ///< per body, reused
};

}  // namespace nonsmooth_sim::world

#endif  // NONSMOOTH_SIM_WORLD_WRENCH_SCHEDULE_H_
