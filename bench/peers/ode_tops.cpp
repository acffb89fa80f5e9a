// N Tippe-Tops in ODE (Debian's libode-dev 0.16.2, double precision). One body per top with two
// sphere geoms offset along e3 (the big sphere at a1, the peg at a2), a plane at z = 0; with
// --scene crowd the tops of CrowdStartOf() between the four wall planes of CrowdWalls().
//
// Contacts: one contact joint per touching sphere, friction limits proportional to the normal
// force (dContactApprox1: mu = 0.3 on both tangent rows), and drilling friction as ODE's
// "rolling" row about the normal (dContactRolling | dContactAxisDep, rhoN = mu R̄ with
// dContactApprox1_N, so the torque limit is mu R̄ lambda_N). No rolling resistance: rho = rho2 = -1,
// which ODE's contact joint reads as "no row" (a coefficient < 0 adds no row, 0 adds an empty row
// with zero bounds that the solver still carries), so each contact has 4 rows: normal, two
// tangents, drilling. Each row has its own box limit: drilling is decoupled from sliding (the
// cylinder C_F, with a box for a disc).
//
// Collision: one top (the single-top scene) has exactly two pairs, each sphere with the plane, so
// they are collided directly (dCollide); N tops and the crowd use a sweep-and-prune space
// (dSpaceCollide), the broad phase a user needs once the pairs are not known in advance.
//
// Settings (--setting): world_step (dWorldStep, the pivoting LCP solver, the default) or
// quick_step (dWorldQuickStep, 20 SOR iterations, ODE's default count). World ERP 0.2 and CFM
// 1e-10 (ODE's double-precision defaults), no bounce, no auto-disable, gyroscopic term on.
// Top-top and top-wall contacts get the same surface as the ground.
#include <ode/ode.h>

#include <utility>
#include <vector>

#include "tippe_top_scene.h"

