// Unit tests of bend2d/hysteresis (docs/models.md §2.2): one hinge driven through
// Covers styles/bond/bend_hysteresis.cpp.
// curvature histories, and the elastic limit against bend2d.
#include <cmath>
#include <random>

#include "helpers.hpp"

using namespace slender;
using namespace slender::test;

namespace {

// Three nodes, rest lengths 1: the hinge's curvature is its turning angle.
struct Hinge {
  Simulation sim{2, 1};
  explicit Hinge(RawParams p) {
    sim.add_chain("w", {Vec3(-1, 0, 0), Vec3(0, 0, 0), Vec3(1, 0, 0)}, 1.0, false);
    sim.add_bond("bend2d/hysteresis", p);
  }
  // Sets the curvature and returns the moment, read back from the force on the tip.
  double moment(double kappa) {
    sim.nodes().x[2] = Vec3(std::cos(kappa), std::sin(kappa), 0);
    sim.compute_forces();
    const Vec3& f = sim.nodes().f[2];
    return -(f.x() * -std::sin(kappa) + f.y() * std::cos(kappa));
  }
  double kpl() { return (*sim.nodes().find<double>("bend.plastic_curvature"))[1]; }
  double value(const std::string& k) { return sim.bonds()[0]->value(k); }
};

// K_e = 60, kappa_y = 0.04, K_h = 3, delta = 0.02
RawParams law(bool guard = true) {
  return P({{"k", 60.0},
            {"yield_curvature", 0.04},
            {"hardening_ratio", 0.05},
            {"transition", 0.02},
            {"guard", guard}});
}

}  // namespace

TEST(BendHysteresisBond, FirstLoadingIsC1WithElasticAndHardeningSlopes) {
  Hinge h(law());
  const double dk = 1e-5;
  double prev_m = h.moment(0.0), prev_slope = 0.0, max_jump = 0.0;
  std::vector<double> slope;
  for (int i = 1; i <= 12000; ++i) {  // up to kappa = 0.12
    const double m = h.moment(i * dk);
    const double s = (m - prev_m) / dk;
    if (i > 1) max_jump = std::max(max_jump, std::abs(s - prev_slope));
    slope.push_back(s);
    prev_m = m;
    prev_slope = s;
  }
  EXPECT_NEAR(slope[100], 60.0, 1e-6);   // linear elastic zone (kappa = 0.001)
  EXPECT_NEAR(slope.back(), 3.0, 1e-6);  // plastic flow: hardening slope K_h
  // the slope changes by (K_e - K_h)/delta dk ~ 0.03 per step in the transition;
  // a kink would jump by up to K_e - K_h = 57
  EXPECT_LT(max_jump, 0.05);
  // M at kappa = 0.1: g(x_p) + K_h kappa_pl with kappa_pl = 0.1 - 0.04
  Hinge h2(law());
  for (int i = 1; i <= 100; ++i) h2.moment(0.001 * i);
  EXPECT_NEAR(h2.kpl(), 0.06, 1e-12);
  EXPECT_NEAR(h2.moment(0.1), 60 * 0.04 - 57.0 / 0.04 * 0.02 * 0.02 + 3 * 0.06, 1e-12);
}

TEST(BendHysteresisBond, UnloadingIsElasticAndLeavesTheResidualCurvature) {
  Hinge h(law());
  for (int i = 1; i <= 100; ++i) h.moment(0.001 * i);  // load to kappa = 0.1
  const double kpl = h.kpl();
  // unloading first retraces the reversible transition (slope K_h rising to K_e,
  // no kink), then is linear with slope K_e; no further flow
  EXPECT_NEAR((h.moment(0.1) - h.moment(0.0999)) / 1e-4, 3.0, 0.2);
  for (double k = 0.0999; k > 0.08; k -= 1e-4) h.moment(k);
  const double m1 = h.moment(0.0701), m2 = h.moment(0.0700);
  EXPECT_NEAR((m1 - m2) / 1e-4, 60.0, 1e-6);
  // residual curvature at M = 0: kappa_pl (1 - K_h/K_e) (docs/models.md §2.2)
  const double res = kpl * (1 - 0.05);
  for (double k = 0.0700; k > res; k -= 1e-4) h.moment(k);
  EXPECT_NEAR(h.moment(res), 0.0, 1e-12);
  EXPECT_EQ(h.kpl(), kpl);
  // re-loading follows the elastic slope up to the moved elastic range
  EXPECT_NEAR((h.moment(res + 0.01) - h.moment(res)) / 0.01, 60.0, 1e-9);
}

