// URDF (urdfdom model + TinyXML2 extension tags) -> core Scene. See urdf_scene.h.
#include "nonsmooth_sim/scene_io/urdf_scene.h"

#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <type_traits>

#include "link_groups.h"
#include "nonsmooth_sim/core/collision/collision.h"
#include "nonsmooth_sim/scene_io/bounded_input.h"
#include "nonsmooth_sim/scene_io/format.h"
#include "nonsmooth_sim/scene_io/mesh_source.h"
#include "nonsmooth_sim/scene_io/urdf_xml.h"

namespace nonsmooth_sim::scene_io {
namespace {

// urdfdom reports through console_bridge and carries on; collect its first error instead of
// printing it (a library does not print), so that the caller gets one line.
class UrdfdomErrors : public console_bridge::OutputHandler {
 public:
  UrdfdomErrors() : previous_(console_bridge::getOutputHandler()) {
    console_bridge::useOutputHandler(this);
  }
  ~UrdfdomErrors() override { console_bridge::useOutputHandler(previous_); }
  UrdfdomErrors(const UrdfdomErrors&) = delete;
  UrdfdomErrors& operator=(const UrdfdomErrors&) = delete;

  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR && first_error_.empty()) {
      first_error_ = text;
    }
  }
  const std::string& first_error() const { return first_error_; }

 private:
  console_bridge::OutputHandler* previous_;
  std::string first_error_;
};

std::string LinkLabel(const std::string& name) { return "link " + Quoted(name); }

// "a", "b", "c" (quoted, comma separated); "none" when empty.
std::string QuotedList(const std::vector<std::string>& names) {
  std::string list;
  for (const std::string& name : names) list += (list.empty() ? "" : ", ") + Quoted(name);
  return list.empty() ? "none" : list;
}

// Mass, centre of mass and inertia about it of a group, in its first link's frame and axes.
struct MassProperties {
  double mass = 0.0;
  Eigen::Vector3d com = Eigen::Vector3d::Zero();
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
};

std::string FormatVector(const Eigen::Vector3d& v) {
  return "(" + Format(v.x()) + ", " + Format(v.y()) + ", " + Format(v.z()) + ")";
}

// Throws unless every coordinate of `point` is within kMaxCoordinate (urdf_scene.h, "Bounds").
void CheckCoordinates(const std::string& what, const Eigen::Vector3d& point) {
  if (point.cwiseAbs().maxCoeff() > kMaxCoordinate) {
    throw UrdfError("urdf: " + what + " " + FormatVector(point) +
                    " m: coordinates must be in [" + Format(-kMaxCoordinate) + ", " +
                    Format(kMaxCoordinate) + "] m");
  }
}

