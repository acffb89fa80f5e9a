// The Tippe-Top scene shared by the peer-engine programs (ode_tops.cpp, mujoco_tops.cpp,
// bullet_tops.cpp): constants, starts of N tops, the observables and the output line.
// No engine headers here: each program converts its engine's state into a TopState.
//
// Constants: those of urdf/tippe_top.urdf (the reference Tippe-Top of Leine & Glocker 2003, as in
// the paper of Moeller, Leine, Glocker 2009) and the start of config/tippe_top.yaml. Keep them in
// step with those two files; bench/peers/multi_top_scene.py writes our N-top scene from the
// same numbers and the same StartOf() rule.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <string>
#include <utility>
#include <vector>

#include <sys/resource.h>

namespace tippe_top {

// --- urdf/tippe_top.urdf ---------------------------------------------------------------------
constexpr double kPi = 3.14159265358979323846;
constexpr double kMass = 6e-3;          // <mass value="6e-3"/>                       [kg]
constexpr double kA = 8e-7;             // ixx = iyy about the centre of mass S       [kg m^2]
constexpr double kC = 7e-7;             // izz (symmetry axis e3)                     [kg m^2]
constexpr double kR1 = 0.015;           // big sphere radius                          [m]
constexpr double kA1 = 0.003;           // S -> centre of the big sphere along +e3    [m]
constexpr double kR2 = 0.005;           // peg sphere radius                          [m]
constexpr double kA2 = 0.016;           // S -> centre of the peg sphere along +e3    [m]
constexpr double kMu = 0.3;             // <ode><mu>0.3</mu>, also torsional/coefficient
constexpr double kPatchRadius = 5e-4;   // torsional/patch_radius: contact-disc radius R [m]
// average friction radius of a Hertz contact, R̄ = 3 pi R / 16 (paper, eq. (50))          [m]
constexpr double kRbar = 3.0 * kPi * kPatchRadius / 16.0;
// the largest drilling torque is mu R̄ lambda_N: engines that take a torsional coefficient as a
// length (torque limit = coefficient x normal force) get mu R̄ ≈ 8.84e-5 m
constexpr double kTorsionalLength = kMu * kRbar;
constexpr double kGravity = 9.81;       // [m/s^2], along -z; the ground is z = 0

// --- config/tippe_top.yaml ------------------------------------------------------------------
constexpr double kTheta0 = 0.1;         // e3 tilted by 0.1 rad about the world x axis
constexpr double kSpin0 = 180.0;        // about the tilted e3 [rad/s]; centre of mass at rest

// --- the run -------------------------------------------------------------------------------
constexpr double kDt = 1e-4;
constexpr double kDuration = 8.0;
// "inverts": the reference (shared tippe-top.md) has the peg touch down near 140 deg and the top
// then spin on its peg near theta = pi; we call a top inverted once theta > 150 deg. The
// inversion time is reported as in `simulate` (first theta > 2.4 rad) next to the peg
// touchdown (first time the peg sphere's lowest point reaches the floor, z <= 0).
constexpr double kInvertedTheta = 150.0 * kPi / 180.0;
constexpr double kTheta24 = 2.4;
// N tops stand on a square grid this far apart: a top wanders up to about 1.4 m from its start in
// 8 s (measured: MuJoCo, whose soft friction lets it slide longest; ODE and Bullet about 1.2 m),
// so two tops cannot meet while each stays within kSpacing / 2 - R1 of its start; the monitor
// records the largest excursion to show that they did
constexpr double kSpacing = 5.0;

// --- the crowd: n tops close together in a walled square arena (--scene crowd) ---------------
// The tops start on a square grid kCrowdSpacing apart (big spheres 15 mm apart), centred on the
// origin, with the tilt, tilt direction and spin of StartOf() and a horizontal velocity of
// 0.1 .. 0.3 m/s in a varied direction, so that they hit each other and the walls. The arena is
// the square |x|, |y| <= CrowdHalfWidth(n) = columns * kCrowdSpacing / 2, bounded by four
// vertical planes (half-spaces: the wall's solid side is outside), as are the ground z = 0.
constexpr double kCrowdSpacing = 0.045;
// two tops "touch" (the pair monitor, the same rule in every engine and in
// bench/peers/crowd_contacts.py for ours) when a sphere of one is within this gap of a sphere of
// the other; a top touches a wall when a sphere is within it of the wall's plane
constexpr double kTouchGap = 1e-5;

// Start of top i of n (n = 1: exactly config/tippe_top.yaml). Top 0 is always the reference
// start; the others vary tilt (0.05 .. 0.2 rad), tilt direction and spin (150 .. 210 rad/s,
// either sense), so that they do not move in lockstep.
struct Start {
  double theta0, azimuth, spin;  // tilt, direction of the tilt axis in the floor, spin about e3
  double pos[3];                 // centre of mass
  double quat[4];                // w, x, y, z: body (S, e3 = z) to world
  double omega[3];               // world frame (spin * e3)
  double vel[3];                 // of the centre of mass, world frame (0 except in the crowd)
};

inline Start StartOf(int i, int n) {
  Start s{};
  if (i == 0) {
    s.theta0 = kTheta0;
    s.azimuth = 0.0;
    s.spin = kSpin0;
  } else {
    s.theta0 = 0.05 + 0.05 * (i % 4);
    s.azimuth = 2.399963229728653 * i;  // golden angle
    s.spin = (150.0 + 10.0 * (i % 7)) * ((i / 7) % 2 == 0 ? 1.0 : -1.0);
  }
  const int columns = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n))));  // ColumnsOf
  s.pos[0] = kSpacing * (i % columns);
  s.pos[1] = kSpacing * (i / columns);
  s.pos[2] = kR1 - kA1 * std::cos(s.theta0);  // big sphere just touching
  // rotation by theta0 about the horizontal axis (cos azimuth, sin azimuth, 0)
  const double h = 0.5 * s.theta0;
  s.quat[0] = std::cos(h);
  s.quat[1] = std::sin(h) * std::cos(s.azimuth);
  s.quat[2] = std::sin(h) * std::sin(s.azimuth);
  s.quat[3] = 0.0;
  // e3 in the world = third column of R(q)
  const double w = s.quat[0], x = s.quat[1], y = s.quat[2], z = s.quat[3];
  const double e3[3] = {2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)};
  for (int k = 0; k < 3; ++k) s.omega[k] = s.spin * e3[k];
  return s;
}

