// N Tippe-Tops in MuJoCo (Debian's libmujoco-dev 2.2.2, double precision). One free body per top
// with two sphere geoms offset along e3 (the big sphere at a1, the peg at a2), a ground plane.
//
// Contacts: condim 4 (normal, two tangents, torsion about the normal), friction "0.3 mu*R̄ 0":
// sliding mu = 0.3, torsional coefficient mu R̄ ≈ 8.84e-5 m (a length: torque limit = coefficient
// x normal force), no rolling resistance. MuJoCo couples the friction components in its cone:
//   elliptic  — (f1/mu)^2 + (f2/mu)^2 + (tau/(mu R̄))^2 <= f_n^2, i.e. the ellipsoid E_F of the paper;
//   pyramidal — the default: the convex hull of the edges f_n (n ± mu_i d_i), i.e.
//               |f1|/mu + |f2|/mu + |tau|/(mu R̄) <= f_n, also coupled (an octahedron).
// Both are soft constraints (MuJoCo's convex formulation, default solref 0.02 1 and solimp
// 0.9 0.95 0.001), Newton solver (default: 100 iterations, tolerance 1e-8), Euler integrator.
//
// Sizes: MuJoCo 2.2 preallocates its contact and constraint buffers (nconmax, default 100
// contacts; njmax, default 500 rows) and drops the contacts beyond them with a warning ("Pre-
// allocated contact buffer is full"): a top whose contact is dropped falls through the floor. So
// the model sizes them: nconmax = 2 n + 64 for independent tops (each sphere has at most one
// contact, with the ground), 4 n + 64 in the crowd (ground, walls and neighbours; measured: at
// most 78 contacts for 64 tops in 1 s), njmax = the rows of nconmax contacts (condim rows with the elliptic cone,
// 2 (condim - 1) with the pyramidal one). A run that still fills a buffer reports
// "buffer_overflow": true (and a line on stderr). The buffers are allocated once, by mj_makeData;
// MuJoCo 2.2 keeps dense njmax x njmax and njmax x nv arrays among them, so they dominate the
// peak RSS and grow with N^2.
// With --scene crowd the tops of CrowdStartOf() between the four wall planes of CrowdWalls().
//
// Settings (--setting): elliptic (the default), pyramidal, elliptic_pgs (the elliptic cone solved
// by PGS instead of Newton: the same convex problem, so the same physics up to the solvers'
// tolerances; the faster of the two for one top), or elliptic_condim3 (a check: elliptic cone
// without torsional friction, condim 3). Euler is MuJoCo's cheapest integrator; condim 4 is the
// smallest that has torsional friction (6 adds rolling resistance, which ours does not have).
#include <mujoco/mujoco.h>

#include <unistd.h>

#include <string>
#include <vector>

#include "tippe_top_scene.h"