namespace {

using namespace tippe_top;

struct World {
  dWorldID world;
  dSpaceID space;
  dJointGroupID contacts;
  dSurfaceParameters surface;
};

void NearCallback(void* data, dGeomID g1, dGeomID g2) {
  World* w = static_cast<World*>(data);
  dBodyID b1 = dGeomGetBody(g1), b2 = dGeomGetBody(g2);
  if (b1 == b2) return;  // the two spheres of one top
  dContact contact[4];
  const int n = dCollide(g1, g2, 4, &contact[0].geom, sizeof(dContact));
  for (int k = 0; k < n; ++k) {
    contact[k].surface = w->surface;
    dJointID j = dJointCreateContact(w->world, w->contacts, &contact[k]);
    dJointAttach(j, b1, b2);
  }
}

TopState StateOf(dBodyID b) {
  TopState s;
  const dReal* p = dBodyGetPosition(b);
  const dReal* q = dBodyGetQuaternion(b);  // w, x, y, z
  const dReal* v = dBodyGetLinearVel(b);
  const dReal* w = dBodyGetAngularVel(b);  // world frame
  for (int k = 0; k < 3; ++k) {
    s.pos[k] = p[k];
    s.vel[k] = v[k];
    s.omega[k] = w[k];
  }
  for (int k = 0; k < 4; ++k) s.quat[k] = q[k];
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  const Args args = ParseArgs(argc, argv, {"world_step", "quick_step"});
  const bool quick = args.setting == "quick_step";

  dInitODE2(0);
  World w;
  w.world = dWorldCreate();
  dWorldSetGravity(w.world, 0, 0, -kGravity);
  dWorldSetERP(w.world, 0.2);
  dWorldSetCFM(w.world, 1e-10);
  dWorldSetQuickStepNumIterations(w.world, 20);
  dWorldSetAutoDisableFlag(w.world, 0);
  // sweep and prune on all three axes: ODE's broad phase without parameters, and its fastest here
  // (N = 16, 256 and the crowd: 1.6-1.8x less CPU than a hash space with cells 2^-7 to 2^-3 m,
  // the same printed results; a simple space is O(N^2))
  w.space = dSweepAndPruneSpaceCreate(nullptr, dSAP_AXES_XYZ);
  w.contacts = dJointGroupCreate(0);
  dGeomID ground = dCreatePlane(w.space, 0, 0, 1, 0);
  if (args.crowd())  // planes a x + b y + c z = d, (a, b, c) towards the free side
    for (const Wall& wall : CrowdWalls(args.n))
      dCreatePlane(w.space, wall.normal[0], wall.normal[1], wall.normal[2], wall.d);

  std::memset(&w.surface, 0, sizeof w.surface);
  w.surface.mode = dContactApprox1 | dContactRolling | dContactAxisDep | dContactMu2;
  w.surface.mu = kMu;
  w.surface.mu2 = kMu;
  w.surface.rho = -1.0;  // no rolling-resistance rows about the tangents (< 0: no row)
  w.surface.rho2 = -1.0;
  w.surface.rhoN = kTorsionalLength;  // drilling: |tau_n| <= mu R̄ lambda_N
  w.surface.bounce = 0.0;

  // one top: its two pairs collided directly; the space only holds the geoms
  const bool direct = args.n == 1 && !args.crowd();
  std::vector<std::pair<dGeomID, dGeomID>> pairs_to_collide;
  std::vector<dBodyID> bodies;
  std::vector<TopState> initial;
  for (int i = 0; i < args.n; ++i) {
    const Start s = args.StartOf(i);
    dBodyID b = dBodyCreate(w.world);
    dMass m;
    dMassSetParameters(&m, kMass, 0, 0, 0, kA, kA, kC, 0, 0, 0);
    dBodySetMass(b, &m);
    dBodySetPosition(b, s.pos[0], s.pos[1], s.pos[2]);
    dQuaternion q = {s.quat[0], s.quat[1], s.quat[2], s.quat[3]};
    dBodySetQuaternion(b, q);
    dBodySetLinearVel(b, s.vel[0], s.vel[1], s.vel[2]);
    dBodySetAngularVel(b, s.omega[0], s.omega[1], s.omega[2]);
    dBodySetGyroscopicMode(b, 1);
    dGeomID big = dCreateSphere(w.space, kR1);
    dGeomSetBody(big, b);
    dGeomSetOffsetPosition(big, 0, 0, kA1);
    dGeomID peg = dCreateSphere(w.space, kR2);
    dGeomSetBody(peg, b);
    dGeomSetOffsetPosition(peg, 0, 0, kA2);
    pairs_to_collide.push_back({big, ground});
    pairs_to_collide.push_back({peg, ground});
    bodies.push_back(b);
    initial.push_back(StateOf(b));
  }

  const long steps = StepsOf(args);
  std::vector<Monitor> monitors = MonitorsFor(initial);
  PairMonitor pairs(args.n, CrowdWalls(args.n));
  std::vector<TopState> state(bodies.size());
  const double c0 = CpuSeconds();
  for (long k = 1; k <= steps; ++k) {
    if (direct)
      for (const auto& p : pairs_to_collide) NearCallback(&w, p.first, p.second);
    else
      dSpaceCollide(w.space, &w, NearCallback);
    if (quick) dWorldQuickStep(w.world, args.dt);
    else dWorldStep(w.world, args.dt);
    dJointGroupEmpty(w.contacts);
    const double t = k * args.dt;
    for (size_t i = 0; i < bodies.size(); ++i) {
      state[i] = StateOf(bodies[i]);
      monitors[i].Update(t, state[i]);
    }
    if (args.crowd()) pairs.Update(state);
  }
  const double cpu = CpuSeconds() - c0;

  std::vector<TopState> final_state;
  for (dBodyID b : bodies) final_state.push_back(StateOf(b));
  const std::string settings =
      std::string(quick ? "dWorldQuickStep 20 iter" : "dWorldStep (LCP)") +
      ", Approx1 box friction mu 0.3, drilling rhoN = mu*Rbar (box, decoupled), no rolling rows, " +
      (direct ? "pairs collided directly" : "sweep-and-prune space") + ", ERP 0.2, CFM 1e-10";
  PrintResult("ode", "0.16.2", settings, args, steps, cpu, monitors, initial, final_state,
              args.crowd() ? pairs.Json() : "");
  dJointGroupDestroy(w.contacts);
  dSpaceDestroy(w.space);
  dWorldDestroy(w.world);
  dCloseODE();
  return 0;
}