inline int ColumnsOf(int n) { return static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n)))); }

inline double CrowdHalfWidth(int n) { return 0.5 * kCrowdSpacing * ColumnsOf(n); }

// Start of top i of the crowd of n: StartOf()'s tilt, direction and spin, on the crowd's grid,
// moving at 0.1 + 0.1 (i % 3) m/s in the direction 1.3 + golden angle * i (not the tilt's).
inline Start CrowdStartOf(int i, int n) {
  Start s = StartOf(i, n);
  const int columns = ColumnsOf(n);
  s.pos[0] = kCrowdSpacing * ((i % columns) - 0.5 * (columns - 1));
  s.pos[1] = kCrowdSpacing * ((i / columns) - 0.5 * (columns - 1));
  const double speed = 0.1 + 0.1 * (i % 3);
  const double heading = 1.3 + 2.399963229728653 * i;
  s.vel[0] = speed * std::cos(heading);
  s.vel[1] = speed * std::sin(heading);
  s.vel[2] = 0.0;
  return s;
}

// The walls of the crowd's arena: planes n . x = d with the normal n pointing into the arena
// (the free side), d = -CrowdHalfWidth(n); the ground is z = 0 as in every scene.
struct Wall {
  double normal[3];
  double d;
};
inline std::vector<Wall> CrowdWalls(int n) {
  const double l = CrowdHalfWidth(n);
  return {{{1, 0, 0}, -l}, {{-1, 0, 0}, -l}, {{0, 1, 0}, -l}, {{0, -1, 0}, -l}};
}