TEST(BendHysteresisBond, ReverseLoadingYieldsAtTheMovedThreshold) {
  Hinge h(law());
  for (int i = 1; i <= 100; ++i) h.moment(0.001 * i);  // kappa_pl = 0.06
  // kinematic hardening: the elastic range [-kappa_y, kappa_y] moved with kappa_pl,
  // so reverse flow starts at kappa = kappa_pl - kappa_y = 0.02, not at -0.04
  for (int i = 99; i >= 21; --i) h.moment(0.001 * i);
  EXPECT_NEAR(h.kpl(), 0.06, 1e-12);
  for (int i = 20; i >= -100; --i) h.moment(0.001 * i);
  EXPECT_LT(h.kpl(), 0.06 - 0.05);
  EXPECT_LT(h.moment(-0.1), 0.0);
}

TEST(BendHysteresisBond, DissipationIsNeverNegative) {
  std::mt19937 g(4);
  std::uniform_real_distribution<double> u(-0.15, 0.15);
  for (int trial = 0; trial < 20; ++trial) {
    Hinge h(law(trial % 2 == 0));
    double k = 0.0;
    double last = 0.0;
    for (int leg = 0; leg < 6; ++leg) {
      const double target = u(g);
      const int n = 400;
      for (int i = 1; i <= n; ++i) {
        h.moment(k + (target - k) * i / n);
        const double d = h.value("dissipated");
        EXPECT_GE(d, last - 1e-9);  // dissipation only grows
        last = std::max(last, d);
      }
      k = target;
    }
    // close the cycle: back to the start
    for (int i = 1; i <= 400; ++i) h.moment(k * (1.0 - i / 400.0));
    EXPECT_GT(h.value("dissipated"), 0.0);
  }
}

TEST(BendHysteresisBond, EnergyBalanceAgainstIndependentQuadrature) {
  // work = integral of M dkappa along the path, by the test's own trapezoid rule on
  // a fine path; it must equal the change of recoverable energy plus dissipation
  std::mt19937 g(8);
  std::uniform_real_distribution<double> u(-0.2, 0.2);
  Hinge h(law());
  double k = 0.0, m_prev = h.moment(0.0), work = 0.0;
  for (int leg = 0; leg < 8; ++leg) {
    const double target = u(g);
    const int n = 20000;
    for (int i = 1; i <= n; ++i) {
      const double kn = k + (target - k) * i / n;
      const double kp = k + (target - k) * (i - 1) / n;
      const double m = h.moment(kn);
      work += 0.5 * (m + m_prev) * (kn - kp);
      m_prev = m;
    }
    k = target;
  }
  EXPECT_NEAR(h.value("work"), work, 1e-6 * std::abs(work));
  EXPECT_GT(h.value("dissipated"), 0.1 * work);
}

TEST(BendHysteresisBond, GuardKeepsZeroMomentInTheLinearZone) {
  // strongly hardened: without the guard, unloading would yield backwards
  // before the moment reaches zero
  for (bool guard : {true, false}) {
    Hinge h(law(guard));
    for (int i = 1; i <= 1000; ++i) h.moment(0.001 * i);  // kappa = 1, kappa_pl ~ 0.96
    const double kpl = h.kpl();
    double k = 1.0;
    while (h.moment(k) > 0) k -= 1e-4;
    if (guard)
      EXPECT_EQ(h.kpl(), kpl);
    else
      EXPECT_LT(h.kpl(), kpl);
  }
}

TEST(BendHysteresisBond, ElasticLimitReproducesBend2dExactly) {
  Simulation a(2, 1), b(2, 1);
  auto pts = wiggly_chain(12, 2, 6, 0.4);
  a.add_chain("w", pts, 1.0, false);
  b.add_chain("w", pts, 1.0, false);
  a.add_bond("bend2d", P({{"k", 60.0}}));
  b.add_bond("bend2d/hysteresis", P({{"k", 60.0}, {"yield_curvature", 4.0}}));
  a.compute_forces();
  b.compute_forces();
  for (size_t i = 0; i < pts.size(); ++i)
    EXPECT_LT((a.nodes().f[i] - b.nodes().f[i]).norm(), 1e-12);
  EXPECT_NEAR(a.potential_energy(), b.potential_energy(), 1e-12);
  EXPECT_LT(fd_force_error(b), 1e-6);  // conservative in the elastic range
  EXPECT_NEAR(b.bonds()[0]->value("dissipated"), 0.0, 1e-9);
  EXPECT_EQ(b.omega_max(), a.omega_max());
}

