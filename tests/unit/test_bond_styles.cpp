// Unit tests of the bond styles: spring and bend2d, and the 2D hinge angle.
#include <cmath>
#include <random>

#include "helpers.hpp"
#include "hinge2d.hpp"

using namespace slender;
using namespace slender::test;

TEST(SpringBond, ForceMatchesEnergyGradient) {
  Simulation sim(3, 1);
  sim.add_chain("w", wiggly_chain(8, 3, 11), 1.0, false);
  // stretch the chain by 7% so every spring carries load
  for (auto& x : sim.nodes().x) x *= 1.07;
  sim.add_bond("spring", P({{"k", 250.0}}));
  EXPECT_LT(fd_force_error(sim), 1e-6);
  EXPECT_GT(sim.potential_energy(), 0.0);
}

TEST(SpringBond, ClosedChainAndExactValue) {
  Simulation sim(2, 1);
  sim.add_chain("ring", {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}, 1.0, true);
  auto& x = sim.nodes().x;
  x[1] = Vec3(1.5, 0, 0);  // first edge stretched by 0.5, third edge (0,1)->(0,0) unchanged
  sim.add_bond("spring", P({{"k", 100.0}}));
  sim.compute_forces();
  // edge 0: 0.5 stretch; edge 1: |(0,1)-(1.5,0)| - sqrt(2)
  const double s1 = std::sqrt(1.5 * 1.5 + 1.0) - std::sqrt(2.0);
  EXPECT_NEAR(sim.energies().at("stretch"), 0.5 * 100 * (0.25 + s1 * s1), 1e-12);
  EXPECT_NEAR(sim.nodes().f[0].x(), 100 * 0.5, 1e-12);  // pulled towards node 1
  EXPECT_LT(fd_force_error(sim), 1e-6);
}

TEST(SpringBond, RejectsBadParameters) {
  Simulation sim(2, 1);
  sim.add_chain("w", wiggly_chain(3, 2, 1), 1.0, false);
  EXPECT_THROW(sim.add_bond("spring", P({{"k", -1.0}})), InputError);
  EXPECT_THROW(sim.add_bond("spring", P({{"k", 1.0}, {"kk", 2.0}})), InputError);
  EXPECT_THROW(sim.add_bond("spring", P({{"k", std::string("stiff")}})), InputError);
  EXPECT_THROW(sim.add_bond("spring", P({})), InputError);
  EXPECT_THROW(
      sim.add_bond("spring", P({{"k", 1.0}, {"chains", std::vector<std::string>{"nope"}}})),
      InputError);
}

TEST(Bend2dBond, ForceMatchesEnergyGradient) {
  Simulation sim(2, 1);
  sim.add_chain("w", wiggly_chain(9, 2, 5, 0.4), 1.0, false);
  sim.add_bond("bend2d", P({{"k", 60.0}}));
  EXPECT_LT(fd_force_error(sim), 1e-6);
}

TEST(Bend2dBond, SignedAngleAndMoment) {
  Simulation sim(2, 1);
  // a left turn by 30 degrees at the middle node
  const double a = M_PI / 6;
  sim.add_chain("w", {Vec3(-1, 0, 0), Vec3(0, 0, 0), Vec3(std::cos(a), std::sin(a), 0)}, 1.0,
                false);
  sim.add_bond("bend2d", P({{"k", 60.0}}));
  sim.compute_forces();
  EXPECT_NEAR(sim.energies().at("bend"), 0.5 * 60 * a * a, 1e-12);
  // the moment k zeta tries to straighten the wire: the tip is pushed clockwise
  const Vec3 tip = sim.nodes().x[2];
  const Vec3 f = sim.nodes().f[2];
  EXPECT_LT(tip.x() * f.y() - tip.y() * f.x(), 0.0);
  EXPECT_NEAR(f.norm(), 60 * a / 1.0, 1e-12);  // |F| = m / |e|
  // forces sum to zero and produce no net torque
  Vec3 sum = Vec3::Zero();
  double torque = 0;
  for (int i = 0; i < 3; ++i) {
    sum += sim.nodes().f[i];
    torque +=
        sim.nodes().x[i].x() * sim.nodes().f[i].y() - sim.nodes().x[i].y() * sim.nodes().f[i].x();
  }
  EXPECT_LT(sum.norm(), 1e-12);
  EXPECT_NEAR(torque, 0.0, 1e-12);
}