namespace {

using namespace tippe_top;

std::string ModelXml(const Args& a, bool elliptic, int condim, const char* solver) {
  char buf[512];
  std::string xml = "<mujoco model=\"tippe_tops\">\n";
  std::snprintf(buf, sizeof buf,
                "  <option timestep=\"%.17g\" gravity=\"0 0 %.17g\" cone=\"%s\" integrator=\"Euler\" "
                "solver=\"%s\"/>\n",
                a.dt, -kGravity, elliptic ? "elliptic" : "pyramidal", solver);
  xml += buf;
  const int nconmax = (a.crowd() ? 4 : 2) * a.n + 64;
  const int rows = elliptic ? condim : 2 * (condim - 1);
  std::snprintf(buf, sizeof buf, "  <size nconmax=\"%d\" njmax=\"%d\"/>\n", nconmax, rows * nconmax);
  xml += buf;
  std::snprintf(buf, sizeof buf,
                "  <default><geom condim=\"%d\" friction=\"%.17g %.17g 0\"/></default>\n", condim,
                kMu, kTorsionalLength);
  xml += buf;
  // a plane collides as an infinite one (a half-space); its size is for rendering only
  xml += "  <worldbody>\n    <geom name=\"ground\" type=\"plane\" size=\"100 100 0.1\"/>\n";
  if (a.crowd()) {
    const std::vector<Wall> walls = CrowdWalls(a.n);
    for (size_t w = 0; w < walls.size(); ++w) {
      const Wall& wall = walls[w];
      // the plane's z axis is the wall's normal, its origin the point d n
      std::snprintf(buf, sizeof buf,
                    "    <geom name=\"wall%zu\" type=\"plane\" size=\"1 1 0.1\" pos=\"%.17g %.17g %.17g\" "
                    "zaxis=\"%.17g %.17g %.17g\"/>\n",
                    w, wall.d * wall.normal[0], wall.d * wall.normal[1], wall.d * wall.normal[2],
                    wall.normal[0], wall.normal[1], wall.normal[2]);
      xml += buf;
    }
  }
  for (int i = 0; i < a.n; ++i) {
    // the pose is set through qpos below; the body frame is the centre of mass S, z = e3
    std::snprintf(buf, sizeof buf,
                  "    <body name=\"top%d\">\n      <freejoint/>\n"
                  "      <inertial pos=\"0 0 0\" mass=\"%.17g\" diaginertia=\"%.17g %.17g %.17g\"/>\n"
                  "      <geom type=\"sphere\" size=\"%.17g\" pos=\"0 0 %.17g\"/>\n"
                  "      <geom type=\"sphere\" size=\"%.17g\" pos=\"0 0 %.17g\"/>\n    </body>\n",
                  i, kMass, kA, kA, kC, kR1, kA1, kR2, kA2);
    xml += buf;
  }
  xml += "  </worldbody>\n</mujoco>\n";
  return xml;
}

TopState StateOf(const mjModel* m, const mjData* d, int i) {
  const int j = m->body_jntadr[i + 1];  // body 0 is the world
  const mjtNum* q = d->qpos + m->jnt_qposadr[j];
  const mjtNum* v = d->qvel + m->jnt_dofadr[j];
  TopState s;
  for (int k = 0; k < 3; ++k) {
    s.pos[k] = q[k];
    s.vel[k] = v[k];
  }
  for (int k = 0; k < 4; ++k) s.quat[k] = q[3 + k];  // w, x, y, z
  mju_rotVecQuat(s.omega, v + 3, q + 3);              // free joint: omega in the body frame
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  const Args args = ParseArgs(argc, argv, {"elliptic", "pyramidal", "elliptic_condim3", "elliptic_pgs"});
  const bool elliptic = args.setting != "pyramidal";
  const int condim = args.setting == "elliptic_condim3" ? 3 : 4;
  const char* solver = args.setting == "elliptic_pgs" ? "PGS" : "Newton";

  // MuJoCo 2.2 loads MJCF from a file
  char path[] = "/tmp/mujoco_tops_XXXXXX";
  const int fd = mkstemp(path);
  const std::string xml = ModelXml(args, elliptic, condim, solver);
  if (fd < 0 || write(fd, xml.data(), xml.size()) != static_cast<ssize_t>(xml.size())) {
    std::fprintf(stderr, "mujoco_tops: cannot write %s\n", path);
    return 1;
  }
  close(fd);
  char error[1000] = "";
  mjModel* m = mj_loadXML(path, nullptr, error, sizeof error);
  unlink(path);
  if (!m) {
    std::fprintf(stderr, "mujoco_tops: %s\n", error);
    return 1;
  }
  mjData* d = mj_makeData(m);

  std::vector<TopState> initial;
  for (int i = 0; i < args.n; ++i) {
    const Start s = args.StartOf(i);
    const int j = m->body_jntadr[i + 1];
    mjtNum* q = d->qpos + m->jnt_qposadr[j];
    mjtNum* v = d->qvel + m->jnt_dofadr[j];
    for (int k = 0; k < 3; ++k) q[k] = s.pos[k];
    for (int k = 0; k < 4; ++k) q[3 + k] = s.quat[k];
    for (int k = 0; k < 3; ++k) v[k] = s.vel[k];  // free joint: linear velocity in the world
    v[3] = 0.0;  // spin about the body's e3
    v[4] = 0.0;
    v[5] = s.spin;
  }
  mj_forward(m, d);
  for (int i = 0; i < args.n; ++i) initial.push_back(StateOf(m, d, i));

  const long steps = StepsOf(args);
  std::vector<Monitor> monitors = MonitorsFor(initial);
  PairMonitor pairs(args.n, CrowdWalls(args.n));
  std::vector<TopState> state(args.n);
  int max_contacts = 0;  // the most contacts MuJoCo found in one step (to check nconmax)
  const double c0 = CpuSeconds();
  for (long k = 1; k <= steps; ++k) {
    mj_step(m, d);
    const double t = k * args.dt;
    for (int i = 0; i < args.n; ++i) {
      state[i] = StateOf(m, d, i);
      monitors[i].Update(t, state[i]);
    }
    if (args.crowd()) pairs.Update(state);
    if (d->ncon > max_contacts) max_contacts = d->ncon;
  }
  const double cpu = CpuSeconds() - c0;
  // a full buffer drops contacts: the run is not valid
  const bool overflow = d->warning[mjWARN_CONTACTFULL].number > 0 || d->warning[mjWARN_CNSTRFULL].number > 0;
  if (overflow)
    std::fprintf(stderr, "mujoco_tops: contact or constraint buffer full (nconmax %d, njmax %d)\n",
                 m->nconmax, m->njmax);

  std::vector<TopState> final_state;
  for (int i = 0; i < args.n; ++i) final_state.push_back(StateOf(m, d, i));
  const std::string settings =
      std::string(elliptic ? "elliptic cone" : "pyramidal cone") +
      (condim == 4 ? ", condim 4, friction 0.3 / torsional mu*Rbar / rolling 0"
                   : ", condim 3 (no torsional friction), friction 0.3") +
      ", " + solver + ", Euler, default solref/solimp";
  std::string extra = "\"max_contacts\": " + std::to_string(max_contacts) + ", \"nconmax\": " +
                      std::to_string(m->nconmax) + ", \"buffer_overflow\": " + (overflow ? "true" : "false");
  if (args.crowd()) extra += ", " + pairs.Json();
  PrintResult("mujoco", mj_versionString(), settings, args, steps, cpu, monitors, initial, final_state, extra);
  mj_deleteData(d);
  mj_deleteModel(m);
  return 0;
}
