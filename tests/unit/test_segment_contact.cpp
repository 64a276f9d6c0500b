// Unit tests of pair contact/segment (3D rods, docs/models.md §5.1) and of the
// segment closest-point routine it uses.
// Covers styles/pair/contact_segment.cpp.
#include <random>

#include "helpers.hpp"
#include "segment_geometry.hpp"

using namespace slender;
using namespace slender::test;

namespace {
double seg_dist(const Vec3& p1, const Vec3& q1, const Vec3& p2, const Vec3& q2, double s,
                double t) {
  return ((p1 + s * (q1 - p1)) - (p2 + t * (q2 - p2))).norm();
}
// brute force: a fine grid, then a local refinement
double brute_dist(const Vec3& p1, const Vec3& q1, const Vec3& p2, const Vec3& q2) {
  double best = 1e300, bs = 0, bt = 0;
  const int n = 200;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      const double d = seg_dist(p1, q1, p2, q2, double(i) / n, double(j) / n);
      if (d < best) best = d, bs = double(i) / n, bt = double(j) / n;
    }
  for (double h = 1.0 / n; h > 1e-9; h *= 0.5)
    for (int k = 0; k < 20; ++k)
      for (int di = -1; di <= 1; ++di)
        for (int dj = -1; dj <= 1; ++dj) {
          const double s = std::clamp(bs + di * h, 0.0, 1.0), t = std::clamp(bt + dj * h, 0.0, 1.0);
          const double d = seg_dist(p1, q1, p2, q2, s, t);
          if (d < best) best = d, bs = s, bt = t;
        }
  return best;
}

// two straight rods of n nodes (spacing 1): one along x, one along `dir`
// through `centre`
std::unique_ptr<Simulation> two_rods(const Vec3& centre, const Vec3& dir, int n = 5) {
  auto sim = std::make_unique<Simulation>(3, 1);
  sim->verbose = false;
  std::vector<Vec3> a, b;
  for (int i = 0; i < n; ++i) {
    a.emplace_back(i - 0.5 * (n - 1), 0, 0);
    b.push_back(centre + (i - 0.5 * (n - 1)) * dir.normalized());
  }
  sim->add_chain("a", a, 1.0, false);
  sim->add_chain("b", b, 1.0, false);
  return sim;
}
}  // namespace

TEST(SegmentGeometry, ClosestPointsMatchBruteForce) {
  std::mt19937 g(5);
  std::uniform_real_distribution<double> u(-1, 1);
  auto rnd = [&] { return Vec3(u(g), u(g), u(g)); };
  for (int k = 0; k < 200; ++k) {
    Vec3 p1 = rnd(), q1 = rnd(), p2 = rnd(), q2 = rnd();
    if (k % 4 == 1) q2 = p2 + 0.7 * (q1 - p1);                 // parallel
    if (k % 4 == 2) q2 = p2 + 0.7 * (q1 - p1) + 1e-9 * rnd();  // nearly parallel
    if (k % 8 == 3) q1 = p1;                                   // a point
    double s, t;
    closest_points(p1, q1, p2, q2, s, t);
    ASSERT_GE(s, 0.0);
    ASSERT_LE(s, 1.0);
    ASSERT_GE(t, 0.0);
    ASSERT_LE(t, 1.0);
    EXPECT_NEAR(seg_dist(p1, q1, p2, q2, s, t), brute_dist(p1, q1, p2, q2), 1e-7) << k;
  }
  // side by side: the middle of the overlap
  double s, t;
  closest_points(Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(1, 1, 0), Vec3(3, 1, 0), s, t);
  EXPECT_NEAR(s, 0.75, 1e-12);
  EXPECT_NEAR(t, 0.25, 1e-12);
}

TEST(SegmentContactPair, NormalForceIsMinusTheEnergyGradient) {
  // crossing rods, and nearly parallel ones, pressed into each other
  for (const Vec3& dir : {Vec3(0.3, 1, 0.2), Vec3(1, 0.05, 0.02)}) {
    auto sim = two_rods(Vec3(0.13, 0.21, 1.6), dir);
    sim->add_pair("contact/segment", P({{"radius", 1.0}, {"youngs_modulus", 1000.0}}));
    sim->compute_forces();
    EXPECT_GT(sim->pairs()[0]->value("contacts"), 0.0);
    EXPECT_LT(fd_force_error(*sim, 1e-7), 1e-5);
  }
}