TEST(Bend2dBond, ClosedRingIsForceFreeWhenRegular) {
  Simulation sim(2, 1);
  std::vector<Vec3> pts;
  for (int i = 0; i < 12; ++i)
    pts.emplace_back(std::cos(2 * M_PI * i / 12), std::sin(2 * M_PI * i / 12), 0);
  sim.add_chain("ring", pts, 1.0, true);
  sim.add_bond("bend2d", P({{"k", 5.0}}));
  sim.compute_forces();
  // every hinge turns by 2 pi / 12, all in the same sense
  EXPECT_NEAR(sim.energies().at("bend"), 12 * 0.5 * 5.0 * std::pow(2 * M_PI / 12, 2), 1e-10);
  // equal turning angles minimise sum zeta^2 at fixed total turning 2 pi
  EXPECT_LT(sim.max_force(), 1e-10);
  sim.nodes().x[3] += Vec3(0.05, -0.02, 0);
  EXPECT_LT(fd_force_error(sim), 1e-6);
}

TEST(BendStyles, NodeFieldsHoldEachHingesCurvatureAndEnergy) {
  // an arc of radius 4 (12 nodes, chord l0 apart) then moved a little: each interior node
  // holds zeta / l0 and its share of the energy, the ends 0; without node_fields nothing
  // is allocated
  for (const std::string style : {"bend2d", "bend2d/hysteresis"}) {
    Simulation sim(2, 1);
    std::vector<Vec3> pts;
    for (int i = 0; i < 12; ++i) pts.emplace_back(4 * std::cos(0.2 * i), 4 * std::sin(0.2 * i), 0);
    sim.add_chain("arc", pts, 1.0, false);
    RawParams p = P({{"k", 5.0}, {"node_fields", true}});
    if (style != "bend2d") p["yield_curvature"] = 0.1;  // the arc (1/4) yields
    sim.add_bond(style, p);
    sim.nodes().x[5] += Vec3(0.03, -0.02, 0);
    sim.compute_forces();
    const auto& kappa = sim.nodes().find<double>("bend.curvature")->values();
    const auto& energy = sim.nodes().find<double>("bend.energy")->values();
    const double l0 = 2 * 4 * std::sin(0.1);
    double sum = 0;
    for (int i = 0; i < 12; ++i) {
      if (i == 0 || i == 11) {
        EXPECT_EQ(kappa[i], 0.0) << style;
        EXPECT_EQ(energy[i], 0.0);
        continue;
      }
      const Hinge2d g(sim.nodes().x[i - 1], sim.nodes().x[i], sim.nodes().x[i + 1]);
      EXPECT_NEAR(kappa[i], g.zeta / l0, 1e-12) << style << " node " << i;
      if (i < 4 || i > 6) {
        EXPECT_NEAR(kappa[i], 0.2 / l0, 1e-12);  // undisturbed: nearly 1/4
      }
      EXPECT_GT(energy[i], 0.0);
      sum += energy[i];
    }
    EXPECT_NEAR(sum, sim.energies().at("bend"), 1e-12 * sum) << style;
    Simulation plain(2, 1);
    plain.add_chain("arc", pts, 1.0, false);
    p.erase("node_fields");
    plain.add_bond(style, p);
    plain.compute_forces();
    EXPECT_FALSE(plain.nodes().has("bend.curvature"));
    EXPECT_FALSE(plain.nodes().has("bend.energy"));
  }
}

