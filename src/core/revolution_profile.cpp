// A body of revolution's profile: the meridian points' half-section, its corners rounded by
// tangent arcs. See revolution_profile.h.
#include "nonsmooth_sim/core/revolution_profile.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "nonsmooth_sim/core/constants.h"

namespace nonsmooth_sim {
namespace {

using Point = Eigen::Vector2d;  // (ρ, z)

[[noreturn]] void Refuse(const std::string& what) {
  throw std::invalid_argument("MakeRevolutionProfile: " + what);
}

double Cross(const Point& o, const Point& a, const Point& b) {
  return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}

// The convex hull of `points` counter-clockwise from the lowest of the leftmost, collinear points
// dropped (Andrew's monotone chain).
std::vector<Point> Hull2d(std::vector<Point> points) {
  std::sort(points.begin(), points.end(), [](const Point& a, const Point& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  points.erase(std::unique(points.begin(), points.end()), points.end());
  if (points.size() < 3) return points;
  std::vector<Point> hull(2 * points.size());
  std::size_t k = 0;
  for (const Point& p : points) {  // lower
    while (k >= 2 && Cross(hull[k - 2], hull[k - 1], p) <= 0.0) --k;
    hull[k++] = p;
  }
  const std::size_t lower = k + 1;
  for (std::size_t i = points.size() - 1; i-- > 0;) {  // upper
    while (k >= lower && Cross(hull[k - 2], hull[k - 1], points[i]) <= 0.0) --k;
    hull[k++] = points[i];
  }
  hull.resize(k - 1);  // the last is the first
  return hull;
}

// Normal angle θ (from +z towards +ρ) of an edge walked from the top to the bottom: outward is
// on the left of the walk, n = (−e_z, e_ρ)/|e|.
double EdgeTheta(const Point& e) { return std::atan2(-e.y(), e.x()); }

Point Mirror(const Point& p) { return Point(-p.x(), p.y()); }

Point U(double theta) { return Point(std::sin(theta), std::cos(theta)); }

// Turn of the walk at b between the edges a→b and b→c [rad].
double Turn(const Point& a, const Point& b, const Point& c) {
  double turn = EdgeTheta(c - b) - EdgeTheta(b - a);
  if (turn <= -kPi) turn += 2.0 * kPi;  // across ±π (the bottom)
  return turn;
}

}  // namespace

std::shared_ptr<const RevolutionProfile> MakeRevolutionProfile(
    const std::vector<Eigen::Vector2d>& meridian, double rounding) {
  if (!(std::isfinite(rounding) && rounding > 0.0)) {
    Refuse("rounding tolerance " + std::to_string(rounding) + ": must be finite and > 0 [m]");
  }
  // the half-section: the hull of the points and the axis between their lowest and highest
  std::vector<Point> points;
  points.reserve(meridian.size() + 2);
  double z_min = INFINITY, z_max = -INFINITY;
  for (const Point& p : meridian) {
    if (!p.allFinite()) Refuse("a meridian point is not finite");
    points.emplace_back(std::abs(p.x()), p.y());
    z_min = std::min(z_min, p.y());
    z_max = std::max(z_max, p.y());
  }
  if (points.empty()) Refuse("no meridian points");
  points.emplace_back(0.0, z_min);
  points.emplace_back(0.0, z_max);
  std::vector<Point> ccw = Hull2d(points);
  if (ccw.size() < 3) Refuse("the meridian points span no area (all on a line)");
  // the walk from the top to the bottom: the hull clockwise from (0, z_max) to (0, z_min)
  std::vector<Point> walk(ccw.rbegin(), ccw.rend());
  std::rotate(walk.begin(),
              std::find(walk.begin(), walk.end(), Point(0.0, z_max)), walk.end());
  walk.resize(std::find(walk.begin(), walk.end(), Point(0.0, z_min)) - walk.begin() + 1);
  // merge points closer than kMergeFraction τ to the last one kept or to the bottom pole (the
  // poles stay; a corner that does not turn gets no arc below)
  const double merge = kMergeFraction * rounding;
  std::vector<Point> chain{walk.front()};
  for (std::size_t i = 1; i + 1 < walk.size(); ++i) {
    if ((walk[i] - chain.back()).norm() >= merge && (walk[i] - walk.back()).norm() >= merge) {
      chain.push_back(walk[i]);
    }
  }
  chain.push_back(walk.back());
  // a pole on the axis followed by a flat disc: the disc's corner alone
  const auto flat_pole = [&](std::size_t pole, std::size_t next) {
    return chain.size() > 2 && chain[next].y() == chain[pole].y();
  };
  if (flat_pole(0, 1)) chain.erase(chain.begin());
  if (flat_pole(chain.size() - 1, chain.size() - 2)) chain.pop_back();
  if (chain.size() < 2) Refuse("the meridian points span no area (all on a line)");
  const std::size_t m = chain.size();
  const auto before = [&](std::size_t k) {
    if (k > 0) return chain[k - 1];
    return chain[0].x() > 0.0 ? Mirror(chain[0]) : Mirror(chain[1]);
  };
  const auto after = [&](std::size_t k) {
    if (k + 1 < m) return chain[k + 1];
    return chain[m - 1].x() > 0.0 ? Mirror(chain[m - 1]) : Mirror(chain[m - 2]);
  };

  auto profile = std::make_shared<RevolutionProfile>();
  profile->rounding = rounding;
  profile->top_z = z_max;
  profile->bottom_z = z_min;
  for (std::size_t k = 0; k < m; ++k) {
    const Point& c = chain[k];
    const Point e_in = c - before(k);
    const Point e_out = after(k) - c;
    const double alpha = Turn(before(k), c, after(k));
    profile->bounding_radius = std::max(profile->bounding_radius, c.norm());
    if (!(alpha > 1e-12)) continue;  // no corner: a straight walk through c
    // the tangent length t and the arc's radius r = t/tan(α/2), centre T_in − r n_in
    const double t =
        std::min({0.5 * e_in.norm(), 0.5 * e_out.norm(), rounding / std::tan(0.25 * alpha)});
    const double theta_in = EdgeTheta(e_in);
    RevolutionArc arc;
    arc.radius = t / std::tan(0.5 * alpha);
    arc.centre = c - t * e_in.normalized() - arc.radius * U(theta_in);
    if (c.x() == 0.0) arc.centre.x() = 0.0;  // a pole's arc: centred on the axis
    arc.theta_end = std::min(theta_in + alpha, kPi);
    if (k == 0 && c.x() > 0.0) profile->top_disc_radius = c.x() - t;
    if (k + 1 == m && c.x() > 0.0) profile->bottom_disc_radius = c.x() - t;
    if (arc.theta_end > 0.0) profile->arcs.push_back(arc);
  }
  if (profile->arcs.empty()) Refuse("the meridian points span no area (all on a line)");
  profile->arcs.back().theta_end = kPi;
  for (RevolutionArc& arc : profile->arcs) arc.cos_end = std::cos(arc.theta_end);
  for (std::size_t k = 0; k + 1 < profile->arcs.size(); ++k) {
    const double length = (ArcStart(*profile, static_cast<int>(k) + 1) -
                           ArcEnd(*profile, static_cast<int>(k))).norm();
    profile->arcs[k].stretch = length >= merge ? length : 0.0;
  }
  return profile;
}

Eigen::Vector2d ProfilePoint(const RevolutionProfile& profile, const Eigen::Vector2d& u,
                             int* arc) {
  // θ ≤ θ_end ⇔ cos θ ≥ cos θ_end on [0, π]
  const auto it = std::lower_bound(
      profile.arcs.begin(), profile.arcs.end() - 1, u.y(),
      [](const RevolutionArc& a, double cos_theta) { return a.cos_end > cos_theta; });
  if (arc != nullptr) *arc = static_cast<int>(it - profile.arcs.begin());
  return it->centre + it->radius * u;
}

Eigen::Vector2d ProfilePoint(const RevolutionProfile& profile, double theta, int* arc) {
  return ProfilePoint(profile, U(theta), arc);
}

Eigen::Vector2d ArcStart(const RevolutionProfile& profile, int k) {
  const RevolutionArc& a = profile.arcs[k];
  return a.centre + a.radius * U(k == 0 ? 0.0 : profile.arcs[k - 1].theta_end);
}

Eigen::Vector2d ArcEnd(const RevolutionProfile& profile, int k) {
  const RevolutionArc& a = profile.arcs[k];
  return a.centre + a.radius * U(a.theta_end);
}

MeridianDirection SplitDirection(const Eigen::Vector3d& d) {
  MeridianDirection result;
  const double s = std::sqrt(d.x() * d.x() + d.y() * d.y());
  const double length = std::sqrt(s * s + d.z() * d.z());
  result.u = Eigen::Vector2d(s / length, d.z() / length);
  if (s > 0.0) result.radial = Eigen::Vector3d(d.x() / s, d.y() / s, 0.0);
  return result;
}

Eigen::Vector3d RevolutionSupport(const RevolutionProfile& profile, const Eigen::Vector3d& d) {
  const MeridianDirection split = SplitDirection(d);
  return AtAzimuth(ProfilePoint(profile, split.u), split.radial);
}

double RevolutionVolume(const RevolutionProfile& profile) {
  // the half-section as a fine polygon, walked top → bottom (clockwise), closed on the axis:
  // ∫ρ dA = −(1/6) Σ (ρ_i + ρ_j)(ρ_i z_j − ρ_j z_i)
  constexpr int kPerArc = 256;
  std::vector<Point> polygon{Point(0.0, profile.top_z)};
  double begin = 0.0;
  for (const RevolutionArc& a : profile.arcs) {
    for (int j = 0; j <= kPerArc; ++j) {
      polygon.push_back(a.centre + a.radius * U(begin + (a.theta_end - begin) * j / kPerArc));
    }
    begin = a.theta_end;
  }
  polygon.emplace_back(0.0, profile.bottom_z);
  double moment = 0.0;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Point& a = polygon[i];
    const Point& b = polygon[(i + 1) % polygon.size()];
    moment -= (a.x() + b.x()) * (a.x() * b.y() - b.x() * a.y()) / 6.0;
  }
  return 2.0 * kPi * moment;
}

}  // namespace nonsmooth_sim
