// `simulate --contacts-csv FILE`: the closed contacts of every sampled step, one row per contact
// (long format: their number changes as contacts open and close), for any scene.
//
//   t, dt, contact, feature, x, y, z, nx, ny, nz, t1x, t1y, t1z, gap, lambda_n, lambda_t1,
//   lambda_t2, lambda_tau, lambda_r1, lambda_r2
//
// contact = "<collider A>/<collider B>" (ContactName), feature = the pair function's feature;
// (x, y, z) the contact point on B, n the normal from A to B and t1 the first tangent, world
// (t2 = n × t1); gap g(q_M) [m]; the
// percussions Λ on B over the step [N s; N m s for τ and the rolling pair], so that the mean
// force over the step is Λ/dt (dt: that step's Δt, the adaptive stepper's last with --accuracy).
// Components a contact does not model are 0.
#ifndef NONSMOOTH_SIM_SIMULATE_CONTACT_CSV_H_
#define NONSMOOTH_SIM_SIMULATE_CONTACT_CSV_H_

#include <array>
#include <string>
#include <vector>

#include "nonsmooth_sim/core/simulator.h"

namespace nonsmooth_sim::simulate {

class ContactCsvRecorder {
 public:
  /// One row per closed contact of the simulator's last step, at time t.
  void Record(double time, const Simulator& simulator);
  /// Writes header and rows (numbers with 15 significant digits); false if it cannot.
  bool Write(const std::string& path) const;

  static constexpr int kValues = 18;  ///< the numeric columns after `contact`
  struct Row {
    std::string contact;
    std::array<double, kValues + 1> values;  ///< t, then the columns after `contact`
  };
  const std::vector<Row>& rows() const { return rows_; }

 private:
  std::vector<Row> rows_;
};

}  // namespace nonsmooth_sim::simulate

#endif  // NONSMOOTH_SIM_SIMULATE_CONTACT_CSV_H_