TEST(SegmentContactPair, HertzCylinderStiffnessFromTheRestLengths) {
  // one crossing at overlap delta: F = E* delta, E* = 2 pi Y (l1 + l2) / (8 (1 - nu^2))
  auto sim = two_rods(Vec3(0, 0, 1.9), Vec3(0, 1, 0), 2);
  sim->add_pair("contact/segment", P({{"radius", 1.0}, {"youngs_modulus", 1000.0}}));
  sim->compute_forces();
  const double estar = 2 * M_PI * 1000.0 * 2.0 / (8 * (1 - 0.33 * 0.33));
  Vec3 fa = sim->nodes().f[0] + sim->nodes().f[1];
  EXPECT_NEAR(fa.z(), -estar * 0.1, 1e-9 * estar);
  EXPECT_NEAR(fa.x(), 0.0, 1e-12);
  // split evenly between the nodes of each segment (the crossing is at both middles)
  EXPECT_NEAR(sim->nodes().f[0].z(), sim->nodes().f[1].z(), 1e-12);
  EXPECT_NEAR(sim->potential_energy(), 0.5 * estar * 0.01, 1e-9 * estar);
}

TEST(SegmentContactPair, ConservesMomentumWithFrictionAndDamping) {
  auto sim = two_rods(Vec3(0.1, 0.2, 1.7), Vec3(0.4, 1, 0.3), 6);
  sim->add_pair("contact/segment", P({{"radius", 1.0},
                                      {"youngs_modulus", 1000.0},
                                      {"damping", 5.0},
                                      {"mu_static", 0.2},
                                      {"mu_dynamic", 0.18}}));
  std::mt19937 g(2);
  std::uniform_real_distribution<double> u(-1, 1);
  for (auto& v : sim->nodes().v) v = Vec3(u(g), u(g), u(g));
  sim->dt = 1e-3;
  for (int k = 0; k < 3; ++k) {
    sim->compute_forces();
    Vec3 F = Vec3::Zero();
    double fabs = 0;
    for (auto& f : sim->nodes().f) F += f, fabs += f.norm();
    EXPECT_GT(fabs, 1.0);
    EXPECT_LT(F.norm(), 1e-12 * fabs);
  }
}

TEST(SegmentContactPair, ChainNeighboursAreExcludedAndListsMatchBruteForce) {
  // a straight rod touches nothing; a coil's turns touch each other
  Simulation straight(3, 1);
  std::vector<Vec3> line;
  for (int i = 0; i < 20; ++i) line.emplace_back(0.5 * i, 0, 0);  // l0 = a / 2
  straight.add_chain("r", line, 1.0, false);
  straight.add_pair("contact/segment", P({{"radius", 1.0}, {"stiffness", 100.0}}));
  straight.compute_forces();
  EXPECT_EQ(straight.pairs()[0]->value("contacts"), 0.0);

  // random short rods in a box: the cell list finds every touching pair
  Simulation box(3, 1);
  std::mt19937 g(9);
  std::uniform_real_distribution<double> u(0, 12);
  std::vector<std::array<Vec3, 2>> segs;
  for (int c = 0; c < 60; ++c) {
    const Vec3 p(u(g), u(g), u(g));
    Vec3 d(u(g) - 6, u(g) - 6, u(g) - 6);
    d = 1.5 * d.normalized();
    std::string name = "c";
    name += std::to_string(c);
    box.add_chain(name, {p, p + d}, 1.0, false);
    segs.push_back({p, p + d});
  }
  box.add_pair("contact/segment", P({{"radius", 0.5}, {"stiffness", 100.0}, {"skin", 0.3}}));
  box.compute_forces();
  int brute = 0;
  for (size_t i = 0; i < segs.size(); ++i)
    for (size_t j = i + 1; j < segs.size(); ++j) {
      double s, t;
      closest_points(segs[i][0], segs[i][1], segs[j][0], segs[j][1], s, t);
      if (seg_dist(segs[i][0], segs[i][1], segs[j][0], segs[j][1], s, t) < 1.0) ++brute;
    }
  EXPECT_GT(brute, 5);
  EXPECT_EQ(box.pairs()[0]->value("contacts"), brute);
}

