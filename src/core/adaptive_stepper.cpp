// Step doubling with error control, see adaptive_stepper.h.
#include "nonsmooth_sim/core/adaptive_stepper.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace nonsmooth_sim {
namespace {

constexpr double kMinTimeStep = 1e-7;  // [s], as SimulatorOptions::time_step
constexpr double kMaxTimeStep = 1e-2;
constexpr double kSmallestStep = 2.0 * kMinTimeStep;  // H: its halves are valid time steps
constexpr double kSafety = 0.9;         // the next step aims at 0.9 of the allowed error
constexpr double kMinFactor = 0.2;      // a step shrinks by at most 5x, grows by at most 2x
constexpr double kMaxFactor = 2.0;

void RequireIn(const char* field, double value, double low, double high) {
  if (!(value >= low && value <= high)) {
    std::ostringstream s;
    s << "AccuracyOptions." << field << " = " << value << ": must be in [" << low << ", " << high
      << "]";
    throw std::invalid_argument(s.str());
  }
}

}  // namespace

void ValidateAccuracyOptions(const AccuracyOptions& options) {
  if (options.tolerance != 0.0) RequireIn("tolerance", options.tolerance, 1e-9, 1.0);
  RequireIn("min_time_step", options.min_time_step, kSmallestStep, kMaxTimeStep);
  RequireIn("max_time_step", options.max_time_step, kSmallestStep, kMaxTimeStep);
  if (options.min_time_step > options.max_time_step) {
    std::ostringstream s;
    s << "AccuracyOptions.min_time_step = " << options.min_time_step
      << " s: must not exceed max_time_step = " << options.max_time_step << " s";
    throw std::invalid_argument(s.str());
  }
}

AdaptiveStepper::AdaptiveStepper(Simulator* simulator, const AccuracyOptions& options)
    : simulator_(simulator), options_(options) {
  ValidateAccuracyOptions(options_);
  if (options_.tolerance <= 0.0) {
    throw std::invalid_argument("AdaptiveStepper: AccuracyOptions.tolerance must be > 0");
  }
  next_step_ = std::clamp(simulator_->options().time_step, options_.min_time_step,
                          options_.max_time_step);
  // the contact solver's tolerance is a noise floor of the estimate: at most TOL/100
  SimulatorOptions simulator_options = simulator_->options();
  simulator_options.solver.tolerance_rel =
      std::min(simulator_options.solver.tolerance_rel, 0.01 * options_.tolerance);
  simulator_->SetOptions(simulator_options);
  UpdateScales();
}

void AdaptiveStepper::UpdateScales() {
  // L per body: the farthest extent of its colliders from S (at least 1 mm)
  const Scene& scene = simulator_->scene();
  size_.assign(scene.bodies.size(), 1e-3);
  extents_.clear();
  for (const Collider& c : scene.colliders) {
    if (c.body < 0) continue;
    double& size = size_[static_cast<std::size_t>(c.body)];
    size = std::max(size, c.pose.translation().norm() + BoundingRadius(c.shape));
    ColliderExtent e;
    e.body = c.body;
    e.center = c.pose.translation();
    const ShapeType type = c.shape.type;
    if (type != ShapeType::kSphere) {
      e.radius = BoundingRadius(c.shape);
      if (type == ShapeType::kCylinder || type == ShapeType::kCapsule ||
          type == ShapeType::kRevolution) {
        e.axis = c.pose.linear().col(2);  // a turn about its own axis moves nothing
      } else {
        e.turns = true;
      }
    }
    extents_.push_back(e);
  }
  smallest_size_ = size_.empty() ? 1.0 : *std::min_element(size_.begin(), size_.end());
}

double AdaptiveStepper::ErrorEstimate(double h) const {
  const std::vector<BodyState>& now = simulator_->state();
  double worst = 0.0;
  for (std::size_t b = 0; b < now.size(); ++b) {
    const BodyState& x = now[b];
    const BodyState& y = end_single_[b];
    const double size = size_[b];
    // velocities as the displacement they make over the step (header: index-2 components)
    worst = std::max({worst, (x.position - y.position).norm() / size,
                      (x.linear_velocity - y.linear_velocity).norm() * h / size,
                      (x.angular_velocity - y.angular_velocity).norm() * h});
  }
  // the orientation by what it moves of each collider's surface: a sphere's centre, a cylinder's,
  // capsule's or body of revolution's axis, every turn of a box, an ellipsoid or a hull (the spin
  // of a top about its axis of symmetry moves nothing and is left free; a spinning die's is not)
  for (const ColliderExtent& e : extents_) {
    const BodyState& x = now[static_cast<std::size_t>(e.body)];
    const BodyState& y = end_single_[static_cast<std::size_t>(e.body)];
    double moved = (x.orientation * e.center - y.orientation * e.center).norm();
    if (e.turns) {
      moved += e.radius * x.orientation.angularDistance(y.orientation);
    } else if (e.radius > 0.0) {
      moved += e.radius * (x.orientation * e.axis - y.orientation * e.axis).norm();
    }
    worst = std::max(worst, moved / size_[static_cast<std::size_t>(e.body)]);
  }
  // Richardson: the half steps' error is the difference over 2^p - 1
  const bool second_order = simulator_->options().integrator == Integrator::kMoreau2;
  return worst / (second_order ? 3.0 : 1.0);
}