// The state of one top as every engine can give it.
struct TopState {
  double pos[3];    // centre of mass S, world
  double quat[4];   // w, x, y, z
  double vel[3];    // of S, world
  double omega[3];  // world
};

// theta: angle between e3 and the vertical (cos theta = R(q)_zz)
inline double Theta(const TopState& s) {
  const double x = s.quat[1], y = s.quat[2], n2 = s.quat[0] * s.quat[0] + x * x + y * y +
                                                   s.quat[3] * s.quat[3];
  double c = 1.0 - 2.0 * (x * x + y * y) / n2;
  c = c > 1.0 ? 1.0 : (c < -1.0 ? -1.0 : c);
  return std::acos(c);
}

// E = 1/2 m |v|^2 + 1/2 omega^T Theta_S omega + m g z_S (as in tippe-top.md)
inline double Energy(const TopState& s) {
  const double w = s.quat[0], x = s.quat[1], y = s.quat[2], z = s.quat[3];
  const double n2 = w * w + x * x + y * y + z * z;
  // R(q) / n2 columns; omega in the body frame = R^T omega
  const double r[3][3] = {{1 - 2 * (y * y + z * z) / n2, 2 * (x * y - w * z) / n2, 2 * (x * z + w * y) / n2},
                          {2 * (x * y + w * z) / n2, 1 - 2 * (x * x + z * z) / n2, 2 * (y * z - w * x) / n2},
                          {2 * (x * z - w * y) / n2, 2 * (y * z + w * x) / n2, 1 - 2 * (x * x + y * y) / n2}};
  double wb[3];
  for (int k = 0; k < 3; ++k) wb[k] = r[0][k] * s.omega[0] + r[1][k] * s.omega[1] + r[2][k] * s.omega[2];
  const double v2 = s.vel[0] * s.vel[0] + s.vel[1] * s.vel[1] + s.vel[2] * s.vel[2];
  return 0.5 * kMass * v2 + 0.5 * (kA * (wb[0] * wb[0] + wb[1] * wb[1]) + kC * wb[2] * wb[2]) +
         kMass * kGravity * s.pos[2];
}

// Lowest point of the peg sphere: z_S + a2 cos theta - R2
inline double PegGap(const TopState& s) {
  const double x = s.quat[1], y = s.quat[2];
  return s.pos[2] + kA2 * (1.0 - 2.0 * (x * x + y * y)) - kR2;
}

// Per-top event monitor, updated every step inside the timed loop (as simulate's monitors are).
struct Monitor {
  double x0 = 0.0, y0 = 0.0;     // start of the centre of mass
  double excursion = 0.0;        // largest horizontal distance of the centre from its start
  double theta_max = 0.0;
  double t_theta_24 = -1.0;      // first theta > 2.4 rad, -1 = never
  double t_inverted = -1.0;      // first theta > 150 deg
  double t_peg_touchdown = -1.0; // first peg gap <= 0
  void Update(double t, const TopState& s) {
    const double th = Theta(s);
    if (th > theta_max) theta_max = th;
    if (t_theta_24 < 0.0 && th > kTheta24) t_theta_24 = t;
    if (t_inverted < 0.0 && th > kInvertedTheta) t_inverted = t;
    if (t_peg_touchdown < 0.0 && PegGap(s) <= 0.0) t_peg_touchdown = t;
    const double dx = s.pos[0] - x0, dy = s.pos[1] - y0, d2 = dx * dx + dy * dy;
    if (d2 > excursion * excursion) excursion = std::sqrt(d2);
  }
};

// The crowd's pair monitor, updated every step inside the timed loop: which pairs of tops touch
// (a sphere of one within kTouchGap of a sphere of the other) and which tops touch a wall, by a
// sort-and-sweep along x (a top reaches at most a2 + R2 = 21 mm from its centre of mass): about
// 2 us per step for the crowd of 64 (0.03 us per body-step; measured on its own, 2026-12-02),
// 0.3-1 % of the peers' step there.
class PairMonitor {
 public:
  PairMonitor(int n, std::vector<Wall> walls)
      : n_(n), walls_(std::move(walls)), touched_(static_cast<size_t>(n) * n, 0),
        wall_previous_(static_cast<size_t>(n) * walls_.size(), 0), order_(n), x_(n) {
    for (int i = 0; i < n; ++i) order_[i] = i;
  }

