// The tangent frame of a contact, carried over from step to step.
//
// The percussions Λ_T1, Λ_T2 of one step warm-start the next (simulator.h), so the tangents of a
// contact that persists (a rolling or sliding contact whose normal turns slowly) must not jump:
// t1 is the previous step's t1 projected onto the new tangent plane, t1 ← (t1 - (t1·n)n)/|…|.
// A new contact takes the hint projected the same way (a plane's x axis: the ground gives world
// x̂, ŷ as the Tippe-Top always had), and if that is (nearly) parallel to n, the world axis least
// aligned with n.
#ifndef NONSMOOTH_SIM_CORE_CONTACT_CONTACT_FRAME_H_
#define NONSMOOTH_SIM_CORE_CONTACT_CONTACT_FRAME_H_

#include <Eigen/Core>

#include "nonsmooth_sim/core/contact/contact_jacobian.h"

namespace nonsmooth_sim {

/// A projected tangent shorter than this (|t - (t·n)n| for a unit t) is too close to the normal
/// to define a direction: a tangent that turned by more than ~84° in one step, or a hint along n.
inline constexpr double kMinProjectedTangent = 0.1;

/// Frame for the unit `normal`: t1 from `previous` (if non-null and not parallel to n), else from
/// `hint`, else the world axis least aligned with n; t2 = n × t1.
inline ContactFrame MakeContactFrame(const Eigen::Vector3d& normal,
                                     const Eigen::Vector3d* previous,
                                     const Eigen::Vector3d& hint) {
  ContactFrame frame;
  frame.normal = normal;
  auto project = [&normal](const Eigen::Vector3d& t) -> Eigen::Vector3d {
    return t - t.dot(normal) * normal;
  };
  // t1 and its length, which normalises it (one square root: normalized() would take another)
  Eigen::Vector3d t1 = Eigen::Vector3d::Zero();
  double length = 0.0;
  if (previous != nullptr) {
    t1 = project(*previous);
    length = t1.norm();
  }
  if (!(length > kMinProjectedTangent)) {
    t1 = project(hint);
    length = t1.norm();
  }
  if (!(length > kMinProjectedTangent)) {
    Eigen::Index axis = 0;
    normal.cwiseAbs().minCoeff(&axis);
    t1 = project(Eigen::Vector3d::Unit(axis));
    length = t1.norm();
  }
  frame.tangent1 = length > 0.0 ? Eigen::Vector3d(t1 / length) : t1;
  frame.tangent2 = normal.cross(frame.tangent1);
  return frame;
}

}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_CORE_CONTACT_CONTACT_FRAME_H_
