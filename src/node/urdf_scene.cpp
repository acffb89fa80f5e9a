// URDF (urdfdom model + TinyXML2 extension tags) -> core Scene. See urdf_scene.h.
#include "nonsmooth_sim/node/urdf_scene.h"

#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <cmath>
#include <set>

#include "nonsmooth_sim/node/urdf_xml.h"

namespace nonsmooth_sim::node {
namespace {

// urdfdom reports through console_bridge and carries on; collect its first error instead of
// printing it, so that the node prints one line.
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

Eigen::Vector3d ToEigen(const urdf::Vector3& v) { return {v.x, v.y, v.z}; }
Eigen::Quaterniond ToEigen(const urdf::Rotation& r) { return {r.w, r.x, r.y, r.z}; }
Eigen::Isometry3d ToEigen(const urdf::Pose& pose) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = ToEigen(pose.rotation).toRotationMatrix();
  t.translation() = ToEigen(pose.position);
  return t;
}

std::string LinkLabel(const std::string& name) { return "link \"" + name + "\""; }

// Θ in link axes at S from the URDF <inertial>: the inertia is given about the centre of mass in
// the axes of <inertial><origin> (rotation R), so Θ_link = R Θ Rᵀ.
RigidBody BodyFromInertial(const urdf::Link& link) {
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
  const Eigen::Matrix3d rotation = ToEigen(inertial.origin.rotation).toRotationMatrix();
  RigidBody body;
  body.name = link.name;
  body.mass = inertial.mass;
  body.inertia = rotation * theta * rotation.transpose();
  body.com_in_link = ToEigen(inertial.origin.position);
  return body;
}

ContactLaw LawFromSurface(const LinkSurface& surface, const UrdfSceneOptions& options) {
  ContactLaw law;
  law.friction_set = options.friction_set;
  law.restitution = surface.restitution;
  const double radius = options.contact_radius.value_or(surface.patch_radius);
  law.rbar = AverageFrictionRadius(radius);  // (50)
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

// The body's parameters when it is a Tippe-Top (see urdf_scene.h), for TippeTopInitialState.
std::optional<TippeTopParameters> TippeTopOf(const Scene& scene, int body_index,
                                             const UrdfSceneOptions& options,
                                             const LinkSurface& surface) {
  const Sphere* big = nullptr;
  const Sphere* peg = nullptr;
  for (const Sphere& s : scene.spheres) {
    if (s.body != body_index) continue;
    if (s.name == "big_sphere") big = &s;
    if (s.name == "peg_sphere") peg = &s;
  }
  const RigidBody& body = scene.bodies[body_index];
  const Eigen::Matrix3d& theta = body.inertia;
  const bool axial = big != nullptr && peg != nullptr && big->center.head<2>().isZero(0.0) &&
                     peg->center.head<2>().isZero(0.0);
  const bool symmetric = theta(0, 0) == theta(1, 1) && theta(0, 1) == 0.0 &&
                         theta(0, 2) == 0.0 && theta(1, 2) == 0.0;
  if (!axial || !symmetric) return std::nullopt;
  TippeTopParameters p;
  p.mass = body.mass;
  p.inertia_equatorial = theta(0, 0);
  p.inertia_axial = theta(2, 2);
  p.big_radius = big->radius;
  p.peg_radius = peg->radius;
  p.big_offset = big->center.z();
  p.peg_offset = peg->center.z();
  p.gravity = options.gravity;
  p.mu = big->law.mu;
  p.contact_radius = options.contact_radius.value_or(surface.patch_radius);
  p.restitution = big->law.restitution;
  p.friction_set = big->law.friction_set;
  return p;
}

struct Builder {
  const UrdfSceneOptions& options;
  const UrdfXml& xml;
  UrdfScene result;
  std::set<std::string> sphere_names;

  void AddSpheres(const urdf::Link& link, int body_index, const Eigen::Vector3d& com_in_link) {
    const auto surface = xml.surfaces.find(link.name);
    const LinkSurface link_surface =
        surface == xml.surfaces.end() ? LinkSurface{} : surface->second;
    int k = 0;
    for (const urdf::CollisionSharedPtr& collision : link.collision_array) {
      const std::string label = LinkLabel(link.name) + " > collision \"" + collision->name + "\"";
      ++k;
      if (!collision->geometry || collision->geometry->type != urdf::Geometry::SPHERE) {
        result.warnings.push_back("urdf: " + label +
                                  ": only sphere collisions touch the ground, skipped");
        continue;
      }
      Sphere sphere;
      sphere.name = collision->name.empty() ? link.name + "_sphere" + std::to_string(k)
                                            : collision->name;
      if (!sphere_names.insert(sphere.name).second) {
        throw UrdfError("urdf: " + label + ": the collision name \"" + sphere.name +
                        "\" is used twice (contacts are addressed by name)");
      }
      sphere.body = body_index;
      sphere.radius = static_cast<const urdf::Sphere&>(*collision->geometry).radius;
      // centre in K: the link frame shifted to the centre of mass, link axes
      sphere.center = ToEigen(collision->origin.position) - com_in_link;
      sphere.law = LawFromSurface(link_surface, options);
      result.scene.spheres.push_back(sphere);
    }
  }

  void AddBody(const urdf::Link& link, const Eigen::Isometry3d& link_pose) {
    const int index = static_cast<int>(result.scene.bodies.size());
    RigidBody body = BodyFromInertial(link);
    BodyState state;
    state.orientation = Eigen::Quaterniond(link_pose.linear());
    state.position = link_pose * body.com_in_link;
    AddSpheres(link, index, body.com_in_link);
    result.scene.bodies.push_back(body);
    result.scene.initial_state.push_back(state);
  }

  // Depth first from the root; `free` = the root or a child of a floating joint.
  void Visit(const urdf::Link& link, const Eigen::Isometry3d& pose, bool free,
             const std::string& joint_label) {
    if (free && link.inertial) {
      AddBody(link, pose);
    } else if (free && !link.collision_array.empty()) {
      throw UrdfError("urdf: " + LinkLabel(link.name) +
                      ": no <inertial> (a free body with collisions needs mass and inertia)");
    } else if (!free && (link.inertial || !link.collision_array.empty())) {
      result.warnings.push_back("urdf: " + LinkLabel(link.name) + " hangs on " + joint_label +
                                ": only the root and links on floating joints are free bodies, "
                                "skipped");
    }
    for (const urdf::JointSharedPtr& joint : link.child_joints) {
      const urdf::LinkSharedPtr child = [&] {
        for (const urdf::LinkSharedPtr& l : link.child_links) {
          if (l->name == joint->child_link_name) return l;
        }
        return urdf::LinkSharedPtr();
      }();
      if (!child) continue;
      Visit(*child, pose * ToEigen(joint->parent_to_joint_origin_transform),
            joint->type == urdf::Joint::FLOATING, "joint \"" + joint->name + "\"");
    }
  }
};

}  // namespace

void ValidateUrdfSceneOptions(const UrdfSceneOptions& options) {
  if (!(std::isfinite(options.gravity) && options.gravity >= 0.0)) {
    throw std::invalid_argument("gravity must be finite and >= 0 [m/s^2]");
  }
  if (options.mu && !(std::isfinite(*options.mu) && *options.mu >= 0.0)) {
    throw std::invalid_argument("mu must be finite and >= 0");
  }
  if (options.contact_radius &&
      !(std::isfinite(*options.contact_radius) && *options.contact_radius >= 0.0)) {
    throw std::invalid_argument("contact_radius must be finite and >= 0 [m]");
  }
}

UrdfScene SceneFromUrdf(const std::string& urdf_xml, const UrdfSceneOptions& options) {
  ValidateUrdfSceneOptions(options);
  const UrdfXml xml = ParseUrdfXml(urdf_xml);

  urdf::ModelInterfaceSharedPtr model;
  {
    UrdfdomErrors errors;
    model = urdf::parseURDF(urdf_xml);
    if (!errors.first_error().empty()) throw UrdfError("urdf: " + errors.first_error());
  }
  if (!model || !model->getRoot()) throw UrdfError("urdf: urdfdom could not build the model");

  Builder builder{options, xml, {}, {}};
  builder.result.scene.gravity = Eigen::Vector3d(0.0, 0.0, -options.gravity);
  builder.result.warnings = xml.warnings;
  builder.Visit(*model->getRoot(), Eigen::Isometry3d::Identity(), true, "");
  UrdfScene& result = builder.result;
  if (result.scene.bodies.empty()) {
    throw UrdfError("urdf: no free body (the root link \"" + model->getRoot()->name +
                    "\" has no <inertial> and no link hangs on a floating joint)");
  }
  for (const auto& [name, surface] : xml.surfaces) {
    if (!model->getLink(name)) {
      result.warnings.push_back("urdf: extension reference \"" + name + "\" is not a link, ignored");
    }
  }
  for (int b = 0; b < static_cast<int>(result.scene.bodies.size()); ++b) {
    const auto surface = xml.surfaces.find(result.scene.bodies[b].name);
    result.tippe_top.push_back(TippeTopOf(result.scene, b, options,
                                          surface == xml.surfaces.end() ? LinkSurface{}
                                                                        : surface->second));
  }
  try {
    ValidateScene(result.scene);
  } catch (const std::invalid_argument& e) {
    throw UrdfError(std::string("urdf: ") + e.what());
  }
  return result;
}

}  // namespace nonsmooth_sim::node