  void Update(const std::vector<TopState>& tops) {
    // centres of the two spheres of every top: S + a e3
    centres_.resize(tops.size());
    for (size_t i = 0; i < tops.size(); ++i) {
      const TopState& s = tops[i];
      const double w = s.quat[0], x = s.quat[1], y = s.quat[2], z = s.quat[3];
      const double n2 = w * w + x * x + y * y + z * z;
      const double e3[3] = {2 * (x * z + w * y) / n2, 2 * (y * z - w * x) / n2, 1 - 2 * (x * x + y * y) / n2};
      for (int k = 0; k < 3; ++k) {
        centres_[i].big[k] = s.pos[k] + kA1 * e3[k];
        centres_[i].peg[k] = s.pos[k] + kA2 * e3[k];
      }
      x_[i] = s.pos[0];
      const double reach = std::fabs(s.pos[0]) > std::fabs(s.pos[1]) ? std::fabs(s.pos[0]) : std::fabs(s.pos[1]);
      if (reach > max_coordinate) max_coordinate = reach;
    }
    // insertion sort by x: the order changes little from one step to the next
    for (int a = 1; a < n_; ++a) {
      const int v = order_[a];
      int b = a - 1;
      while (b >= 0 && x_[order_[b]] > x_[v]) {
        order_[b + 1] = order_[b];
        --b;
      }
      order_[b + 1] = v;
    }
    constexpr double kReach = 2.0 * (kA2 + kR2) + kTouchGap;
    current_.clear();
    for (int a = 0; a < n_; ++a) {
      const int i = order_[a];
      for (int b = a + 1; b < n_ && x_[order_[b]] - x_[i] <= kReach; ++b) {
        const int j = order_[b];
        const double dx = tops[i].pos[0] - tops[j].pos[0], dy = tops[i].pos[1] - tops[j].pos[1],
                     dz = tops[i].pos[2] - tops[j].pos[2];
        if (dx * dx + dy * dy + dz * dz > kReach * kReach) continue;
        if (Touch(centres_[i], centres_[j])) current_.push_back(i < j ? i * n_ + j : j * n_ + i);
      }
    }
    std::sort(current_.begin(), current_.end());
    if (!current_.empty()) ++touch_steps;
    pair_touch_steps += static_cast<long>(current_.size());
    if (static_cast<long>(current_.size()) > max_touching_pairs) max_touching_pairs = static_cast<long>(current_.size());
    for (long key : current_) {
      if (!std::binary_search(previous_.begin(), previous_.end(), key)) ++pair_onsets;
      if (!touched_[key]) {
        touched_[key] = 1;
        ++pairs_touched;
      }
    }
    previous_.swap(current_);
    // walls
    bool any_wall = false;
    for (int i = 0; i < n_; ++i) {
      for (size_t w = 0; w < walls_.size(); ++w) {
        const Wall& wall = walls_[w];
        const double* c[2] = {centres_[i].big, centres_[i].peg};
        const double r[2] = {kR1, kR2};
        // the centre of mass farther than a2 + R2 from the wall: no sphere reaches it
        const double* p = tops[i].pos;
        bool touch = false;
        if (wall.normal[0] * p[0] + wall.normal[1] * p[1] + wall.normal[2] * p[2] - wall.d <= 0.5 * kReach)
          for (int k = 0; k < 2; ++k)
            touch = touch || wall.normal[0] * c[k][0] + wall.normal[1] * c[k][1] + wall.normal[2] * c[k][2] -
                                     wall.d - r[k] <= kTouchGap;
        char& previous = wall_previous_[i * walls_.size() + w];
        if (touch && !previous) ++wall_onsets;
        any_wall = any_wall || touch;
        previous = touch;
      }
    }
    if (any_wall) ++wall_touch_steps;
  }

