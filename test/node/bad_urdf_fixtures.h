// The malformed URDF fixtures (test/node/fixtures) and what their one error line must say: the
// rostest starts the node with each of them (exit code 1, the scene loader's UrdfError on stderr;
// its wording is src/scene_io/*.cpp's).
#ifndef NONSMOOTH_SIM_TEST_NODE_BAD_URDF_FIXTURES_H_
#define NONSMOOTH_SIM_TEST_NODE_BAD_URDF_FIXTURES_H_

#include <string>
#include <vector>

namespace nonsmooth_sim::node::test {

struct BadUrdf {
  std::string file;                   // under test/node/fixtures
  std::vector<std::string> expected;  // substrings of the error line: element and reason
};

inline const std::vector<BadUrdf>& BadUrdfFixtures() {
  static const std::vector<BadUrdf> fixtures = {
      {"not_xml.urdf", {"not well-formed XML", "Line number=3", "inertial"}},
      {"not_robot.urdf", {"root element is <model>", "expected <robot>"}},
      {"no_inertial.urdf", {"link \"tippe_top\"", "no <inertial>",
                            "a free body with collisions needs mass and inertia"}},
      {"no_free_body.urdf", {"no free body", "root link \"tippe_top\" has no <inertial>"}},
      {"negative_mass.urdf", {"link \"tippe_top\" > inertial > mass", "must be > 0"}},
      {"non_pd_inertia.urdf", {"link \"tippe_top\" > inertial > inertia",
                               "not positive definite"}},
      {"zero_radius.urdf", {"collision \"big_sphere\" > geometry > sphere", "radius=\"0\"",
                            "must be > 0"}},
      {"nan_origin.urdf", {"collision \"peg_sphere\" > origin", "\"nan\" is not a finite number"}},
      {"nan_inertia.urdf", {"inertial > inertia", "iyy", "\"NaN\" is not a finite number"}},
      {"nan_friction.urdf", {"gazebo reference=\"tippe_top\"", "mu", "not a finite number"}},
      // finite but not a simulable rigid body: the first two crashed the node at its
      // first step, the last two were accepted silently
      {"tiny_mass.urdf", {"link \"tippe_top\" > inertial > mass", "value=\"4.9e-324\"",
                          "expected [1e-06, 1e+06] kg"}},
      {"far_inertial_origin.urdf", {"link \"tippe_top\" > inertial > origin", "xyz=\"0 0 1e300\"",
                                    "expected [-1000, 1000] m"}},
      {"absurd_inertia.urdf", {"link \"tippe_top\" > inertial > inertia", "principal moments",
                               "triangle inequality"}},
      {"absurd_friction.urdf", {"gazebo reference=\"tippe_top\"", "ode > mu",
                                "1e300 is out of range, expected [0, 1000]"}},
      // a link with mass on a joint the simulator does not model: its mass must not be lost
      {"moving_joint.urdf", {"joint \"rotor_joint\" (continuous) moves link \"rotor\"",
                             "make it fixed to merge the link into its parent, or floating"}},
  };
  return fixtures;
}

}  // namespace nonsmooth_sim::node::test

#endif  // NONSMOOTH_SIM_TEST_NODE_BAD_URDF_FIXTURES_H_
