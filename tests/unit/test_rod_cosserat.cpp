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

// --- director = "tangent": d3 on the edge tangent exactly (docs/models.md §4.6)

namespace {
RawParams tangent_rod(std::vector<double> kbar, double rot_inertia = 0.1) {
  return P({{"YI", 2.0},
            {"GJ", 1.5},
            {"director", std::string("tangent")},
            {"rot_inertia", rot_inertia},
            {"rest_curvature", std::move(kbar)}});
}
// Spins every frame about its own d3 by a random angle.
void spin_frames(Simulation& sim, unsigned seed, double amp) {
  auto& q = sim.coordinates("rod.q").q->values();
  std::mt19937 g(seed);
  std::uniform_real_distribution<double> u(-amp, amp);
  for (size_t i = 0; i + 1 < q.size(); ++i) {
    const double a = u(g);
    const Vec3 t = qrod::d3(q[i]);
    q[i] = qrod::mul(Vec4(std::cos(a / 2), std::sin(a / 2) * t.x(), std::sin(a / 2) * t.y(),
                          std::sin(a / 2) * t.z()),
                     q[i]);
  }
}
}  // namespace

TEST(CosseratRodBond, TangentDirectorForcesMatchTheEnergyOfFramesCarriedWithTheEdges) {
  // the nodes' forces are -dE/dx with every frame carried onto its moved tangent by the
  // smallest rotation; the frames' generalised forces spin them about d3 only
  Simulation sim(3, 1);
  sim.add_chain("r", wiggly_chain(9, 3, 5, 0.3), 1.0, false);
  sim.add_bond("rod/cosserat", tangent_rod({0.05, 0.2, -0.1}));
  sim.compute_forces();
  spin_frames(sim, 3, 0.8);
  sim.compute_forces();
  EXPECT_GT(sim.energies().at("twist"), 1e-3);
  EXPECT_EQ(sim.energies().at("coupling"), 0.0);
  EXPECT_LT(fd_force_error(sim), 1e-6);
  auto& c = sim.coordinates("rod.q");
  auto& q = c.q->values();
  sim.compute_forces();
  const auto fq = c.f->values();
  double fscale = 0;
  for (auto& v : fq) fscale = std::max(fscale, v.norm());
  ASSERT_GT(fscale, 1e-3);
  const double h = 1e-6;
  for (size_t i = 0; i + 1 < q.size(); ++i) {
    // d3 on the tangent
    const Vec3 t = (sim.nodes().x[i + 1] - sim.nodes().x[i]).normalized();
    EXPECT_LT((qrod::d3(q[i]) - t).norm(), 1e-12);
    // spin by +-h: dE/dtheta = -torque . t = -(fq . g) / 2, g = L(q) t
    const Vec4 g = qrod::rotation_map(q[i]) * t;
    const Vec4 q0 = q[i];
    auto spun = [&](double a) {
      return qrod::mul(Vec4(std::cos(a / 2), std::sin(a / 2) * t.x(), std::sin(a / 2) * t.y(),
                            std::sin(a / 2) * t.z()),
                       q0);
    };
    q[i] = spun(h);
    const double ep = total_energy(sim);
    q[i] = spun(-h);
    const double em = total_energy(sim);
    q[i] = q0;
    EXPECT_NEAR(0.5 * fq[i].dot(g), -(ep - em) / (2 * h), 1e-6 * fscale) << i;
    // nothing across the tangent, nothing radial
    EXPECT_NEAR((fq[i] - fq[i].dot(g) * g).norm(), 0.0, 1e-12 * fscale) << i;
  }
}

