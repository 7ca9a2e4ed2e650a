/// A forward solve that does not converge says where the largest force is, so that the
/// user can find the part of the layout at fault.
#include <gtest/gtest.h>

#include <string>

#include "rigid_body_case.hpp"
#include "tightfit/body/generators.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/garment/primitive_garments.hpp"
#include "tightfit/solve/garment_simulation.hpp"

namespace tightfit::solve_failure_message_test {

TEST(SolveFailureMessage, NamesThePieceAndPlaceOfTheLargestForce) {
  CylinderParams cyl;
  cyl.radius = 0.05;
  cyl.length = 0.2;
  cyl.edge_length = 0.01;
  const Body body = test::rigid_body(cylinder_surface(cyl));
  const LimitSurface surface(body.surface);
  SleeveParams sleeve;
  sleeve.radius = cyl.radius;
  sleeve.axial_begin = -0.04;
  sleeve.axial_end = 0.04;
  sleeve.hoop_scale = 0.85;
  sleeve.edge_length = 0.012;
  sleeve.jitter = 0.3;
  sleeve.pin_first_ring = sleeve.pin_last_ring = true;
  NewtonOptions newton;
  newton.max_iterations = 1;  // far from converged after one step
  newton.max_chord_steps = 0;
  GarmentSimulation sim(body, surface, make_sleeve(sleeve, surface, body.surface.vertices),
                        test::rigid_materials(), newton);
  try {
    sim.solve();
    FAIL() << "expected the solve to stop unconverged";
  } catch (const SolverError& e) {
    const std::string what = e.what();
    std::printf("  %s\n", what.c_str());
    EXPECT_NE(what.find("did not converge"), std::string::npos) << what;
    EXPECT_NE(what.find("largest force "), std::string::npos) << what;
    EXPECT_NE(what.find(" N on garment vertex "), std::string::npos) << what;
    EXPECT_NE(what.find("(piece 'sleeve')"), std::string::npos) << what;
    EXPECT_NE(what.find(") m"), std::string::npos) << what;
  }
}

}  // namespace tightfit::solve_failure_message_test