// The rigid-body checks of "Bounds" (urdf_scene.h) on a mass m and its inertia Θ about the centre
// of mass: m in [kMinMass, kMaxMass]; the principal moments I₁ ≤ I₂ ≤ I₃ (eigenvalues of Θ) > 0
// with I₃ ≤ (I₁ + I₂)(1 + kInertiaTriangleTolerance); √(Iᵢ/m) in [kMinGyrationRadius,
// kMaxGyrationRadius]; and with extent > 0, √(I₃/m) ≤ kGyrationSizeFactor·extent. `what` names
// the element ("link "b" > inertial > inertia") or the body.
void CheckRigidBody(const std::string& what, double mass, const Eigen::Matrix3d& inertia,
                    double extent) {
  const auto fail = [&](const std::string& reason) {
    throw UrdfError("urdf: " + what + ": " + reason);
  };
  if (!(mass >= kMinMass && mass <= kMaxMass)) {
    fail("mass " + Format(mass) + " kg must be in [" + Format(kMinMass) + ", " +
         Format(kMaxMass) + "] kg");
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(
      0.5 * (inertia + inertia.transpose()), Eigen::EigenvaluesOnly);
  const Eigen::Vector3d moments = eigen.eigenvalues();  // ascending
  const std::string listed = "principal moments " + Format(moments[0]) + ", " +
                             Format(moments[1]) + ", " + Format(moments[2]) + " kg m^2";
  if (!(moments[0] > 0.0)) fail(listed + ": not positive definite");
  if (moments[2] > (moments[0] + moments[1]) * (1.0 + kInertiaTriangleTolerance)) {
    fail(listed + ": " + Format(moments[2]) + " > " + Format(moments[0]) + " + " +
         Format(moments[1]) +
         " violates the triangle inequality (each principal moment of a rigid body is at most "
         "the sum of the other two; relative tolerance " +
         Format(kInertiaTriangleTolerance) + ")");
  }
  const double smallest = std::sqrt(moments[0] / mass);
  const double largest = std::sqrt(moments[2] / mass);
  const std::string range = "[" + Format(kMinGyrationRadius) + ", " +
                            Format(kMaxGyrationRadius) + "] m";
  if (!(smallest >= kMinGyrationRadius && largest <= kMaxGyrationRadius)) {
    fail(listed + " for mass " + Format(mass) + " kg: radii of gyration sqrt(I/m) from " +
         Format(smallest) + " to " + Format(largest) + " m must be in " + range);
  }
  if (extent > 0.0 && largest > kGyrationSizeFactor * extent) {
    fail(listed + " for mass " + Format(mass) + " kg: the largest radius of gyration sqrt(I/m) = " +
         Format(largest) + " m must be at most " + Format(kGyrationSizeFactor) +
         " x the body's extent " + Format(extent) +
         " m (the farthest point of its collisions from the centre of mass)");
  }
}

// Θ of one <inertial> in the group link's axes: the inertia is given about the link's centre of
// mass in the axes of <inertial><origin> (rotation R_o); the member link is turned by R_m in the
// group link's frame, so Θ = (R_m R_o) Θ (R_m R_o)ᵀ. Throws unless Θ is positive definite and a
// rigid body's (CheckRigidBody).
void AddInertial(const LinkGroup::Member& member,
                 std::vector<std::pair<double, Eigen::Vector3d>>* masses,
                 std::vector<Eigen::Matrix3d>* inertias) {
  const urdf::Link& link = *member.link;
  const urdf::Inertial& inertial = *link.inertial;
  Eigen::Matrix3d theta;
  theta << inertial.ixx, inertial.ixy, inertial.ixz,  //
      inertial.ixy, inertial.iyy, inertial.iyz,       //
      inertial.ixz, inertial.iyz, inertial.izz;
  if (Eigen::LLT<Eigen::Matrix3d>(theta).info() != Eigen::Success) {
    throw UrdfError("urdf: " + LinkLabel(link.name) +
                    " > inertial > inertia: not positive definite (ixx=" +
                    std::to_string(inertial.ixx) + " iyy=" + std::to_string(inertial.iyy) +
                    " izz=" + std::to_string(inertial.izz) + " ixy=" +
                    std::to_string(inertial.ixy) + " ixz=" + std::to_string(inertial.ixz) +
                    " iyz=" + std::to_string(inertial.iyz) + ")");
  }
  CheckRigidBody(LinkLabel(link.name) + " > inertial > inertia", inertial.mass, theta, 0.0);
  const Eigen::Matrix3d rotation =
      member.pose.linear() * ToEigen(inertial.origin.rotation).toRotationMatrix();
  masses->emplace_back(inertial.mass, member.pose * ToEigen(inertial.origin.position));
  inertias->push_back(rotation * theta * rotation.transpose());
}

// The members' inertials combined (see urdf_scene.h): m = Σ mᵢ, c = Σ mᵢ cᵢ / m,
// Θ_S = Σ [Θᵢ + mᵢ (|dᵢ|² 1 − dᵢ dᵢᵀ)] with dᵢ = cᵢ − c. mass = 0 when no member has one.
MassProperties CombinedMass(const std::vector<LinkGroup::Member>& members) {
  std::vector<std::pair<double, Eigen::Vector3d>> masses;  // (mᵢ, cᵢ)
  std::vector<Eigen::Matrix3d> inertias;                   // Θᵢ about cᵢ
  for (const LinkGroup::Member& member : members) {
    if (member.link->inertial) AddInertial(member, &masses, &inertias);
  }
  MassProperties total;
  if (masses.empty()) return total;
  for (const auto& [m, c] : masses) total.mass += m;
  // c = c₀ + Σ (mᵢ/m)(cᵢ − c₀): exactly c₀ for a single link
  const Eigen::Vector3d& reference = masses.front().second;
  total.com = reference;
  for (const auto& [m, c] : masses) total.com += (m / total.mass) * (c - reference);
  // parallel-axis theorem: Θ_S = Σ [Θᵢ + mᵢ (|dᵢ|² 1 − dᵢ dᵢᵀ)]
  for (std::size_t i = 0; i < masses.size(); ++i) {
    const Eigen::Vector3d d = masses[i].second - total.com;
    total.inertia += inertias[i] + masses[i].first * (d.squaredNorm() * Eigen::Matrix3d::Identity() -
                                                      d * d.transpose());
  }
  return total;
}

ContactLaw LawFromSurface(const LinkSurface& surface, const UrdfSceneOptions& options) {
  ContactLaw law;
  law.friction_set = surface.friction_set.value_or(options.friction_set);
  law.restitution = surface.restitution;
  const double radius = options.contact_radius.value_or(surface.patch_radius);
  law.rbar = AverageFrictionRadius(radius);  // (50)
  law.rolling_resistance = static_cast<float>(options.rolling_resistance.value_or(
      surface.rolling_resistance.value_or(surface.rolling_friction)));
  if (options.mu) {
    law.mu = *options.mu;
  } else {
    law.mu = surface.mu;
    // Gazebo bounds the drilling torque by μ_τ (3πR/16) λ_N, the core by R̄ μ λ_N
    if (surface.torsional_coefficient != surface.mu && surface.mu > 0.0) {
      law.rbar *= surface.torsional_coefficient / surface.mu;
    }
  }
  return law;
}

bool EndsWith(const std::string& text, const std::string& suffix) {
  return text.size() >= suffix.size() &&
         text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// The body's parameters when it is a Tippe-Top (see urdf_scene.h), for TippeTopInitialState.
std::optional<TippeTopParameters> TippeTopOf(const Scene& scene, int body_index,
                                             const UrdfSceneOptions& options,
                                             const LinkSurface& surface) {
  const Collider* big = nullptr;
  const Collider* peg = nullptr;
  int big_count = 0;
  int peg_count = 0;
  for (const Collider& c : scene.colliders) {
    if (c.body != body_index) continue;
    if (EndsWith(c.name, "big_sphere")) {
      big = &c;
      ++big_count;
    }
    if (EndsWith(c.name, "peg_sphere")) {
      peg = &c;
      ++peg_count;
    }
  }
  if (big_count != 1 || peg_count != 1) return std::nullopt;
  const auto on_axis = [](const Collider& c) {
    return c.shape.type == ShapeType::kSphere && c.pose.translation().head<2>().isZero(0.0);
  };
  const Eigen::Matrix3d& theta = scene.bodies[body_index].inertia;
  const bool symmetric = theta(0, 0) == theta(1, 1) && theta(0, 1) == 0.0 &&
                         theta(0, 2) == 0.0 && theta(1, 2) == 0.0;
  if (!on_axis(*big) || !on_axis(*peg) || !symmetric) return std::nullopt;
  TippeTopParameters p;
  p.mass = scene.bodies[body_index].mass;
  p.inertia_equatorial = theta(0, 0);
  p.inertia_axial = theta(2, 2);
  p.big_radius = big->shape.radius;
  p.peg_radius = peg->shape.radius;
  p.big_offset = big->pose.translation().z();
  p.peg_offset = peg->pose.translation().z();
  p.gravity = options.gravity;
  p.mu = big->law.mu;
  p.contact_radius = options.contact_radius.value_or(surface.patch_radius);
  p.restitution = big->law.restitution;
  p.rolling_resistance = big->law.rolling_resistance;
  p.friction_set = big->law.friction_set;
  return p;
}

class Builder {
 public:
  Builder(const urdf::ModelInterface& model, const UrdfXml& xml, const UrdfSceneOptions& options)
      : model_(model), xml_(xml), options_(options) {
    for (std::size_t i = 0; i < xml.link_order.size(); ++i) document_index_[xml.link_order[i]] = i;
    if (options.ground) collider_links_["ground"] = "";
  }

  UrdfScene Build() {
    result_.warnings = xml_.warnings;
    CheckExtensionReferences();
    result_.scene.gravity = Eigen::Vector3d(0.0, 0.0, -options_.gravity);
    result_.scene.collision_table = options_.collision_table;
    const urdf::Link& root = *model_.getRoot();
    // the joints the user holds rigid (checked against the model first), then the groups
    const HeldJoints held = ResolveHeldJoints(model_, xml_.joint_holds, options_.hold_joints);
    groups_ = GroupLinks(model_, held, &result_.warnings);
    // bodies in the document order of their links; the world group (the root's) first
    std::stable_sort(groups_.begin(), groups_.end(), [&](const LinkGroup& a, const LinkGroup& b) {
      const auto rank = [&](const LinkGroup& g) {
        return std::make_pair(g.kind != LinkGroup::Kind::kWorld, Index(*g.members.front().link));
      };
      return rank(a) < rank(b);
    });
    for (LinkGroup& group : groups_) {
      std::stable_sort(group.members.begin() + 1, group.members.end(),
                       [&](const LinkGroup::Member& a, const LinkGroup::Member& b) {
                         return Index(*a.link) < Index(*b.link);
                       });
      switch (group.kind) {
        case LinkGroup::Kind::kWorld: AddWorld(group); break;
        case LinkGroup::Kind::kFree: AddBody(group); break;
        case LinkGroup::Kind::kLeftOut: break;  // nothing in it to simulate (link_groups.h)
      }
    }
    if (result_.scene.bodies.empty()) {
      throw UrdfError("urdf: no free body: the root " + LinkLabel(root.name) +
                      (root.inertial ? ""
                                     : " has no <inertial> (nor has a link fixed to it), so it "
                                       "is the static world,") +
                      " and no link with an <inertial> hangs on a floating joint");
    }
    if (options_.ground) result_.scene.colliders.push_back(GroundPlane());
    for (int b = 0; b < static_cast<int>(result_.scene.bodies.size()); ++b) {
      result_.tippe_top.push_back(
          TippeTopOf(result_.scene, b, options_, Surface(result_.scene.bodies[b].name)));
    }
    ReportMissingCollideFunctions();
    return std::move(result_);
  }

 private:
  std::size_t Index(const urdf::Link& link) const {
    const auto it = document_index_.find(link.name);
    return it == document_index_.end() ? document_index_.size() : it->second;
  }

  LinkSurface Surface(const std::string& link) const {
    const auto it = xml_.surfaces.find(link);
    return it == xml_.surfaces.end() ? LinkSurface{} : it->second;
  }

  // Typos in references are errors: every <nonsmooth_sim> names a link and every shape a
  // collision of it. An unknown Gazebo reference may be a Gazebo-only name: a warning.
  void CheckExtensionReferences() {
    for (const ExtensionBlock& block : xml_.extension_blocks) {
      if (!model_.getLink(block.link)) {
        throw UrdfError("urdf: " + block.where + ": no link named " + Quoted(block.link) +
                        "; links: " + QuotedList(xml_.link_order));
      }
    }
    for (const auto& [link_name, shapes] : xml_.shapes) {
      const urdf::LinkConstSharedPtr link = model_.getLink(link_name);
      std::vector<std::string> names;
      for (const urdf::CollisionSharedPtr& c : link->collision_array) {
        if (!c->name.empty()) names.push_back(c->name);
      }
      for (const auto& [collision, shape] : shapes) {
        if (std::find(names.begin(), names.end(), collision) == names.end()) {
          throw UrdfError("urdf: " + shape.where + ": " + LinkLabel(link_name) +
                          " has no collision named " + Quoted(collision) +
                          "; its named collisions: " + QuotedList(names));
        }
      }
    }
    for (const std::string& ref : xml_.gazebo_references) {
      if (!model_.getLink(ref) && !model_.getJoint(ref)) {
        result_.warnings.push_back("urdf: gazebo reference=" + Quoted(ref) +
                                   " is neither a link nor a joint, ignored");
      }
    }
  }

  void AddWorld(const LinkGroup& group) {
    const std::string& world = group.members.front().link->name;
    for (const LinkGroup::Member& member : group.members) {
      if (member.link->inertial) {
        throw UrdfError("urdf: " + LinkLabel(member.link->name) + " is fixed to the world " +
                        LinkLabel(world) +
                        ": static links have no mass; make it a floating joint or remove the "
                        "inertial");
      }
      AddColliders(*member.link, group.world_pose * member.pose, kWorld);
      result_.fixed_links.push_back({member.link->name, kWorld, group.world_pose * member.pose});
    }
  }

  void AddBody(const LinkGroup& group) {
    const urdf::Link& link = *group.members.front().link;
    const MassProperties mass = CombinedMass(group.members);
    if (mass.mass == 0.0) {
      for (const LinkGroup::Member& member : group.members) {
        if (!member.link->collision_array.empty()) {
          throw UrdfError("urdf: " + LinkLabel(link.name) +
                          ": no <inertial> (a free body with collisions needs mass and inertia" +
                          (group.members.size() > 1 ? ", on it or on a link fixed to it)" : ")"));
        }
      }
      return;  // a bare frame
    }
    const int index = static_cast<int>(result_.scene.bodies.size());
    RigidBody body;
    body.name = link.name;
    body.mass = mass.mass;
    body.inertia = mass.inertia;
    body.com_in_link = mass.com;
    // K: the body link's frame shifted to S, link axes
    const Eigen::Isometry3d link_in_body(Eigen::Translation3d(-mass.com));
    std::vector<std::string> merged;
    for (const LinkGroup::Member& member : group.members) {
      AddColliders(*member.link, link_in_body * member.pose, index);
      if (member.link == &link) continue;
      merged.push_back(member.link->name);
      result_.fixed_links.push_back({member.link->name, index, member.pose});
    }
    // the body as a whole (links merged): its mass, its inertia against its size, its start
    double extent = 0.0;
    for (const Collider& c : result_.scene.colliders) {
      if (c.body != index) continue;
      extent = std::max(extent, c.pose.translation().norm() + BoundingRadius(c.shape));
    }
    CheckRigidBody(LinkLabel(link.name) +
                       (merged.empty() ? std::string(" (the body)")
                                       : " (the body, with the links fixed to it)"),
                   mass.mass, mass.inertia, extent);
    BodyState state;
    state.orientation = Eigen::Quaterniond(group.world_pose.linear());
    state.position = group.world_pose * mass.com;
    CheckCoordinates(LinkLabel(link.name) +
                         ": its start (the joint origins from the root) puts the centre of mass at",
                     state.position);
    result_.scene.bodies.push_back(body);
    result_.scene.initial_state.push_back(state);
    result_.merged_links.push_back(std::move(merged));
  }

  // The colliders of `link`; `frame` maps the link frame to K of body `body` (or to the world).
  void AddColliders(const urdf::Link& link, const Eigen::Isometry3d& frame, int body) {
    const LinkSurface surface = Surface(link.name);
    const auto overrides = xml_.shapes.find(link.name);
    int k = 0;
    for (const urdf::CollisionSharedPtr& collision : link.collision_array) {
      ++k;
      const std::string label = LinkLabel(link.name) + " > collision " + Quoted(collision->name);
      const ShapeOverride* override = nullptr;
      if (overrides != xml_.shapes.end()) {
        const auto it = overrides->second.find(collision->name);
        if (it != overrides->second.end()) override = &it->second;
      }
      Collider collider;
      Eigen::Isometry3d shape_frame = Eigen::Isometry3d::Identity();  // in the collision's
      if (override != nullptr && override->revolution) {
        if (!collision->geometry || collision->geometry->type != urdf::Geometry::MESH) {
          throw UrdfError("urdf: " + override->where + ": <body_of_revolution> reads the "
                          "collision's <mesh>, but " + label + " has none; allowed: a <mesh> "
                          "collision");
        }
        const MeshRevolution body = MeshBodyOfRevolution(
            static_cast<const urdf::Mesh&>(*collision->geometry), *override->revolution, label);
        collider.shape = body.shape;
        shape_frame = body.frame;
      } else if (override != nullptr) {
        if (override->shape.type == ShapeType::kPlane && body != kWorld) {
          throw UrdfError("urdf: " + override->where + ": a plane is a half-space fixed in the "
                          "world, but " + LinkLabel(link.name) + " is part of a free body; "
                          "allowed on free bodies: <ellipsoid>, <capsule>");
        }
        collider.shape = override->shape;
      } else if (!collision->geometry) {
        result_.warnings.push_back("urdf: " + label + ": no geometry, skipped");
        continue;
      } else {
        switch (collision->geometry->type) {
          case urdf::Geometry::SPHERE:
            collider.shape =
                Shape::Sphere(static_cast<const urdf::Sphere&>(*collision->geometry).radius);
            break;
          case urdf::Geometry::CYLINDER: {
            const auto& c = static_cast<const urdf::Cylinder&>(*collision->geometry);
            collider.shape = Shape::Cylinder(c.radius, 0.5 * c.length);  // axis z
            break;
          }
          case urdf::Geometry::BOX: {
            const urdf::Vector3& size = static_cast<const urdf::Box&>(*collision->geometry).dim;
            collider.shape = Shape::Box(0.5 * ToEigen(size));
            break;
          }
          case urdf::Geometry::MESH: {
            const auto& mesh = static_cast<const urdf::Mesh&>(*collision->geometry);
            collider.shape = Shape::Hull(MeshHull(mesh, label));
            break;
          }
          default:
            result_.warnings.push_back("urdf: " + label + ": unknown geometry type, skipped");
            continue;
        }
      }
      collider.name =
          collision->name.empty() ? link.name + "_collision" + std::to_string(k) : collision->name;
      ClaimName(collider.name, link.name, label);
      collider.body = body;
      collider.pose = frame * ToEigen(collision->origin) * shape_frame;
      collider.law = LawFromSurface(surface, options_);
      CheckCoordinates(label + (body == kWorld ? ": its world position (the joint origins from "
                                                 "the root)"
                                               : ": its position relative to the body's centre of "
                                                 "mass"),
                       collider.pose.translation());
      CheckContactRadius(surface, collider, label);
      result_.scene.colliders.push_back(collider);
    }
  }

  // R of a collider's law (the option or the link's patch radius) lies on the shape: at most its
  // bounding radius on a free body; R̄ = 3πR/16·μ_τ/μ at most kMaxLength (μ_τ/μ can be huge).
  void CheckContactRadius(const LinkSurface& surface, const Collider& collider,
                          const std::string& label) const {
    const double radius = options_.contact_radius.value_or(surface.patch_radius);
    const char* source = options_.contact_radius ? "the option contact_radius"
                                                 : "<torsional><patch_radius> of the link";
    if (collider.body != kWorld && radius > BoundingRadius(collider.shape)) {
      throw UrdfError("urdf: " + label + ": contact patch radius R = " + Format(radius) +
                      " m (" + source + ") must be at most the size of the shape, its bounding "
                      "radius " + Format(BoundingRadius(collider.shape)) +
                      " m (a contact patch lies on the shape)");
    }
    if (collider.law.rbar > kMaxLength) {
      throw UrdfError("urdf: " + label + ": drilling radius Rbar = 3 pi R/16 * mu_tau/mu = " +
                      Format(collider.law.rbar) + " m (R = " + Format(radius) + " m, mu_tau = " +
                      Format(surface.torsional_coefficient) + ", mu = " + Format(surface.mu) +
                      ") must be at most " + Format(kMaxLength) + " m");
    }
  }

  // The convex hull of a <mesh> (mesh_source.h); one line naming the collision and the file if
  // it cannot be one.
  std::shared_ptr<const ConvexHull> MeshHull(const urdf::Mesh& mesh, const std::string& label) {
    return ReadMesh(mesh, label, [&](const std::string& path) {
      return LoadMeshHull(path, ToEigen(mesh.scale), options_.max_hull_vertices,
                          options_.max_bytes);
    });
  }

  // A <mesh> as a body of revolution (mesh_source.h), the same way.
  MeshRevolution MeshBodyOfRevolution(const urdf::Mesh& mesh, const RevolutionRequest& request,
                                      const std::string& label) {
    return ReadMesh(mesh, label, [&](const std::string& path) {
      return LoadMeshRevolution(path, ToEigen(mesh.scale), request.axis, request.tolerance,
                                options_.max_bytes);
    });
  }

  template <typename Load>
  std::invoke_result_t<Load, const std::string&> ReadMesh(const urdf::Mesh& mesh,
                                                          const std::string& label, Load load) {
    std::string path;
    try {
      const char* environment = std::getenv("ROS_PACKAGE_PATH");
      path = ResolveMeshFilename(
          mesh.filename, options_.mesh_directory,
          options_.ros_package_path.value_or(environment != nullptr ? environment : ""));
      return load(path);
    } catch (const std::invalid_argument& e) {
      throw UrdfError("urdf: " + label + ": mesh " + Quoted(mesh.filename) +
                      (path.empty() || path == mesh.filename ? "" : " (" + path + ")") + ": " +
                      e.what());
    }
  }

  // Contacts are addressed by collider name: every name once.
  void ClaimName(const std::string& name, const std::string& link, const std::string& label) {
    const auto [it, inserted] = collider_links_.emplace(name, link);
    if (inserted) return;
    if (it->second.empty()) {
      throw UrdfError("urdf: " + label + ": the name " + Quoted(name) +
                      " is reserved for the ground plane (rename the collision, or load without "
                      "the ground)");
    }
    throw UrdfError("urdf: " + label + ": the collision name " + Quoted(name) +
                    " is also used by " + LinkLabel(it->second) +
                    " (contacts are addressed by name; rename one)");
  }

  // A pair of shape types that can meet (different bodies, or a body and the world) without a
  // collide function would pass through each other silently: one warning per pair of types.
  void ReportMissingCollideFunctions() {
    struct Seen {
      int body;
      const std::string* name;
    };
    // per type, colliders on up to two distinct bodies: enough to find a pair on two bodies
    std::array<std::vector<Seen>, kShapeTypeCount> seen;
    for (const Collider& c : result_.scene.colliders) {
      std::vector<Seen>& s = seen[static_cast<int>(c.shape.type)];
      if (s.size() < 2 && (s.empty() || s.front().body != c.body)) s.push_back({c.body, &c.name});
    }
    for (int a = 0; a < kShapeTypeCount; ++a) {
      for (int b = a; b < kShapeTypeCount; ++b) {
        const ShapeType ta = static_cast<ShapeType>(a);
        const ShapeType tb = static_cast<ShapeType>(b);
        for (const Seen& x : seen[a]) {
          const auto y = std::find_if(seen[b].begin(), seen[b].end(),
                                      [&](const Seen& s) { return s.body != x.body; });
          if (y == seen[b].end()) continue;
          if (result_.scene.collision_table.Find(ta, tb) == nullptr) {
            result_.warnings.push_back(
                "urdf: no collide function for " + std::string(ShapeTypeName(ta)) + "-" +
                std::string(ShapeTypeName(tb)) + " pairs (e.g. colliders " + Quoted(*x.name) +
                " and " + Quoted(*y->name) + "): they pass through each other");
          }
          break;
        }
      }
    }
  }

  const urdf::ModelInterface& model_;
  const UrdfXml& xml_;
  const UrdfSceneOptions& options_;
  std::map<std::string, std::size_t> document_index_;
  std::map<std::string, std::string> collider_links_;  // collider name → link ("" = the ground)
  std::vector<LinkGroup> groups_;
  UrdfScene result_;
};

}  // namespace

void ValidateUrdfSceneOptions(const UrdfSceneOptions& options) {
  // (the comparisons are false for NaN)
  if (!(options.gravity >= 0.0 && options.gravity <= kMaxGravity)) {
    throw std::invalid_argument("gravity = " + Format(options.gravity) + ": must be in [0, " +
                                Format(kMaxGravity) + "] [m/s^2]");
  }
  if (options.mu && !(*options.mu >= 0.0 && *options.mu <= kMaxFriction)) {
    throw std::invalid_argument("mu = " + Format(*options.mu) + ": must be in [0, " +
                                Format(kMaxFriction) + "]");
  }
  if (options.contact_radius &&
      !(*options.contact_radius >= 0.0 && *options.contact_radius <= kMaxLength)) {
    throw std::invalid_argument("contact_radius = " + Format(*options.contact_radius) +
                                ": must be in [0, " + Format(kMaxLength) +
                                "] [m] (and at most the size of every shape of a free body)");
  }
  if (options.rolling_resistance &&
      !(*options.rolling_resistance >= 0.0 && *options.rolling_resistance <= kMaxLength)) {
    throw std::invalid_argument("rolling_resistance = " + Format(*options.rolling_resistance) +
                                ": must be in [0, " + Format(kMaxLength) + "] [m]");
  }
  if (options.max_bytes < 1 || options.max_bytes > kMaxInputBytesOption) {
    throw std::invalid_argument("max_bytes = " + std::to_string(options.max_bytes) +
                                ": must be in [1, " + std::to_string(kMaxInputBytesOption) +
                                "] [bytes]");
  }
  if (!IsFrictionSet(options.friction_set)) {
    throw std::invalid_argument("friction_set must be one of " + FrictionSetNameList());
  }
  for (const std::string& joint : options.hold_joints) {
    try {
      CheckNameLength("joint", joint);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string("hold_joints: ") + e.what());
    }
  }
  if (options.max_hull_vertices < 4 || options.max_hull_vertices > kMaxHullVerticesBound) {
    throw std::invalid_argument("max_hull_vertices = " +
                                std::to_string(options.max_hull_vertices) + ": must be in [4, " +
                                std::to_string(kMaxHullVerticesBound) + "]");
  }
}

