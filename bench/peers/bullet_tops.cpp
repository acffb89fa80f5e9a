// N Tippe-Tops in Bullet (Debian's libbullet-dev 3.24, its double-precision build
// bullet-float64). One rigid body per top, a btCompoundShape of two spheres offset along e3 (the
// big sphere at a1, the peg at a2), a static plane at z = 0.
//
// Contacts (btDiscreteDynamicsWorld, btSequentialImpulseConstraintSolver): Bullet multiplies the
// two objects' coefficients (combined friction = mu_top x mu_ground; combined spinning friction =
// spinning_top x mu_ground + mu_top x spinning_ground), so the ground gets friction 1 and no
// spinning or rolling friction, the top friction 0.3 and spinning friction mu R̄ ≈ 8.84e-5 m (a
// length: torque limit = coefficient x normal impulse). The spinning row is clamped on its own,
// decoupled from the sliding rows (the cylinder C_F). Bullet adds the spinning row only when the
// combined rolling friction is positive, so the top gets a rolling friction of 1e-12 m (a
// rolling-resistance torque 1e-8 of the drilling one). Restitution 0, no damping, no sleeping,
// implicit gyroscopic term (BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_BODY, Bullet's default), one
// internal step of dt per stepSimulation.
//
// Combining rules: Bullet's defaults multiply (friction mu_a mu_b, spinning s_a mu_b + mu_a s_b),
// which would give two tops mu = 0.09; the program sets the pair rule of nonsmooth_sim (and
// MuJoCo's max): friction min(mu_a, mu_b), spinning friction max(s_a, s_b); against the ground
// (friction 1, spinning 0) that is the same mu = 0.3 and mu R̄ as the multiplying rules, so only
// the crowd's top-top contacts see the difference. With --scene crowd the tops of CrowdStartOf()
// between the four static planes of CrowdWalls() (friction 1, spinning and rolling 0, as the ground).
//
// Settings (--setting): default (10 iterations, one friction direction along the slip, split
// impulse, Bullet's defaults) or iter100_2dir (100 iterations, two friction directions).
#include <BulletCollision/CollisionDispatch/btManifoldResult.h>
#include <btBulletDynamicsCommon.h>

#include <algorithm>

#include <memory>
#include <vector>

#include "tippe_top_scene.h"

