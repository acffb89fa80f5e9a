// The accuracy knob: a Simulator advanced by steps chosen from an error estimate, instead of a
// fixed Δt (docs/accuracy.md).
//
// Each step of size H is taken twice from the same start, once as one step of H and once as two
// steps of H/2 (step doubling, Simulator::Save / Restore); the two half steps are kept. For a
// scheme of order p the difference of the two estimates the error of the half steps,
//   err ≈ ‖y_{H/2,H/2} - y_H‖ / (2^p - 1),   p = 2 (Integrator::kMoreau2), 1 (kMoreau)
// in a norm scaled per body (L: the farthest extent of its colliders from its centre of mass):
//   ‖Δ‖ = max over bodies of max(|Δr_S| / L, |Δv_S| H / L, |Δω| H, |Δx_c| / L)
// where Δx_c is how far the orientation error moves a collider c of the body: its centre, plus
// for a cylinder, capsule or body of revolution its axis and for a box, ellipsoid or hull any
// turn, times its bounding radius (a turn about a sphere's centre or a cylinder's axis moves
// nothing: the spin phase of a top is left free, the face a die shows is not).
// Velocities count by the displacement they make over the step, as DAE codes scale the error of
// index-2 components by H: on a closed contact, the end velocity is held to the contact law at
// every step, and one step of H and two of H/2 differ in it by O(H) (the Tippe-Top sliding:
// |Δv_z| ≈ 2e-3 m/s² · H) although the velocity converges at second order over a run (its
// error at a fixed time falls 4x per halving of a fixed step). Scaled by 1/v_ref instead, that
// difference set the step (h ∝ TOL, first-order cost) and the achieved error was 100-1000x
// below TOL; scaled by H, the achieved errors of the Tippe-Top's touchdown and the
// rattleback's reversal lie within 10x of TOL from 1e-2 to 1e-6 (docs/accuracy.md).
// Two position errors both estimates share are added, as the difference cannot show them: the
// gap correction's lift and the depth at which a new contact (an impact) was found.
// The step is accepted if err ≤ TOL · H / (1 s): the error made per second of simulated time is
// at most TOL, so that the error at a fixed time grows with TOL, not with the number of steps.
// The next step is H · clamp(0.9 (TOL·H/err)^{1/p}, 0.2, 2), within [min, max]; a rejected
// step is tried again from the start with that H. A change of the contact state within a step
// (a contact closing or opening, stick ↔ slip, an impact) is first order whatever the scheme:
// its error does not fall as H^{p+1}, so the step shrinks until the change is localised to the
// smallest step, which is then accepted (counted in AdaptiveStatistics::forced_steps).
#ifndef NONSMOOTH_SIM_CORE_ADAPTIVE_STEPPER_H_
#define NONSMOOTH_SIM_CORE_ADAPTIVE_STEPPER_H_

#include <functional>
#include <limits>
#include <vector>

#include "nonsmooth_sim/core/simulator.h"

namespace nonsmooth_sim {

struct AccuracyOptions {
  /// TOL: the estimated error per second of simulated time, relative to the scales above, in
  /// [1e-9, 1]; 0 = fixed steps of SimulatorOptions::time_step
  double tolerance = 0.0;
  double min_time_step = 1e-6;  ///< [s], in [2e-7, 1e-2] (its halves ≥ 1e-7), ≤ max_time_step
  double max_time_step = 1e-2;  ///< [s], in [2e-7, 1e-2]
};
/// Throws std::invalid_argument naming the field and its allowed range.
void ValidateAccuracyOptions(const AccuracyOptions& options);

struct AdaptiveStatistics {
  long accepted_steps = 0;  ///< steps of H kept (each taken as two half steps)
  long rejected_steps = 0;  ///< steps tried and taken again smaller
  long forced_steps = 0;    ///< accepted at min_time_step with err above TOL·H
  long simulator_steps = 0; ///< Simulator::Step calls, rejected ones included (the cost)
  double smallest_step = std::numeric_limits<double>::infinity();  ///< [s], accepted H
  double largest_step = 0.0;                                        ///< [s]
  /// the largest and the summed err of accepted steps (as TOL is defined above)
  double max_error = 0.0;
  double error_sum = 0.0;
};

class AdaptiveStepper {
 public:
  /// `simulator` must outlive the stepper; its time step is changed by the stepper.
  AdaptiveStepper(Simulator* simulator, const AccuracyOptions& options);

  /// Advances the simulator to time t_end (its last step shortened to land on it); calls
  /// `accepted` after every accepted step with the statistics of its second half step and its
  /// H). Stops early if a step meets a non-finite value (the simulator's
  /// diverged()). Returns the statistics of the last step.
  StepStatistics AdvanceTo(double t_end,
                           const std::function<void(const StepStatistics&, double h)>& accepted);

  const AdaptiveStatistics& statistics() const { return statistics_; }
  const AccuracyOptions& options() const { return options_; }
  /// The step the next AdvanceTo starts with [s].
  double next_step() const { return next_step_; }

 private:
  // err of the state now against end_single_ (scaled as above), per the scheme's order
  double ErrorEstimate(double h) const;  // h: the step H
  void UpdateScales();

  Simulator* simulator_;
  AccuracyOptions options_;
  AdaptiveStatistics statistics_;
  double next_step_;
  Simulator::Checkpoint start_;
  std::vector<BodyState> end_single_;   // y_H
  std::vector<double> size_;            // per body: L [m]
  // per collider on a body: what of its pose an orientation error moves (ErrorEstimate)
  struct ColliderExtent {
    int body = 0;
    Eigen::Vector3d center = Eigen::Vector3d::Zero();  // in body axes [m]
    Eigen::Vector3d axis = Eigen::Vector3d::Zero();    // the symmetry axis (body axes), or 0
    double radius = 0.0;  // bounding radius [m]; 0: a sphere (only its centre moves)
    bool turns = false;   // no symmetry axis: every rotation moves its surface
  };
  std::vector<ColliderExtent> extents_;
  double smallest_size_ = 1.0;          // min L [m]: the scale of StepStatistics::gap_correction
};

}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_CORE_ADAPTIVE_STEPPER_H_