TEST(SegmentContactPair, CrossingRodsDoNotPassThroughEachOther) {
  // rod b falls onto rod a (clamped) at speeds up to a tenth of the bar wave speed
  for (double speed : {0.1, 1.0, 3.0}) {
    auto sim = two_rods(Vec3(0, 0, 2.5), Vec3(0, 1, 0), 7);
    sim->add_bond("spring", P({{"k", 3141.6}}));
    sim->add_bond("rod/straight", P({{"YI", 785.4}}));
    sim->add_pair("contact/segment", P({{"radius", 1.0}, {"youngs_modulus", 1000.0}}));
    sim->add_fix("hold", "clamp", P({{"group", std::string("a")}}));
    for (int i = 7; i < 14; ++i) sim->nodes().v[i] = Vec3(0, 0, -speed);
    sim->set_integrator("verlet", P({{"dt", 0.002}}));
    double zmin = 1e300;
    sim->run(RunOptions{static_cast<long>(4.0 / (speed * 0.002)), 10, [&](Simulation& s) {
                          zmin = std::min(zmin, s.nodes().x[10].z());
                          return false;
                        }});
    EXPECT_GT(zmin, 1.0) << "speed " << speed;  // never deeper than half the radius sum
    EXPECT_GT(sim->nodes().v[10].z(), 0.0) << "bounced back";
  }
}

TEST(SegmentContactPair, StickSlipTransitionAtTheStaticFrictionRatio) {
  // a short rod pressed with N onto a clamped one and pulled along it with T:
  // it stays for T / N < mu_s = 0.2 and slides for T / N > mu_s
  // (at 0.19 the small jolt at the end of the ramp starts a slip that mu_d = 0.18 cannot stop)
  for (double ratio : {0.15, 0.18, 0.21, 0.25}) {
    Simulation sim(3, 1);
    sim.verbose = false;
    std::vector<Vec3> bottom;
    for (int i = 0; i < 21; ++i) bottom.emplace_back(i - 10.0, 0, 0);
    sim.add_chain("bottom", bottom, 1.0, false);
    sim.add_chain("top", {Vec3(0, -0.5, 1.95), Vec3(0, 0.5, 1.95)}, 1.0, false);
    sim.add_pair("contact/segment", P({{"radius", 1.0},
                                       {"youngs_modulus", 1000.0},
                                       {"damping", 20.0},
                                       {"mu_static", 0.2},
                                       {"mu_dynamic", 0.18}}));
    sim.add_fix("hold", "clamp", P({{"group", std::string("bottom")}}));
    const double N = 100.0;
    sim.add_fix("press", "force/constant",
                P({{"group", std::string("top")}, {"force", std::vector<double>{0, 0, -0.5 * N}}}));
    sim.add_fix("drag", "damping/viscous", P({{"gamma", 2.0}, {"group", std::string("top")}}));
    sim.set_integrator("verlet", P({{"dt", 1e-3}}));
    sim.run(RunOptions{10000, 0, {}});  // settle under the normal load first
    const double x0 = sim.nodes().x[21].x();
    // a slow ramp: a sudden pull would overshoot the stick spring to twice the load
    const double T = 0.5 * ratio * N, ramp = 10.0;
    sim.add_fix("pull", "force/constant",
                P({{"group", std::string("top")},
                   {"force", std::vector<double>{0, 0, 0}},
                   {"rate", std::vector<double>{T / ramp, 0, 0}}}));
    sim.run(RunOptions{10000, 0, {}});
    sim.fix("pull").modify(P({{"group", std::string("top")},
                              {"force", std::vector<double>{T, 0, 0}},
                              {"rate", std::vector<double>{0, 0, 0}}}));
    const double x10 = sim.nodes().x[21].x() - x0;
    sim.run(RunOptions{10000, 0, {}});
    const double moved = sim.nodes().x[21].x() - x0 - x10;
    if (ratio < 0.2) {
      EXPECT_LT(std::abs(moved), 1e-3) << "T/N = " << ratio << " must stick";
      EXPECT_LT(std::abs(x10), 0.2) << "only the stick spring stretches";
    } else {
      EXPECT_GT(moved, 0.05) << "T/N = " << ratio << " must slide";
    }
  }
}
