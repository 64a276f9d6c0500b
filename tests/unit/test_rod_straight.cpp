// Unit tests of bond rod/straight (discrete elastic rod without directors,
// docs/models.md §3): forces against the energy, invariances, exact values.
// Covers styles/bond/rod_straight.cpp and styles/compute/gyration.cpp.
#include <Eigen/Geometry>
#include <cmath>

#include "helpers.hpp"

using namespace slender;
using namespace slender::test;

namespace {
double rod_energy(const std::vector<Vec3>& pts, bool closed, double YI = 2.0, int dim = 3) {
  Simulation sim(dim, 1);
  sim.add_chain("r", pts, 1.0, closed);
  sim.add_bond("rod/straight", P({{"YI", YI}}));
  sim.compute_forces();
  return sim.potential_energy();
}
}  // namespace

TEST(StraightRodBond, ForcesAreMinusTheEnergyGradient) {
  for (bool closed : {false, true}) {
    Simulation sim(3, 1);
    auto pts = wiggly_chain(9, 3, 11, 0.4);
    if (closed)  // bend the chain round so that the closing edge is of normal length
      for (size_t i = 0; i < pts.size(); ++i) {
        const double t = 2 * M_PI * i / pts.size();
        pts[i] +=
            Vec3(1.5 * std::cos(t) - pts[i].x() + 0.0, 1.5 * std::sin(t), 0.2 * std::sin(3 * t));
      }
    sim.add_chain("r", pts, 1.0, closed);
    sim.add_bond("rod/straight", P({{"YI", 3.0}}));
    EXPECT_LT(fd_force_error(sim), 1e-6) << (closed ? "closed" : "open");
  }
  // strongly bent (turning angles near 150 degrees) and unequal edges
  Simulation sharp(3, 1);
  sharp.add_chain("r",
                  {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.2, 0.3, 0.1), Vec3(1.1, 0.9, -0.4),
                   Vec3(2.5, 1.0, 0.3)},
                  1.0, false);
  sharp.add_bond("rod/straight", P({{"YI", 1.0}}));
  EXPECT_LT(fd_force_error(sharp), 1e-6);
}

TEST(StraightRodBond, StraightRestStateHasNoEnergyOrForce) {
  Simulation sim(3, 1);
  std::vector<Vec3> pts;
  for (int i = 0; i < 10; ++i) pts.emplace_back(0.3 * i, 0.7 * i, -0.2 * i);
  sim.add_chain("r", pts, 1.0, false);
  sim.add_bond("rod/straight", P({{"YI", 5.0}}));
  sim.compute_forces();
  EXPECT_NEAR(sim.potential_energy(), 0.0, 1e-24);
  for (auto& f : sim.nodes().f) EXPECT_LT(f.norm(), 1e-12);
}

TEST(StraightRodBond, EnergyIsInvariantUnderRigidMotionsAndMomentumIsConserved) {
  auto pts = wiggly_chain(8, 3, 4, 0.5);
  const double e0 = rod_energy(pts, false);
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(0.7, Vec3(1, 2, -0.5).normalized()).toRotationMatrix();
  std::vector<Vec3> moved;
  for (auto& p : pts) moved.push_back(R * p + Vec3(3, -1, 2));
  EXPECT_NEAR(rod_energy(moved, false), e0, 1e-12 * e0);
  // internal forces: no net force and no net torque
  Simulation sim(3, 1);
  sim.add_chain("r", pts, 1.0, false);
  sim.add_bond("rod/straight", P({{"YI", 2.0}}));
  sim.compute_forces();
  Vec3 F = Vec3::Zero(), T = Vec3::Zero();
  for (size_t i = 0; i < pts.size(); ++i) {
    F += sim.nodes().f[i];
    T += pts[i].cross(sim.nodes().f[i]);
  }
  EXPECT_LT(F.norm(), 1e-12);
  EXPECT_LT(T.norm(), 1e-12);
}

TEST(StraightRodBond, OneHingeStoresTheDiscreteBendingEnergy) {
  // turning angle phi: |kb| = 2 tan(phi/2) (docs/models.md §3.1 (4.2)), E = YI |kb|^2 / (2 l0)
  for (double phi : {0.1, 1.0, 2.5}) {
    const double l0 = 1.0, YI = 2.0;
    std::vector<Vec3> pts{Vec3(-l0, 0, 0), Vec3(0, 0, 0),
                          Vec3(l0 * std::cos(phi), l0 * std::sin(phi), 0)};
    const double kb = 2 * std::tan(phi / 2);
    EXPECT_NEAR(rod_energy(pts, false, YI), YI * kb * kb / (2 * l0), 1e-12) << phi;
  }
}