UrdfScene SceneFromUrdf(const std::string& urdf_xml, const UrdfSceneOptions& options) {
  ValidateUrdfSceneOptions(options);
  if (urdf_xml.size() > options.max_bytes) {
    throw UrdfError("urdf: the text has " + std::to_string(urdf_xml.size()) +
                    " bytes, more than the bound of " + DescribeBytes(options.max_bytes) +
                    " (refused before parsing)");
  }
  const UrdfXml xml = ParseUrdfXml(urdf_xml);

  urdf::ModelInterfaceSharedPtr model;
  {
    UrdfdomErrors errors;
    model = urdf::parseURDF(urdf_xml);
    if (!errors.first_error().empty()) throw UrdfError("urdf: " + errors.first_error());
  }
  if (!model || !model->getRoot()) throw UrdfError("urdf: urdfdom could not build the model");

  UrdfScene result = Builder(*model, xml, options).Build();
  result.robot_name = model->getName();
  try {
    ValidateScene(result.scene);
  } catch (const std::invalid_argument& e) {
    throw UrdfError(std::string("urdf: ") + e.what());
  }
  for (std::string& warning : result.warnings) warning = OneLine(warning);  // names quoted
  return result;
}

UrdfScene LoadUrdfFile(const std::string& path, const UrdfSceneOptions& options) {
  std::string text;
  try {
    text = ReadBoundedFile(path, options.max_bytes, "a URDF file");
  } catch (const std::invalid_argument& e) {
    throw UrdfError("urdf: " + path + ": " + e.what());
  }
  try {
    if (options.mesh_directory.empty()) {
      // relative mesh paths: from the URDF file's folder
      UrdfSceneOptions with_folder = options;
      with_folder.mesh_directory = std::filesystem::path(path).parent_path().string();
      if (with_folder.mesh_directory.empty()) with_folder.mesh_directory = ".";
      return SceneFromUrdf(text, with_folder);
    }
    return SceneFromUrdf(text, options);
  } catch (const UrdfError& e) {
    // "urdf: <reason>" → "urdf: <path>: <reason>"
    const std::string what = e.what();
    const std::string prefix = "urdf: ";
    throw UrdfError(prefix + path + ": " +
                    (what.rfind(prefix, 0) == 0 ? what.substr(prefix.size()) : what));
  }
}

}  // namespace nonsmooth_sim::scene_io
