// Unit tests of compute morphology2d on hand-made wires with known answers.
#include <cmath>

#include "helpers.hpp"

using namespace slender;
using namespace slender::test;

namespace {
// n nodes on a circle arc of radius R around the origin, spacing 1, turning by
// the given total angle
std::vector<Vec3> arc(double R, double total) {
  std::vector<Vec3> pts;
  const double step = 2 * std::asin(0.5 / R);
  const int n = static_cast<int>(std::floor(total / step)) + 1;
  for (int i = 0; i < n; ++i) pts.emplace_back(R * std::cos(i * step), R * std::sin(i * step), 0);
  return pts;
}
}  // namespace

TEST(Morphology2dCompute, CurvatureNearTheWallIsClassic) {
  Simulation sim(2, 1);
  sim.add_chain("w", arc(9.0, 5.0), 1.0, false);  // r = 10: all hinges in the outer ring
  sim.add_compute("m", "morphology2d", P({{"radius", 10.0}}));
  EXPECT_EQ(sim.column("m.A"), 0.0);
  // each hinge turns by the arc step: B = (n - 2) step^2 / l0
  const double step = 2 * std::asin(0.5 / 9.0);
  const double n = std::floor(5.0 / step) + 1;
  EXPECT_NEAR(sim.column("m.B"), (n - 2) * step * step, 1e-9);
  EXPECT_EQ(sim.column("m.classic"), 1.0);
  EXPECT_NEAR(sim.column("m.net_winding"), (n - 2) * step / (2 * M_PI), 1e-9);
}

TEST(Morphology2dCompute, DoubleSpiralWindsPerArmNotNet) {
  // an S: two arcs turning in opposite senses, like the arms of a double spiral
  Simulation sim(2, 1);
  auto a = arc(2.0, 2 * M_PI);
  std::vector<Vec3> pts;
  for (auto it = a.rbegin(); it != a.rend(); ++it) pts.push_back(*it + Vec3(0, 0, 0));
  for (size_t i = 1; i < a.size(); ++i) pts.push_back(Vec3(4.0 - a[i].x(), -a[i].y(), 0));
  sim.add_chain("w", pts, 1.0, false);
  sim.add_compute("m", "morphology2d", P({{"radius", 20.0}}));
  EXPECT_LT(sim.column("m.net_winding"), 0.1);
  EXPECT_GT(sim.column("m.winding"), 0.8);
}

TEST(Morphology2dCompute, CurvatureInTheCentreIsNotClassicAndWindingCountsTurns) {
  Simulation sim(2, 1);
  sim.add_chain("w", arc(3.0, 4 * M_PI), 1.0, false);  // two full turns in the inner disc
  sim.add_compute("m", "morphology2d", P({{"radius", 10.0}}));
  EXPECT_EQ(sim.column("m.B"), 0.0);
  EXPECT_GT(sim.column("m.A"), 0.0);
  EXPECT_EQ(sim.column("m.classic"), 0.0);
  EXPECT_NEAR(sim.column("m.net_winding"), 2.0, 0.1);
  EXPECT_NEAR(sim.column("m.winding"), 1.0, 0.1);  // each half turns once
  // the part of a wire outside the cavity does not count
  Simulation out(2, 1);
  out.add_chain("w", arc(12.0, 3.0), 1.0, false);
  out.add_compute("m", "morphology2d", P({{"radius", 10.0}}));
  EXPECT_EQ(out.column("m.A") + out.column("m.B") + out.column("m.winding"), 0.0);
}