TEST(Bend2dBond, Needs2D) {
  Simulation sim(3, 1);
  sim.add_chain("w", wiggly_chain(3, 3, 1), 1.0, false);
  EXPECT_THROW(sim.add_bond("bend2d", P({{"k", 1.0}})), InputError);
}

TEST(BondStyles, StiffestModeMatchesChainDispersion) {
  Simulation sim(2, 1);
  sim.add_chain("w", wiggly_chain(5, 2, 1, 0.0), 2.0, false);
  sim.add_bond("spring", P({{"k", 800.0}}));
  EXPECT_NEAR(sim.omega_max(), 2 * std::sqrt(800.0 / 2.0), 1e-12);
  sim.add_bond("bend2d", P({{"k", 50.0}}));
  const double wb = 4 * std::sqrt(50.0 / 2.0);
  EXPECT_NEAR(sim.omega_max(), std::sqrt(4 * 800.0 / 2.0 + wb * wb), 1e-9);
}

TEST(BendStyles, DashpotDissipatesGammaTimesTurningRateSquared) {
  // power of the dashpot forces: sum F . v = -gamma (dzeta/dt)^2 per hinge
  for (const char* style : {"bend2d", "bend2d/hysteresis"}) {
    auto make = [&](double gamma) {
      auto s = std::make_unique<Simulation>(2, 1);
      s->add_chain("w", {Vec3(-1, 0, 0), Vec3(0, 0, 0), Vec3(0.8, 0.6, 0)}, 1.0, false);
      RawParams p = P({{"k", 60.0}, {"damping", gamma}});
      if (std::string(style) == "bend2d/hysteresis") p["yield_curvature"] = 4.0;
      s->add_bond(style, p);
      s->nodes().v[0] = Vec3(0.1, 0.3, 0);
      s->nodes().v[1] = Vec3(-0.2, 0.1, 0);
      s->nodes().v[2] = Vec3(0.4, -0.5, 0);
      s->compute_forces();
      return s;
    };
    auto with = make(2.0), without = make(0.0);
    double power = 0.0;
    for (int i = 0; i < 3; ++i)
      power += (with->nodes().f[i] - without->nodes().f[i]).dot(with->nodes().v[i]);
    // dzeta/dt by finite differences of the turning angle along the velocities
    auto angle = [](const std::vector<Vec3>& x) {
      const Vec3 e0 = x[1] - x[0], e1 = x[2] - x[1];
      return std::atan2(e0.x() * e1.y() - e0.y() * e1.x(), e0.dot(e1));
    };
    std::vector<Vec3> xp = with->nodes().x, xm = xp;
    const double h = 1e-6;
    for (int i = 0; i < 3; ++i) {
      xp[i] += h * with->nodes().v[i];
      xm[i] -= h * with->nodes().v[i];
    }
    const double rate = (angle(xp) - angle(xm)) / (2 * h);
    EXPECT_NEAR(power, -2.0 * rate * rate, 1e-6) << style;
    EXPECT_LT(power, 0.0) << style;
    // the dashpot conserves momentum
    Vec3 sum = Vec3::Zero();
    for (int i = 0; i < 3; ++i) sum += with->nodes().f[i] - without->nodes().f[i];
    EXPECT_LT(sum.norm(), 1e-12) << style;
  }
}

