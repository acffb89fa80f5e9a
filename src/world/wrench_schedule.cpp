// The wrench schedule. See wrench_schedule.h.
#include "nonsmooth_sim/world/wrench_schedule.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace nonsmooth_sim::world {

void WrenchSchedule::CheckRoom() const {
  if (wrenches_.size() >= kMaxWrenches) {
    throw std::invalid_argument("already " + std::to_string(kMaxWrenches) +
                                " wrenches active (the most at once): clear some with "
                                "~clear_body_wrenches");
  }
}

void WrenchSchedule::Add(const ExternalWrench& wrench) {
  wrenches_.push_back(wrench);
  active_ = true;
}

void WrenchSchedule::Clear(int body) {
  std::vector<ExternalWrench> kept;
  for (const ExternalWrench& w : wrenches_) {
    if (w.body != body) kept.push_back(w);
  }
  wrenches_.swap(kept);
}

void WrenchSchedule::ClearAll() {
  wrenches_.clear();
  active_ = false;
}

void WrenchSchedule::Remap(const std::vector<int>& body_map) {
  std::vector<ExternalWrench> kept;
  for (ExternalWrench w : wrenches_) {
    w.body = body_map[static_cast<std::size_t>(w.body)];
    if (w.body >= 0) kept.push_back(w);
  }
  wrenches_.swap(kept);
}

void WrenchSchedule::Apply(Simulator* sim, double interval) {
  // each wrench weighted by the part φ of [t, t + Δt] it covers (Δt: the step, or with an
  // accuracy the interval the adaptive stepper advances): the impulse over it is exactly the
  // wrench integrated over the requested interval
  const double t = sim->time();
  const double dt = interval;
  const std::size_t bodies = sim->scene().bodies.size();
  force_.assign(bodies, Eigen::Vector3d::Zero());
  torque_.assign(bodies, Eigen::Vector3d::Zero());
  std::size_t kept = 0;
  for (const ExternalWrench& w : wrenches_) {
    const double overlap = std::min(t + dt, w.end) - std::max(t, w.start);
    if (overlap > 0.0) {
      const double fraction = std::min(1.0, overlap / dt);
      const BodyState& s = sim->state()[static_cast<std::size_t>(w.body)];
      const Eigen::Vector3d arm = s.orientation * w.point_in_body;  // r = R(q) p
      force_[static_cast<std::size_t>(w.body)] += fraction * w.force;
      torque_[static_cast<std::size_t>(w.body)] += fraction * (w.torque + arm.cross(w.force));
    }
    if (w.end > t + dt) wrenches_[kept++] = w;  // still to come
  }
  wrenches_.resize(kept);
  bool any = false;  // a non-zero wrench in this step: the next one must look again (to clear it)
  for (std::size_t b = 0; b < bodies; ++b) {
    const auto current = sim->ExternalWrench(static_cast<int>(b));
    if (current.first != force_[b] || current.second != torque_[b]) {
      sim->SetExternalWrench(static_cast<int>(b), force_[b], torque_[b]);
    }
    any = any || !force_[b].isZero(0.0) || !torque_[b].isZero(0.0);
  }
  active_ = any || !wrenches_.empty();
}

}  // namespace nonsmooth_sim::world