TEST(StraightRodBond, RingEnergyConvergesToTheContinuum) {
  // a ring of radius R stores pi YI / R; the discrete energy converges at second order
  const double R = 3.0, YI = 2.0, exact = M_PI * YI / R;
  double prev = 0;
  for (int n : {12, 24, 48}) {
    std::vector<Vec3> pts;
    for (int i = 0; i < n; ++i)
      pts.emplace_back(R * std::cos(2 * M_PI * i / n), R * std::sin(2 * M_PI * i / n), 0);
    // rest lengths are the chord lengths (add_chain takes the initial edge lengths)
    const double err = std::abs(rod_energy(pts, true, YI) - exact) / exact;
    if (prev > 0) {
      EXPECT_NEAR(prev / err, 4.0, 0.4) << n;
    }
    prev = err;
  }
  EXPECT_LT(prev, 4e-3);  // measured 3.6e-3 at n = 48
}

TEST(StraightRodBond, PlanarRodMatchesTheTwoDimensionalBendingSpring) {
  // for small turning angles YI |kb|^2 / l = 1/2 (YI / l0) zeta^2 + O(zeta^4)
  auto pts = wiggly_chain(10, 2, 8, 0.02);
  Simulation flat(2, 1);
  flat.add_chain("w", pts, 1.0, false);
  const double l0 = 1.0, YI = 60.0;
  flat.add_bond("bend2d", P({{"k", YI / l0}}));
  flat.compute_forces();
  // rest lengths differ slightly from 1 in a wiggly chain: compare within 5 %
  const double e2d = flat.potential_energy();
  const double e3d = rod_energy(pts, false, YI, 2);
  EXPECT_GT(e2d, 0.0);
  EXPECT_NEAR(e3d, e2d, 0.05 * e2d);
}

TEST(StraightRodBond, NodeEnergiesSumToTheEnergyAndAreAllocatedOnlyOnRequest) {
  auto pts = wiggly_chain(9, 3, 12, 0.4);
  Simulation plain(3, 1);
  plain.add_chain("r", pts, 1.0, false);
  plain.add_bond("rod/straight", P({{"YI", 2.0}}));
  EXPECT_EQ(plain.nodes().find<double>("bend.energy"), nullptr);
  Simulation sim(3, 1);
  sim.add_chain("r", pts, 1.0, false);
  sim.add_bond("rod/straight", P({{"YI", 2.0}, {"node_energy", true}}));
  sim.compute_forces();
  double sum = 0;
  for (double e : sim.nodes().find<double>("bend.energy")->values()) sum += e;
  EXPECT_NEAR(sum, sim.potential_energy(), 1e-12 * sum);
  EXPECT_EQ(sim.nodes().find<double>("bend.energy")->values().front(), 0.0);  // an end node
}

TEST(GyrationCompute, RingAndFilledSphereValues) {
  // a ring of radius R: R_g = R; uniform masses
  Simulation ring(3, 1);
  std::vector<Vec3> pts;
  for (int i = 0; i < 64; ++i)
    pts.emplace_back(2.0 + 3 * std::cos(2 * M_PI * i / 64), 3 * std::sin(2 * M_PI * i / 64), 1.0);
  ring.add_chain("r", pts, 1.0, true);
  ring.add_compute("g", "gyration", P({}));
  EXPECT_NEAR(ring.column("g.rg"), 3.0, 1e-12);
  // points filling a ball of radius 5 uniformly: R_g^2 = 3/5 R^2 (docs/models.md §5.4, the
  // limit of (4.60)); those outside 'inside' are left out
  Simulation ball(3, 1);
  std::vector<Vec3> b;
  for (double x = -7; x <= 7; x += 0.35)
    for (double y = -7; y <= 7; y += 0.35)
      for (double z = -7; z <= 7; z += 0.35) b.emplace_back(x, y, z);
  ball.add_chain("b", b, 1.0, false);
  ball.add_compute("g", "gyration", P({{"inside", 5.0}}));
  EXPECT_NEAR(ball.column("g.rg2"), 0.6 * 25.0, 0.02 * 15.0);
}