namespace {

using namespace tippe_top;

constexpr double kRollingFrictionEnable = 1e-12;  // [m], see above

btScalar MinFriction(const btCollisionObject* a, const btCollisionObject* b) {
  return std::min(a->getFriction(), b->getFriction());
}
btScalar MaxSpinningFriction(const btCollisionObject* a, const btCollisionObject* b) {
  return std::max(a->getSpinningFriction(), b->getSpinningFriction());
}

TopState StateOf(const btRigidBody* b) {
  TopState s;
  const btVector3& p = b->getCenterOfMassPosition();
  const btQuaternion q = b->getOrientation();
  const btVector3& v = b->getLinearVelocity();
  const btVector3& w = b->getAngularVelocity();  // world frame
  for (int k = 0; k < 3; ++k) {
    s.pos[k] = p[k];
    s.vel[k] = v[k];
    s.omega[k] = w[k];
  }
  s.quat[0] = q.w();
  s.quat[1] = q.x();
  s.quat[2] = q.y();
  s.quat[3] = q.z();
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  const Args args = ParseArgs(argc, argv, {"default", "iter100_2dir"});
  const bool strong = args.setting == "iter100_2dir";

  gCalculateCombinedFrictionCallback = &MinFriction;
  gCalculateCombinedSpinningFrictionCallback = &MaxSpinningFriction;
  btDefaultCollisionConfiguration configuration;
  btCollisionDispatcher dispatcher(&configuration);
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btDiscreteDynamicsWorld world(&dispatcher, &broadphase, &solver, &configuration);
  world.setGravity(btVector3(0, 0, -kGravity));
  if (strong) {
    world.getSolverInfo().m_numIterations = 100;
    world.getSolverInfo().m_solverMode |= SOLVER_USE_2_FRICTION_DIRECTIONS;
  }

  btStaticPlaneShape plane(btVector3(0, 0, 1), 0);
  btRigidBody::btRigidBodyConstructionInfo ground_info(0.0, nullptr, &plane);
  ground_info.m_friction = 1.0;
  ground_info.m_rollingFriction = 0.0;
  ground_info.m_spinningFriction = 0.0;
  ground_info.m_restitution = 0.0;
  btRigidBody ground(ground_info);
  world.addRigidBody(&ground);
  // the crowd's walls: static planes n . x = d, n towards the arena
  std::vector<std::unique_ptr<btStaticPlaneShape>> wall_shapes;
  std::vector<std::unique_ptr<btRigidBody>> walls;
  if (args.crowd()) {
    for (const Wall& wall : CrowdWalls(args.n)) {
      wall_shapes.push_back(std::make_unique<btStaticPlaneShape>(
          btVector3(wall.normal[0], wall.normal[1], wall.normal[2]), wall.d));
      btRigidBody::btRigidBodyConstructionInfo info(0.0, nullptr, wall_shapes.back().get());
      info.m_friction = 1.0;
      info.m_rollingFriction = 0.0;
      info.m_spinningFriction = 0.0;
      info.m_restitution = 0.0;
      walls.push_back(std::make_unique<btRigidBody>(info));
      world.addRigidBody(walls.back().get());
    }
  }

  btSphereShape big(kR1), peg(kR2);
  btCompoundShape top_shape;
  top_shape.addChildShape(btTransform(btQuaternion::getIdentity(), btVector3(0, 0, kA1)), &big);
  top_shape.addChildShape(btTransform(btQuaternion::getIdentity(), btVector3(0, 0, kA2)), &peg);

  std::vector<std::unique_ptr<btRigidBody>> bodies;
  std::vector<TopState> initial;
  for (int i = 0; i < args.n; ++i) {
    const Start s = args.StartOf(i);
    btRigidBody::btRigidBodyConstructionInfo info(kMass, nullptr, &top_shape, btVector3(kA, kA, kC));
    info.m_startWorldTransform = btTransform(btQuaternion(s.quat[1], s.quat[2], s.quat[3], s.quat[0]),
                                             btVector3(s.pos[0], s.pos[1], s.pos[2]));
    info.m_friction = kMu;
    info.m_spinningFriction = kTorsionalLength;
    info.m_rollingFriction = kRollingFrictionEnable;
    info.m_restitution = 0.0;
    info.m_linearDamping = 0.0;
    info.m_angularDamping = 0.0;
    auto b = std::make_unique<btRigidBody>(info);
    b->setActivationState(DISABLE_DEACTIVATION);
    b->setFlags(BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_BODY);
    b->setLinearVelocity(btVector3(s.vel[0], s.vel[1], s.vel[2]));
    b->setAngularVelocity(btVector3(s.omega[0], s.omega[1], s.omega[2]));
    world.addRigidBody(b.get());
    initial.push_back(StateOf(b.get()));
    bodies.push_back(std::move(b));
  }

  const long steps = StepsOf(args);
  std::vector<Monitor> monitors = MonitorsFor(initial);
  PairMonitor pairs(args.n, CrowdWalls(args.n));
  std::vector<TopState> state(bodies.size());
  const double c0 = CpuSeconds();
  for (long k = 1; k <= steps; ++k) {
    world.stepSimulation(args.dt, 0);  // maxSubSteps 0: exactly one step of dt
    const double t = k * args.dt;
    for (size_t i = 0; i < bodies.size(); ++i) {
      state[i] = StateOf(bodies[i].get());
      monitors[i].Update(t, state[i]);
    }
    if (args.crowd()) pairs.Update(state);
  }
  const double cpu = CpuSeconds() - c0;

  std::vector<TopState> final_state;
  for (const auto& b : bodies) final_state.push_back(StateOf(b.get()));
  const std::string settings =
      std::string(strong ? "SI 100 iter, 2 friction dirs" : "SI 10 iter (default), 1 friction dir") +
      ", mu 0.3, spinning friction mu*Rbar (decoupled), rolling 1e-12, split impulse, ERP2 0.2, "
      "pairs: min friction, max spinning friction";
  std::string version = std::to_string(btGetVersion() / 100) + "." + std::to_string(btGetVersion() % 100);
  version += btIsDoublePrecision() ? " (double)" : " (single)";
  PrintResult("bullet", version, settings, args, steps, cpu, monitors, initial, final_state,
              args.crowd() ? pairs.Json() : "");
  for (const auto& b : bodies) world.removeRigidBody(b.get());
  for (const auto& b : walls) world.removeRigidBody(b.get());
  world.removeRigidBody(&ground);
  return 0;
}