  // the JSON fields (without braces), for PrintResult's extra
  std::string Json() const {
    return "\"touch_gap\": " + std::to_string(kTouchGap) + ", \"touch_steps\": " + std::to_string(touch_steps) +
           ", \"pair_touch_steps\": " + std::to_string(pair_touch_steps) +
           ", \"pair_onsets\": " + std::to_string(pair_onsets) +
           ", \"pairs_touched\": " + std::to_string(pairs_touched) +
           ", \"max_touching_pairs\": " + std::to_string(max_touching_pairs) +
           ", \"wall_onsets\": " + std::to_string(wall_onsets) +
           ", \"wall_touch_steps\": " + std::to_string(wall_touch_steps) +
           ", \"max_coordinate\": " + std::to_string(max_coordinate);
  }

  long touch_steps = 0;        // steps with at least one touching pair
  long pair_touch_steps = 0;   // touching pairs summed over the steps
  long pair_onsets = 0;        // a pair touches that did not touch in the step before
  long pairs_touched = 0;      // distinct pairs that touched at some step
  long max_touching_pairs = 0; // most pairs touching in one step
  long wall_onsets = 0;        // a top touches a wall that it did not touch in the step before
  long wall_touch_steps = 0;   // steps with at least one top touching a wall
  double max_coordinate = 0.0; // largest |x| or |y| of a centre of mass (inside the arena: < its half-width)

 private:
  struct Centres {
    double big[3], peg[3];
  };
  static bool Touch(const Centres& p, const Centres& q) {
    const double* cp[2] = {p.big, p.peg};
    const double* cq[2] = {q.big, q.peg};
    const double r[2] = {kR1, kR2};
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b) {
        const double dx = cp[a][0] - cq[b][0], dy = cp[a][1] - cq[b][1], dz = cp[a][2] - cq[b][2];
        const double reach = r[a] + r[b] + kTouchGap;
        if (dx * dx + dy * dy + dz * dz <= reach * reach) return true;
      }
    return false;
  }
  int n_;
  std::vector<Wall> walls_;
  std::vector<char> touched_, wall_previous_;
  std::vector<int> order_;
  std::vector<double> x_;
  std::vector<Centres> centres_;
  std::vector<long> current_, previous_;
};

// Command line shared by the peers: --n N --duration T --dt DT --setting NAME --scene tops|crowd
struct Args {
  int n = 1;
  double duration = kDuration;
  double dt = kDt;
  std::string setting;
  std::string scene = "tops";  // tops: n independent tops (StartOf); crowd: CrowdStartOf, walls
  bool crowd() const { return scene == "crowd"; }
  Start StartOf(int i) const { return crowd() ? CrowdStartOf(i, n) : tippe_top::StartOf(i, n); }
};

// settings: the names the program accepts, the first is the default
inline Args ParseArgs(int argc, char** argv, const std::vector<std::string>& settings) {
  Args a;
  a.setting = settings.front();
  bool ok = true;
  for (int i = 1; i < argc && ok; ++i) {
    const std::string k = argv[i];
    const bool has_value = i + 1 < argc;
    if (k == "--n" && has_value) a.n = std::atoi(argv[++i]);
    else if (k == "--duration" && has_value) a.duration = std::atof(argv[++i]);
    else if (k == "--dt" && has_value) a.dt = std::atof(argv[++i]);
    else if (k == "--setting" && has_value) a.setting = argv[++i];
    else if (k == "--scene" && has_value) a.scene = argv[++i];
    else ok = false;
  }
  bool known = false;
  for (const std::string& s : settings) known = known || s == a.setting;
  const bool scene_ok = a.scene == "tops" || a.scene == "crowd";
  if (!ok || !known || !scene_ok || a.n < 1 || a.duration <= 0.0 || a.dt <= 0.0) {
    std::string names;
    for (const std::string& s : settings) names += (names.empty() ? "" : " | ") + s;
    std::fprintf(stderr, "usage: %s [--n N >= 1] [--duration S] [--dt S] [--setting %s] [--scene tops | crowd]\n",
                 argv[0], names.c_str());
    std::exit(2);
  }
  return a;
}