TEST(CosseratRodBond, TangentDirectorRelaxesToTheHelixOfItsRestDarbouxVector) {
  // rest Darboux vector (0, kappa, tau): the free rod at rest is a helix of curvature
  // kappa and torsion tau; the chord over arc length s is
  // sqrt((2 r sin(w s / 2))^2 + (c s)^2), w = |(kappa, tau)|, r = kappa / w^2, c = tau / w.
  // The stiff penalty (C = 1e4) must land on the same shape.
  const double kappa = 0.25, tau = 0.15, l = 0.25;
  const int n = 41;
  double chord[2];
  for (int mode = 0; mode < 2; ++mode) {
    Simulation sim(3, 1);
    sim.verbose = false;
    std::vector<Vec3> pts;
    for (int i = 0; i < n; ++i) pts.emplace_back(l * i, 0, 0);
    sim.add_chain("r", pts, 1.0, false);
    sim.add_bond("spring", P({{"k", 4000.0}}));
    RawParams p = mode == 0 ? tangent_rod({0, kappa, tau}, 0.5)
                            : P({{"YI", 2.0},
                                 {"GJ", 1.5},
                                 {"coupling", 1e4},
                                 {"rot_inertia", 0.5},
                                 {"rest_curvature", std::vector<double>{0, kappa, tau}}});
    sim.add_bond("rod/cosserat", p);
    sim.set_integrator("verlet", P({{"dt", std::string("auto")}}));
    sim.minimize(1e-9, 2000000);
    EXPECT_LT(sim.max_force(), 1e-8) << mode;
    EXPECT_LT(sim.potential_energy(), 1e-10) << mode;
    chord[mode] = (sim.nodes().x[n - 1] - sim.nodes().x[0]).norm();
  }
  const double w = std::hypot(kappa, tau), r = kappa / (w * w), c = tau / w, s = l * (n - 1);
  const double exact = std::hypot(2 * r * std::sin(w * s / 2), c * s);
  EXPECT_NEAR(chord[0], exact, 0.01 * exact);
  EXPECT_NEAR(chord[0], chord[1], 1e-3 * exact);
}

TEST(CosseratRodBond, TangentDirectorConservesEnergyUnderVerletToSecondOrder) {
  // the carried frames, the spin's inertia and the torques on the nodes make one
  // conservative system: undamped, the total energy stays put while bending and twist
  // trade energy with the motion, and the error falls as dt^2 (a rate that lost its
  // radial part only, without keeping its length, gave a first-order loss)
  double drift[2], ke_max = 0.0, pe0 = 0.0, dt_auto = 0.0;
  for (int halve = 0; halve < 2; ++halve) {
    Simulation sim(3, 1);
    sim.verbose = false;
    sim.add_chain("r", wiggly_chain(12, 3, 9, 0.25), 1.0, false);
    sim.add_bond("spring", P({{"k", 400.0}}));
    sim.add_bond("rod/cosserat", tangent_rod({0.0, 0.3, 0.2}, 0.2));
    sim.compute_forces();
    spin_frames(sim, 7, 1.0);
    if (halve == 0) {
      sim.set_integrator("verlet", P({{"dt", std::string("auto")}}));
      sim.run(RunOptions{0, 0, nullptr});
      dt_auto = sim.dt;
    }
    sim.set_integrator("verlet", P({{"dt", halve ? dt_auto / 2 : dt_auto}}));
    sim.compute_forces();
    pe0 = sim.potential_energy();
    const double e0 = sim.kinetic_energy() + pe0;
    drift[halve] = 0.0;
    sim.run(RunOptions{halve ? 4000 : 2000, 10, [&](Simulation& s) {
                         ke_max = std::max(ke_max, s.kinetic_energy());
                         drift[halve] = std::max(drift[halve], std::abs(s.kinetic_energy() +
                                                                        s.potential_energy() - e0));
                         return false;
                       }});
  }
  EXPECT_GT(dt_auto, 0.0);
  EXPECT_GT(ke_max, 0.2 * pe0);         // it moved
  EXPECT_LT(drift[0], 0.02 * pe0);      // and kept its energy
  EXPECT_GT(drift[0] / drift[1], 3.0);  // second order: 4 for halving dt
}

TEST(CosseratRodBond, TangentDirectorRefusesGearAndAPenaltyStiffness) {
  {
    Simulation sim(3, 1);
    sim.verbose = false;
    sim.add_chain("r", wiggly_chain(5, 3, 2), 1.0, false);
    sim.add_bond("rod/cosserat", tangent_rod({0, 0, 0}));
    try {
      sim.set_integrator("gear", P({{"dt", 0.001}}));
      sim.run(RunOptions{10, 0, nullptr});
      FAIL() << "gear ran frames carried with the positions";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("verlet"), std::string::npos) << e.what();
    }
  }
  Simulation sim(3, 1);
  sim.add_chain("r", wiggly_chain(5, 3, 2), 1.0, false);
  RawParams p = tangent_rod({0, 0, 0});
  p["coupling"] = 10.0;
  EXPECT_THROW(sim.add_bond("rod/cosserat", p), InputError);
  EXPECT_THROW(sim.add_bond("rod/cosserat", P({{"YI", 2.0}, {"GJ", 1.5}, {"rot_inertia", 0.1}})),
               InputError);
}
