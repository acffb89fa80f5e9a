// `simulate --contacts-csv`: one row per closed contact per sample. See contact_csv.h.
#include "contact_csv.h"

#include <cstdio>
#include <memory>

namespace nonsmooth_sim::simulate {

void ContactCsvRecorder::Record(double time, const Simulator& simulator) {
  const double dt = simulator.options().time_step;
  for (const ContactState& c : simulator.contacts()) {
    Row row;
    row.contact = ContactName(simulator.scene(), c);
    const Eigen::Vector3d& n = c.frame.normal;
    const Eigen::Vector3d& t1 = c.frame.tangent1;
    row.values = {time,
                  dt,
                  static_cast<double>(c.feature),
                  c.point.x(),
                  c.point.y(),
                  c.point.z(),
                  n.x(),
                  n.y(),
                  n.z(),
                  t1.x(),
                  t1.y(),
                  t1.z(),
                  c.gap,
                  c.percussion[0],
                  c.percussion[1],
                  c.percussion[2],
                  c.percussion[3],
                  c.rolling_percussion[0],
                  c.rolling_percussion[1]};
    rows_.push_back(std::move(row));
  }
}

bool ContactCsvRecorder::Write(const std::string& path) const {
  const std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "w"),
                                                              &std::fclose);
  if (!file) return false;
  std::fputs("t,dt,contact,feature,x,y,z,nx,ny,nz,t1x,t1y,t1z,gap,lambda_n,lambda_t1,lambda_t2,"
             "lambda_tau,lambda_r1,lambda_r2\n",
             file.get());
  for (const Row& row : rows_) {
    std::fprintf(file.get(), "%.15g,%.15g,%s", row.values[0], row.values[1], row.contact.c_str());
    for (int i = 2; i <= kValues; ++i) std::fprintf(file.get(), ",%.15g", row.values[i]);
    std::fputc('\n', file.get());
  }
  return std::ferror(file.get()) == 0;
}

}  // namespace nonsmooth_sim::simulate