TEST(BendHysteresisBond, StateOnlyInScenesThatUseIt) {
  Simulation a(2, 1);
  a.add_chain("w", wiggly_chain(5, 2, 1), 1.0, false);
  a.add_bond("bend2d", P({{"k", 1.0}}));
  EXPECT_FALSE(a.nodes().has("bend.plastic_curvature"));
  Simulation b(2, 3);
  b.add_chain("w", wiggly_chain(5, 2, 1), 1.0, false);
  b.add_bond("bend2d/hysteresis",
             P({{"k", 1.0}, {"yield_curvature", 0.02}, {"initial_plastic", 1e-3}}));
  auto* kpl = b.nodes().find<double>("bend.plastic_curvature");
  ASSERT_NE(kpl, nullptr);
  EXPECT_EQ((*kpl)[0], 0.0);  // chain ends carry no hinge
  EXPECT_NE((*kpl)[2], 0.0);  // seeded symmetry breaking
  EXPECT_LE(std::abs((*kpl)[2]), 1e-3);
  EXPECT_THROW(b.add_bond("bend2d/hysteresis",
                          P({{"k", 1.0}, {"yield_curvature", 0.02}, {"transition", 0.05}})),
               InputError);
}

// saturate = true, the literal reading of Alg. 1 (docs/models.md §2.2): the moment is g(x)
// alone, so once the node flows it stays at g(x_p) however far the hinge is bent; unloading
// is elastic from there and leaves the whole plastic curvature; the energy balance holds.
TEST(BendHysteresisBond, SaturatingLawPlateausAndBalancesItsEnergy) {
  RawParams p = law();
  p["saturate"] = true;
  Hinge h(p);
  const double plateau = 60 * 0.04 - 57.0 / 0.04 * 0.02 * 0.02;  // g(x_p), slope K_h there
  for (int i = 1; i <= 100; ++i) h.moment(0.001 * i);            // load to kappa = 0.1
  EXPECT_NEAR(h.kpl(), 0.06, 1e-12);
  EXPECT_NEAR(h.moment(0.1), plateau, 1e-12);
  for (int i = 101; i <= 300; ++i) h.moment(0.001 * i);  // on to 0.3: no growth
  EXPECT_NEAR(h.moment(0.3), plateau, 1e-12);
  EXPECT_NEAR(h.kpl(), 0.26, 1e-12);
  // the hardening law would have grown by K_h * 0.2 = 0.6 over the same path
  Hinge hard(law());
  for (int i = 1; i <= 300; ++i) hard.moment(0.001 * i);
  EXPECT_NEAR(hard.moment(0.3) - plateau, 3.0 * 0.26, 1e-12);
  // unloading to zero moment: elastic, at kappa = kappa_pl (no K_h kappa_pl to undo)
  EXPECT_NEAR(h.moment(0.26), 0.0, 1e-12);
  EXPECT_NEAR(h.kpl(), 0.26, 1e-12);
  // work = change of recoverable energy + dissipation along a random path (trapezoid rule)
  std::mt19937 g(8);
  std::uniform_real_distribution<double> u(-0.2, 0.2);
  Hinge w(p);
  double k = 0.0, m_prev = w.moment(0.0), work = 0.0;
  for (int leg = 0; leg < 8; ++leg) {
    const double target = u(g);
    const int n = 20000;
    for (int i = 1; i <= n; ++i) {
      const double kn = k + (target - k) * i / n;
      const double m = w.moment(kn);
      work += 0.5 * (m + m_prev) * (target - k) / n;
      m_prev = m;
    }
    k = target;
  }
  EXPECT_NEAR(w.value("work"), work, 1e-6 * std::abs(work));
  EXPECT_GT(w.value("dissipated"), 0.1 * work);
  // conservative in the elastic range: forces against the energy by finite differences
  Simulation s(2, 1);
  s.add_chain("w", wiggly_chain(12, 2, 6, 0.02), 1.0, false);
  RawParams q = P({{"k", 60.0}, {"yield_curvature", 0.5}, {"saturate", true}});
  s.add_bond("bend2d/hysteresis", q);
  s.compute_forces();
  EXPECT_LT(fd_force_error(s), 1e-6);
}
