// Unit tests of bond rod/cosserat (quaternion Cosserat rod, docs/models.md §4) and of
// the integration of its quaternions (generalised coordinates) by verlet and gear.
// Covers styles/bond/rod_cosserat.cpp.
#include <random>

#include "helpers.hpp"
#include "quaternion_rod.hpp"

using namespace slender;
using namespace slender::test;

namespace {
RawParams rod(double kbar2 = 0.0, double gamma_q = 0.0) {
  return P({{"YI", 2.0},
            {"GJ", 1.5},
            {"coupling", 50.0},
            {"rot_inertia", 0.1},
            {"rest_curvature", std::vector<double>{0.05, kbar2, -0.1}},
            {"rot_damping", gamma_q}});
}
double total_energy(Simulation& sim) {
  sim.compute_forces();
  return sim.potential_energy();
}
// A straight rod of 21 nodes 0.5 apart with kbar = (0, 1/R, 0): it curls into an arc of
// radius R.
void add_precurved_rod(Simulation& sim, double R, double rot_damping) {
  std::vector<Vec3> pts;
  for (int i = 0; i < 21; ++i) pts.emplace_back(0.5 * i, 0, 0);
  sim.add_chain("r", pts, 1.0, false);
  sim.add_bond("spring", P({{"k", 400.0}}));
  sim.add_bond("rod/cosserat", P({{"YI", 2.0},
                                  {"GJ", 1.5},
                                  {"coupling", 200.0},
                                  {"rot_inertia", 0.5},
                                  {"rest_curvature", std::vector<double>{0, 1 / R, 0}},
                                  {"rot_damping", rot_damping}}));
}

}  // namespace

TEST(CosseratRodBond, ForcesAndQuaternionForcesAreMinusTheEnergyGradient) {
  Simulation sim(3, 1);
  sim.add_chain("r", wiggly_chain(7, 3, 21, 0.3), 1.0, false);
  sim.add_bond("rod/cosserat", rod(0.2));
  sim.compute_forces();  // binds the frames
  auto& q = sim.coordinates("rod.q").q->values();
  std::mt19937 g(4);
  std::normal_distribution<double> n(0, 0.15);
  for (size_t i = 0; i + 1 < q.size(); ++i)
    q[i] = (q[i] + Vec4(n(g), n(g), n(g), n(g))).normalized();
  EXPECT_LT(fd_force_error(sim), 1e-6);
  // generalised forces along tangent directions of |q| = 1
  sim.compute_forces();
  const auto fq = sim.coordinates("rod.q").f->values();
  double fscale = 0;
  for (auto& v : fq) fscale = std::max(fscale, v.norm());
  const double h = 1e-6;
  for (size_t i = 0; i + 1 < q.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      Vec4 w(n(g), n(g), n(g), n(g));
      w -= w.dot(q[i]) * q[i];
      const Vec4 q0 = q[i];
      q[i] = q0 + h * w;
      const double ep = total_energy(sim);
      q[i] = q0 - h * w;
      const double em = total_energy(sim);
      q[i] = q0;
      EXPECT_NEAR(fq[i].dot(w), -(ep - em) / (2 * h), 1e-6 * fscale) << i;
      EXPECT_NEAR(fq[i].dot(q[i]), 0.0, 1e-12 * fscale);  // projected
    }
}

TEST(CosseratRodBond, StraightRodAtRestAndTwistActsOnFramesOnly) {
  Simulation sim(3, 1);
  std::vector<Vec3> pts;
  for (int i = 0; i < 8; ++i) pts.emplace_back(0.9 * i, 0.2 * i, -0.1 * i);
  sim.add_chain("r", pts, 1.0, false);
  sim.add_bond("rod/cosserat",
               P({{"YI", 2.0}, {"GJ", 1.5}, {"coupling", 50.0}, {"rot_inertia", 0.1}}));
  sim.compute_forces();
  EXPECT_NEAR(sim.potential_energy(), 0.0, 1e-20);
  for (auto& f : sim.nodes().f) EXPECT_LT(f.norm(), 1e-12);
  // twist the frames about the tangent, edge by edge: torsion energy, no force on
  // the straight centreline
  auto& q = sim.coordinates("rod.q").q->values();
  const double step = 0.1;
  for (int i = 0; i < 7; ++i)
    q[i] = qrod::mul(q[i], Vec4(std::cos(0.5 * step * i), 0, 0, std::sin(0.5 * step * i)));
  sim.compute_forces();
  const double l = std::sqrt(0.81 + 0.04 + 0.01);
  const double k3 = 2.0 / l * std::sin(0.5 * step);  // docs/models.md §4.3
  EXPECT_NEAR(sim.energies().at("twist"), 6 * 0.5 * l * 1.5 * k3 * k3, 1e-12);
  EXPECT_NEAR(sim.energies().at("bend"), 0.0, 1e-20);
  for (auto& f : sim.nodes().f) EXPECT_LT(f.norm(), 1e-10);
}

TEST(CosseratRodBond, RodWithRestCurvatureRelaxesToItsArc) {
  // a straight rod with kbar = (0, 1/R, 0) curls into an arc of radius R; the
  // chord of an arc of length L is 2 R sin(L / 2R)
  for (const char* integ : {"verlet", "gear"}) {
    Simulation sim(3, 1);
    sim.verbose = false;
    const double R = 4.0;
    add_precurved_rod(sim, R, 2.0);
    sim.add_fix("drag", "damping/viscous", P({{"gamma", 2.0}}));
    sim.set_integrator(integ, P({{"dt", std::string("auto")}}));
    // damped dynamics until the rod is at rest (Gear's stable step is the smaller)
    sim.run(RunOptions{600000, 1000,
                       [](Simulation& s) { return s.step > 5000 && s.kinetic_energy() < 1e-9; }});
    const double chord = (sim.nodes().x[20] - sim.nodes().x[0]).norm();
    EXPECT_NEAR(chord, 2 * R * std::sin(10.0 / (2 * R)), 0.02 * R) << integ;
    EXPECT_LT(sim.kinetic_energy(), 1e-6) << integ;
    for (auto& qi : sim.coordinates("rod.q").q->values()) EXPECT_NEAR(qi.norm(), 1.0, 1e-12);
  }
}