// bond "damper" (styles/bond/damper.cpp): internal damping between neighbours.
TEST(DamperBond, LeavesRigidMotionAndSlidingFreeAndDissipates) {
  Simulation sim(3, 1);
  sim.add_chain("w", wiggly_chain(9, 3, 5), 1.0, false);
  sim.add_bond("damper", P({{"gamma", 2.0}}));
  auto& v = sim.nodes().v;
  // a rigid translation: no force
  for (auto& vi : v) vi = Vec3(0.3, -0.2, 0.7);
  sim.compute_forces();
  for (auto& f : sim.nodes().f) EXPECT_LT(f.norm(), 1e-14);
  EXPECT_EQ(sim.potential_energy(), 0.0);
  // any motion: the forces sum to zero and their power is -gamma sum |v_a - v_b|^2
  std::mt19937 g(3);
  std::normal_distribution<double> n(0, 1);
  for (auto& vi : v) vi = Vec3(n(g), n(g), n(g));
  sim.compute_forces();
  Vec3 total = Vec3::Zero();
  double power = 0.0, expected = 0.0;
  for (size_t i = 0; i < v.size(); ++i) {
    total += sim.nodes().f[i];
    power += sim.nodes().f[i].dot(v[i]);
  }
  for (size_t i = 0; i + 1 < v.size(); ++i) expected -= 2.0 * (v[i] - v[i + 1]).squaredNorm();
  EXPECT_LT(total.norm(), 1e-12);
  EXPECT_NEAR(power, expected, 1e-12 * std::abs(expected));
}

TEST(DamperBond, StraightChainSlidingAlongItselfFeelsNoForce) {
  // unlike damping/viscous, which pulls gamma v back on every node
  Simulation sim(3, 1);
  std::vector<Vec3> pts;
  for (int i = 0; i < 6; ++i) pts.emplace_back(0, 0, -1.0 * i);
  sim.add_chain("r", pts, 1.0, false);
  sim.add_bond("damper", P({{"gamma", 5.0}}));
  for (auto& vi : sim.nodes().v) vi = Vec3(0, 0, -0.03);
  sim.compute_forces();
  for (auto& f : sim.nodes().f) EXPECT_EQ(f.norm(), 0.0);
  Simulation drag(3, 1);
  drag.add_chain("r", pts, 1.0, false);
  drag.add_fix("drag", "damping/viscous", P({{"gamma", 5.0}}));
  for (auto& vi : drag.nodes().v) vi = Vec3(0, 0, -0.03);
  drag.compute_forces();
  Vec3 sum = Vec3::Zero();
  for (auto& f : drag.nodes().f) sum += f;
  EXPECT_NEAR(sum.z(), 6 * 5.0 * 0.03, 1e-12);  // grows with the chain's length
}

// The hinge angle's series branches (|turn| up to 45 degrees: the series to atan 0.2, the
// reduced arguments beyond) agree with std::atan2 to a few units in the last place over
// the whole range and at its edges; outside it is std::atan2 itself.
TEST(HingeAngle, SeriesBranchAgreesWithAtan2ToRounding) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> ratio(-1.0, 1.0), scale(-8.0, 8.0);
  double worst_ulps = 0.0;
  for (int i = 0; i < 200000; ++i) {
    // ratios spread over many decades, the largest turns included
    const double t = i % 4 == 0 ? ratio(rng) : ratio(rng) * std::pow(10.0, -8.0 * (i % 4) / 3.0);
    const double d = std::pow(10.0, scale(rng)), c = t * d;
    const double ref = std::atan2(c, d);
    const double ulp = std::nextafter(std::abs(ref), INFINITY) - std::abs(ref);
    worst_ulps = std::max(worst_ulps, std::abs(hinge_angle(c, d) - ref) / ulp);
  }
  EXPECT_LE(worst_ulps, 4.0);
  for (double c : {0.2, -0.2, 0.2000001, 0.6, 0.6000001, -0.6, 1.0, -1.0, 1.0000001, -5.0, 1e-300})
    for (double d : {1.0, -1.0, 0.0}) EXPECT_NEAR(hinge_angle(c, d), std::atan2(c, d), 3e-16);
  EXPECT_EQ(hinge_angle(0.0, 1.0), 0.0);
  EXPECT_EQ(hinge_angle(1.3, 1.0), std::atan2(1.3, 1.0));  // outside the branch: atan2 itself
  EXPECT_EQ(hinge_angle(0.3, -1.0), std::atan2(0.3, -1.0));
}