StepStatistics AdaptiveStepper::AdvanceTo(
    double t_end, const std::function<void(const StepStatistics&, double h)>& accepted) {
  StepStatistics stats;
  stats.state_finite = !simulator_->diverged();
  if (simulator_->scene().bodies.size() != size_.size()) UpdateScales();  // the world changed
  const double order = simulator_->options().integrator == Integrator::kMoreau2 ? 2.0 : 1.0;
  // a remainder below the smallest step is absorbed into the last step
  while (!simulator_->diverged() && t_end - simulator_->time() > 0.5 * kSmallestStep) {
    const double remaining = t_end - simulator_->time();
    double h = std::min(next_step_, remaining);
    // no sliver after it: the rest in one step, or in two halves
    if (remaining - h < options_.min_time_step) {
      h = h < remaining && remaining >= 2.0 * options_.min_time_step ? 0.5 * remaining : remaining;
    }
    h = std::clamp(h, kSmallestStep, kMaxTimeStep);
    // the smallest step allowed, or the rest up to t_end below two of them: accepted whatever
    const bool smallest =
        h <= options_.min_time_step * (1.0 + 1e-12) || remaining <= 2.0 * options_.min_time_step;
    // shortened to land on t_end: its error says nothing about the natural step
    const bool shortened = h < next_step_;
    simulator_->Save(&start_);
    // y_H
    simulator_->SetTimeStep(h);
    simulator_->Step(&stats);
    ++statistics_.simulator_steps;
    if (!stats.state_finite) {
      // diverged in one step of H: try the half steps from the start (they may not)
      simulator_->Restore(start_);
    } else {
      end_single_ = simulator_->state();
      simulator_->Restore(start_);
    }
    // y_{H/2,H/2}
    simulator_->SetTimeStep(0.5 * h);
    simulator_->Step(&stats);
    double lift = std::max(stats.gap_correction, stats.new_contact_depth);
    if (stats.state_finite) simulator_->Step(&stats);
    lift = std::max({lift, stats.gap_correction, stats.new_contact_depth});
    statistics_.simulator_steps += 2;
    if (!stats.state_finite) return stats;  // diverged: the simulator stays stopped
    const bool single_finite = end_single_.size() == simulator_->state().size();
    // position errors the kept steps made that both estimates share, so that their difference
    // does not show them: the gap correction's lift, and the depth at which a new contact (an
    // impact) was found, a part of a step late (StepStatistics::new_contact_depth)
    const double error = single_finite ? std::max(ErrorEstimate(h), lift / smallest_size_)
                                       : std::numeric_limits<double>::infinity();
    const double allowed = options_.tolerance * h;  // TOL per second of simulated time
    const double ratio = error / allowed;
    double factor = ratio > 0.0 ? kSafety * std::pow(ratio, -1.0 / order) : kMaxFactor;
    factor = std::clamp(factor, kMinFactor, kMaxFactor);
    if (ratio <= 1.0 || smallest) {
      if (ratio > 1.0) ++statistics_.forced_steps;
      ++statistics_.accepted_steps;
      statistics_.smallest_step = std::min(statistics_.smallest_step, h);
      statistics_.largest_step = std::max(statistics_.largest_step, h);
      statistics_.max_error = std::max(statistics_.max_error, error);
      statistics_.error_sum += error;
      if (!shortened || factor < 1.0) {
        next_step_ = std::clamp(h * factor, options_.min_time_step, options_.max_time_step);
      }
      if (accepted) accepted(stats, h);
      continue;
    }
    // rejected: back to the start, smaller
    ++statistics_.rejected_steps;
    simulator_->Restore(start_);
    next_step_ = std::clamp(h * factor, options_.min_time_step, options_.max_time_step);
  }
  return stats;
}

}  // namespace nonsmooth_sim