inline long StepsOf(const Args& a) { return std::lround(a.duration / a.dt); }

// CPU seconds of this process (all threads; the engines step on one thread here)
inline double CpuSeconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

// peak resident set of this process [KiB] (Linux: ru_maxrss is in KiB)
inline long PeakRssKb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss;
}

inline std::string Json(double v) {
  if (!std::isfinite(v)) return "null";
  char b[32];
  std::snprintf(b, sizeof b, "%.9g", v);
  return b;
}
inline std::string JsonTime(double t) { return t < 0.0 ? "null" : Json(t); }

// Monitors for the n tops, their start positions set
inline std::vector<Monitor> MonitorsFor(const std::vector<TopState>& initial) {
  std::vector<Monitor> m(initial.size());
  for (size_t i = 0; i < initial.size(); ++i) {
    m[i].x0 = initial[i].pos[0];
    m[i].y0 = initial[i].pos[1];
  }
  return m;
}

// The one machine-readable line: a JSON object. Events are those of top 0 (the reference start
// when n = 1); "inverted_tops" counts the tops of the n with theta > 150 deg at some time;
// "max_excursion" is the largest excursion of any top (they cannot have met if it stays below
// kSpacing / 2 - R1).
// "peak_rss_kb" is this process's peak resident set (getrusage ru_maxrss); "extra" holds more
// fields (the crowd's pair monitor), without braces.
inline void PrintResult(const char* engine, const std::string& version, const std::string& settings,
                        const Args& a, long steps, double cpu_s, const std::vector<Monitor>& monitors,
                        const std::vector<TopState>& initial, const std::vector<TopState>& final_state,
                        const std::string& extra = "") {
  double e0 = 0.0, e1 = 0.0;
  int inverted = 0;
  bool finite = true;
  for (size_t i = 0; i < final_state.size(); ++i) {
    e0 += Energy(initial[i]);
    e1 += Energy(final_state[i]);
    if (monitors[i].t_inverted >= 0.0) ++inverted;
    for (double c : final_state[i].pos) finite = finite && std::isfinite(c);
  }
  double excursion = 0.0;
  for (const Monitor& m : monitors) excursion = m.excursion > excursion ? m.excursion : excursion;
  const Monitor& m = monitors[0];
  std::printf(
      "{\"engine\": \"%s\", \"version\": \"%s\", \"settings\": \"%s\", \"n\": %d, \"dt\": %s, "
      "\"duration\": %s, \"steps\": %ld, \"cpu_s\": %s, \"inverts\": %s, \"theta_max\": %s, "
      "\"t_theta_above_2_4\": %s, \"t_inverted\": %s, \"t_peg_touchdown\": %s, \"theta_final\": %s, "
      "\"z_final\": %s, \"energy_initial\": %s, \"energy_final\": %s, \"inverted_tops\": %d, "
      "\"max_excursion\": %s, \"finite\": %s, \"scene\": \"%s\", \"peak_rss_kb\": %ld%s%s}\n",
      engine, version.c_str(), settings.c_str(), a.n, Json(a.dt).c_str(), Json(a.duration).c_str(), steps,
      Json(cpu_s).c_str(), m.t_inverted >= 0.0 ? "true" : "false", Json(m.theta_max).c_str(),
      JsonTime(m.t_theta_24).c_str(), JsonTime(m.t_inverted).c_str(), JsonTime(m.t_peg_touchdown).c_str(),
      Json(Theta(final_state[0])).c_str(), Json(final_state[0].pos[2]).c_str(), Json(e0).c_str(),
      Json(e1).c_str(), inverted, Json(excursion).c_str(), finite ? "true" : "false", a.scene.c_str(),
      PeakRssKb(), extra.empty() ? "" : ", ", extra.c_str());
}

}  // namespace tippe_top