TEST(CosseratRodBond, MinimizeUntwistsFramesThatExertNoForceOnTheNodes) {
  // twisted frames on a straight rod: torsion energy but no force on the nodes, so a
  // minimiser that only looked at node forces would stop at once; FIRE must turn the
  // frames back to a common twist (free ends: zero energy)
  Simulation sim(3, 1);
  sim.verbose = false;
  std::vector<Vec3> pts;
  for (int i = 0; i < 8; ++i) pts.emplace_back(0.9 * i, 0.2 * i, -0.1 * i);
  sim.add_chain("r", pts, 1.0, false);
  sim.add_bond("spring", P({{"k", 400.0}}));
  sim.add_bond("rod/cosserat",
               P({{"YI", 2.0}, {"GJ", 1.5}, {"coupling", 50.0}, {"rot_inertia", 0.1}}));
  sim.compute_forces();
  auto& q = sim.coordinates("rod.q").q->values();
  for (int i = 0; i < 7; ++i)
    q[i] = qrod::mul(q[i], Vec4(std::cos(0.15 * i * i), 0, 0, std::sin(0.15 * i * i)));
  sim.compute_forces();
  const double e0 = sim.energies().at("twist");
  ASSERT_GT(e0, 0.1);
  for (auto& f : sim.nodes().f) ASSERT_LT(f.norm(), 1e-10);
  EXPECT_GT(sim.max_force(), 0.1);  // the frames' generalised forces count
  const long steps = sim.minimize(1e-9, 200000);
  EXPECT_LT(steps, 200000);
  EXPECT_LT(sim.max_force(), 1e-9);
  EXPECT_LT(sim.potential_energy(), 1e-12 * e0);
  for (auto& qi : q) EXPECT_NEAR(qi.norm(), 1.0, 1e-12);
}

TEST(CosseratRodBond, LbfgsRefusesFreeFrames) {
  // L-BFGS moves node positions only: with free frames it would stop with the frames
  // still turning, so it refuses and names the minimiser that handles them
  Simulation sim(3, 1);
  sim.verbose = false;
  sim.add_chain("r", {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0.1, 0)}, 1.0, false);
  sim.add_bond("spring", P({{"k", 400.0}}));
  sim.add_bond("rod/cosserat",
               P({{"YI", 2.0}, {"GJ", 1.5}, {"coupling", 50.0}, {"rot_inertia", 0.1}}));
  try {
    sim.minimize(1e-9, 100, "lbfgs");
    FAIL() << "lbfgs accepted free rod frames";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("fire"), std::string::npos) << e.what();
  }
}

TEST(CosseratRodBond, MinimizeCurlsAPrecurvedRodIntoItsArc) {
  // as RodWithRestCurvatureRelaxesToItsArc, by FIRE: nodes and frames together
  Simulation sim(3, 1);
  sim.verbose = false;
  const double R = 4.0;
  add_precurved_rod(sim, R, 0.0);
  sim.set_integrator("verlet", P({{"dt", std::string("auto")}}));
  sim.minimize(1e-8, 400000);
  EXPECT_LT(sim.max_force(), 1e-8);
  const double chord = (sim.nodes().x[20] - sim.nodes().x[0]).norm();
  // the discrete arc: 20 chords of 0.5 on a circle of radius R (to the stretch of the springs)
  EXPECT_NEAR(chord, 2 * R * std::sin(10.0 / (2 * R)), 0.01 * R);
  EXPECT_LT(sim.potential_energy(), 1e-6);
}

TEST(CosseratRodBond, ClosedRingIsBentButUntwistedAndItsForcesMatchTheEnergy) {
  // frames carried round a planar ring come back as -q; the energy must not see it
  const int n = 24;
  const double R = 3.0;
  std::vector<Vec3> pts;
  for (int i = 0; i < n; ++i)
    pts.emplace_back(R * std::cos(2 * M_PI * i / n), R * std::sin(2 * M_PI * i / n), 0);
  Simulation sim(3, 1);
  sim.add_chain("ring", pts, 1.0, true);
  sim.add_bond("rod/cosserat",
               P({{"YI", 2.0}, {"GJ", 1.5}, {"coupling", 50.0}, {"rot_inertia", 0.1}}));
  sim.compute_forces();
  // bending 2/l sin(theta/2) per vertex, theta = 2 pi / n: E = n l/2 YI kappa^2
  const double l = 2 * R * std::sin(M_PI / n), kap = 2 / l * std::sin(M_PI / n);
  EXPECT_NEAR(sim.energies().at("bend"), n * 0.5 * l * 2.0 * kap * kap, 1e-9);
  EXPECT_NEAR(sim.energies().at("twist"), 0.0, 1e-20);
  // move the nodes off the frames' tangents so that every term acts, and compare
  std::mt19937 g(8);
  std::normal_distribution<double> u(0, 0.05);
  for (auto& x : sim.nodes().x) x += Vec3(u(g), u(g), u(g));
  EXPECT_LT(fd_force_error(sim), 1e-6);
}
