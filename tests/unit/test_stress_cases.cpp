// Stiff and extreme cases (the stability promise): every case either runs stably (energy
// bounded, no interpenetration beyond a stated tolerance, conservation where it should
// hold) or stops with the guard's message naming a stable dt; never NaN, never a silent
// blow-up. Each case prints one "STRESS |" line with its measured outcome; the table in
// docs/stability.md is made from them.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <string>

#include "helpers.hpp"
#include "simulation.hpp"
#ifdef SLENDER_HAVE_SHELL
#include "shell/surface.hpp"
#include "shell/trimesh.hpp"
#endif

using namespace slender;
using namespace slender::test;

namespace {

struct Outcome {
  bool stable = false;
  std::string message;  // the guard's message when it stopped the run
  double e0 = 0, e_end = 0, e_max = 0;
  long steps = 0;
};

// One run whose guard stop is an outcome (any other exception fails the test); the
// scene must hold no NaN afterwards either way.
Outcome guarded_run(Simulation& sim, const RunOptions& ro) {
  Outcome o;
  sim.guard.last_good_file = "stress_last_good.h5";
  try {
    sim.run(ro);
    o.stable = true;
  } catch (const InstabilityError& e) {
    o.message = e.what();
  }
  std::remove("stress_last_good.h5");
  for (auto& x : sim.nodes().x) EXPECT_TRUE(x.allFinite()) << "NaN left in the scene";
  o.steps = sim.step;
  return o;
}

// Runs `steps` steps in chunks, tracking the total energy; a guard stop is an outcome,
// any other exception a failure of the test.
Outcome run_case(Simulation& sim, long steps, long chunk = 100) {
  sim.compute_forces();
  const double e0 = sim.kinetic_energy() + sim.potential_energy();
  double e_max = e0, e_end = e0;
  Outcome o = guarded_run(sim, RunOptions{steps, chunk, [&](Simulation& s) {
                                            const double e =
                                                s.kinetic_energy() + s.potential_energy();
                                            e_max = std::max(e_max, e);
                                            e_end = e;
                                            return false;
                                          }});
  o.e0 = e0;
  o.e_max = e_max;
  o.e_end = e_end;
  return o;
}

void report(const std::string& family, const std::string& name, const Outcome& o,
            const std::string& detail) {
  std::printf("STRESS | %s | %s | %s | %s\n", family.c_str(), name.c_str(),
              o.stable ? "stable" : "guard stop", detail.c_str());
}

// An undamped bent wire (an arc of radius 1) with random velocities: spring + bend2d.
std::unique_ptr<Simulation> bent_wire(double k_bend, double k_stretch, unsigned seed) {
  auto sim = std::make_unique<Simulation>(2, seed);
  sim->verbose = false;
  std::vector<Vec3> pts;
  const int n = 21;
  for (int i = 0; i < n; ++i) {
    const double a = 0.05 * i;
    pts.emplace_back(std::sin(a), 1 - std::cos(a), 0);
  }
  sim->add_chain("w", pts, 1.0 / n, false);
  sim->add_bond("spring", P({{"k", k_stretch}}));
  sim->add_bond("bend2d", P({{"k", k_bend}}));
  std::mt19937 g(seed);
  std::uniform_real_distribution<double> u(-0.01, 0.01);
  for (auto& v : sim->nodes().v) v = Vec3(u(g), u(g), 0);
  return sim;
}

double max_strain(const Simulation& sim) {
  double worst = 0;
  for (const Chain& c : sim.topology().chains)
    for (int e = 0; e < c.n_edges(); ++e) {
      const double l = (sim.nodes().x[c.edge_head(e)] - sim.nodes().x[c.edge_tail(e)]).norm();
      worst = std::max(worst, std::abs(l / c.rest_length[e] - 1));
    }
  return worst;
}

std::string fmt(const char* f, double a, double b = 0, double c = 0) {
  char buf[256];
  std::snprintf(buf, sizeof buf, f, a, b, c);
  return buf;
}

}  // namespace

// Near-inextensible wires: stretching-to-bending stiffness ratio k_s l^2 / k_b from 1e2 to
// 1e8. dt = "auto" follows the stiffest spring (dt ~ ratio^-1/2), Verlet keeps the energy
// and the wire keeps its length.
TEST(StressCases, NearInextensibleWires) {
  const double l = 0.05, kb = 1.0;
  double dt_prev = 0;
  for (double ratio : {1e2, 1e4, 1e6, 1e8}) {
    auto sim = bent_wire(kb, ratio * kb / (l * l), 3);
    sim->set_integrator("verlet", P({}));
    Outcome o = run_case(*sim, 4000);
    const double drift = std::abs(o.e_end - o.e0) / o.e0;
    report("wire 2D", fmt("k_s l^2/k_b = %.0e", ratio), o,
           fmt("dt %.3g, energy drift %.1e, max strain %.1e", sim->dt, drift, max_strain(*sim)));
    EXPECT_TRUE(o.stable) << o.message;
    EXPECT_LT(drift, 1e-2);
    EXPECT_LT(max_strain(*sim), 1e-2);
    if (dt_prev > 0) {
      EXPECT_NEAR(dt_prev / sim->dt, 10.0, 1.0);  // 100x stiffer: dt / 10
    }
    dt_prev = sim->dt;
  }
}

// Time steps at 0.5x, 1x and 2x the step dt = "auto" proposes (half the stable limit),
// and at 4x (twice the limit): the first three run with bounded energy, the last is
// stopped by the guard with a message that names a stable dt.
TEST(StressCases, TimeStepMultiplesOfTheProposedStep) {
  struct Model {
    std::string name;
    std::function<std::unique_ptr<Simulation>()> make;
    std::string integrator;
  };
  std::vector<Model> models = {
      {"wire 2D (spring + bend2d)", [] { return bent_wire(1.0, 4e4, 5); }, "verlet"},
      {"rod 3D (rod/straight)",
       [] {
         auto sim = std::make_unique<Simulation>(3, 7);
         sim->verbose = false;
         sim->add_chain("r", wiggly_chain(15, 3, 7, 0.2), 1.0, false);
         sim->add_bond("spring", P({{"k", 3000.0}}));
         sim->add_bond("rod/straight", P({{"YI", 50.0}}));
         std::mt19937 g(7);
         std::uniform_real_distribution<double> u(-0.1, 0.1);
         for (auto& v : sim->nodes().v) v = Vec3(u(g), u(g), u(g));
         return sim;
       },
       "gear"},
#ifdef SLENDER_HAVE_SHELL
      {"shell (koiter, h = 0.02)",
       [] {
         auto sim = std::make_unique<Simulation>(3, 9);
         sim->verbose = false;
         shell::add_surface(*sim, "s", shell::make_disc(1.0, 3), 1e-3);
         sim->add_shell("koiter", P({{"mesh", std::string("s")},
                                     {"thickness", 0.02},
                                     {"boundary", std::string("mirror")}}));
         std::mt19937 g(9);
         std::uniform_real_distribution<double> u(-0.01, 0.01);
         for (auto& v : sim->nodes().v) v = Vec3(u(g), u(g), u(g));
         return sim;
       },
       "newmark"},
#endif
  };
  for (auto& m : models) {
    auto probe = m.make();
    probe->set_integrator(m.integrator, P({}));
    probe->run(RunOptions{0, 0, {}});
    const double proposed = probe->dt;
    for (double mult : {0.5, 1.0, 2.0, 4.0}) {
      auto sim = m.make();
      RawParams ip = P({{"dt", mult * proposed}});
      if (m.integrator == "newmark") ip["gamma"] = 0.5;  // undamped: energy must stay put
      sim->set_integrator(m.integrator, ip);
      Outcome o = run_case(*sim, 3000);
      const double drift = std::abs(o.e_max - o.e0) / o.e0;
      report(m.name, fmt("dt = %.1f x proposed (%.3g)", mult, proposed), o,
             o.stable ? fmt("max energy rise %.1e", drift) : o.message.substr(0, 160));
      if (mult <= 2.0) {
        EXPECT_TRUE(o.stable) << m.name << " at " << mult << "x: " << o.message;
        EXPECT_LT(drift, mult < 2.0 ? 1e-2 : 0.2) << m.name << " at " << mult << "x";
      } else {
        EXPECT_FALSE(o.stable) << m.name << " ran at twice its stable limit";
        EXPECT_NE(o.message.find("rerun with dt <="), std::string::npos) << o.message;
      }
    }
  }
}

// Nodes driven into a circular wall at high speed (quadratic penalty k_c = 1e6, wire
// diameter d = 0.1, dt = "auto" from the stiff spring). Either the run resolves the
// impact, with the deepest overlap the penalty's energy balance predicts (k_c delta^3 / 3
// = the kinetic energy, within 10 %), or the guard stops it and names the dt that
// resolves it; rerun with that dt, it does, unless the impact crushes the wire itself,
// which the guard reports too. (How deep a node goes is the penalty's
// business: a stiffer wall for faster impacts.)
TEST(StressCases, NodesDrivenIntoAWall) {
  auto drive = [](double speed, double dt, Outcome& o, double& worst, bool& passed) {
    Simulation sim(2, 1);
    sim.verbose = false;
    sim.add_chain("w", {Vec3(0, 0, 0), Vec3(0.1, 0, 0)}, 1.0, false);
    sim.add_bond("spring", P({{"k", 1e6}}));  // stiff: the pair hits the wall as one body
    sim.add_fix("cavity", "wall/circle",
                P({{"radius", 1.0}, {"stiffness", 1e6}, {"diameter", 0.1}}));
    for (auto& v : sim.nodes().v) v = Vec3(speed, 0, 0);
    sim.set_integrator("verlet", dt > 0 ? P({{"dt", dt}}) : P({}));
    worst = 0;
    passed = false;
    const long steps = static_cast<long>(3.0 / speed / (dt > 0 ? dt : 5e-4)) + 100;
    RunOptions ro{steps, 1, [&](Simulation& s) {
                    for (auto& x : s.nodes().x) {
                      worst = std::max(worst, x.norm() + 0.05 - 1.0);
                      passed = passed || x.norm() > 1.0;
                    }
                    return false;
                  }};
    o = guarded_run(sim, ro);
    return sim.dt;
  };
  for (double speed : {1.0, 10.0, 100.0, 1000.0}) {
    Outcome o;
    double worst;
    bool passed;
    const double predicted = std::cbrt(3 * speed * speed / 1e6);  // mass 2, k_c delta^3 / 3
    double dt = drive(speed, 0, o, worst, passed);
    report("wall/circle", fmt("node at speed %g, dt auto", speed), o,
           o.stable ? fmt("deepest overlap %.3g d (energy balance: %.3g d), dt %.3g", worst / 0.1,
                          predicted / 0.1, dt)
                    : o.message.substr(0, 200));
    if (speed <= 1) {
      EXPECT_TRUE(o.stable) << o.message;
    }
    if (!o.stable) {
      // the guard's advice: "dt <= X keeps it to half of that"
      const auto at = o.message.find("dt <= ");
      ASSERT_NE(at, std::string::npos) << o.message;
      const double advised = std::stod(o.message.substr(at + 6));
      dt = drive(speed, advised, o, worst, passed);
      report("wall/circle", fmt("node at speed %g, the advised dt %.3g", speed, advised), o,
             o.stable ? fmt("deepest overlap %.3g d (energy balance: %.3g d)", worst / 0.1,
                            predicted / 0.1)
                      : o.message.substr(0, 200));
      if (speed >= 1000) {
        // at 1000 the impact crushes the wire itself (the rear node runs into the
        // front one): a guard stop naming the chain, at any dt
        EXPECT_FALSE(o.stable);
        EXPECT_NE(o.message.find("of chain 'w'"), std::string::npos) << o.message;
        continue;
      }
      ASSERT_TRUE(o.stable) << "the advised dt did not resolve speed " << speed << ": "
                            << o.message;
    }
    // the wire is not rigid: at 100 its spring gives a little and the node goes 12 % less deep
    EXPECT_NEAR(worst / predicted, 1.0, speed < 100 ? 0.05 : 0.2) << "speed " << speed;
  }
}

// High friction: a wire pressed on the cavity wall (mu_s = 5) with a tangential pull
// below and above mu_s times the load, with a little viscous drag. Held or sliding,
// the run stays stable. (A load switched on at once overshoots the undamped stick spring
// to twice its static value, so it is held only below mu_s / 2.)
TEST(StressCases, HighFrictionOnTheWall) {
  for (double ratio : {2.0, 7.0}) {
    Simulation sim(2, 1);
    sim.verbose = false;
    // a wall of radius 1000: locally flat, so the load keeps its direction to it
    sim.add_chain("w", {Vec3(999.93, -0.05, 0), Vec3(999.93, 0.05, 0)}, 1.0, false);
    sim.add_bond("spring", P({{"k", 1e3}}));
    sim.add_fix("cavity", "wall/circle",
                P({{"radius", 1000.0},
                   {"stiffness", 1e5},
                   {"diameter", 0.15},
                   {"damping", 1.0},
                   {"mu_static", 5.0},
                   {"mu_dynamic", 4.5}}));
    sim.set_group("all2", {0, 1});
    const double load = 1.0;
    sim.add_fix(
        "push", "force/constant",
        P({{"group", std::string("all2")}, {"force", std::vector<double>{load, ratio * load, 0}}}));
    sim.add_fix("drag", "damping/viscous", P({{"gamma", 1.0}}));
    sim.set_integrator("verlet", P({}));
    Outcome o = run_case(sim, 20000, 1000);
    const double y0 = sim.nodes().x[0].y();
    o = run_case(sim, 20000, 1000);
    const double slide = sim.nodes().x[0].y() - y0;
    report("wall/circle", fmt("mu_s = 5, tangential / normal load = %g", ratio), o,
           fmt("slide in the second half %.3g", slide));
    EXPECT_TRUE(o.stable) << o.message;
    if (ratio < 5) {
      EXPECT_LT(std::abs(slide), 1e-3);
    } else {
      EXPECT_GT(std::abs(slide), 1e-2);
    }
  }
}

// Zero-length wire edges and degenerate shell triangles are refused at input with a
// message naming them, instead of producing NaN in the first force evaluation.
TEST(StressCases, DegenerateElementsAreRefused) {
  Simulation sim(2, 1);
  sim.verbose = false;
  try {
    sim.add_chain("w", {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0)}, 1.0, false);
    FAIL() << "a zero-length edge was accepted";
  } catch (const InputError& e) {
    std::printf("STRESS | wire | zero-length edge | input error | %s\n", e.what());
    EXPECT_NE(std::string(e.what()).find("coincide"), std::string::npos) << e.what();
  }
#ifdef SLENDER_HAVE_SHELL
  shell::TriMesh m = shell::make_rectangle(1.0, 1.0, 4, 4);
  m.x[m.tri[5][0]] = m.x[m.tri[5][1]];  // collapse an edge
  Simulation s3(3, 1);
  try {
    shell::add_surface(s3, "s", m, 0.0);
    FAIL() << "a collapsed triangle was accepted";
  } catch (const InputError& e) {
    std::printf("STRESS | shell | collapsed triangle | input error | %s\n", e.what());
    EXPECT_NE(std::string(e.what()).find("degenerate"), std::string::npos) << e.what();
  }
#endif
}

// Crossing and near-parallel rod contacts (3D segments, radius a = 0.5, linear law):
// two straight rods thrown at each other cross at right angles or at 1e-6 rad; they
// bounce without passing through (the centre lines stay on their sides) at speeds the
// step resolves, and the guard stops the run otherwise.
TEST(StressCases, CrossingAndNearParallelRods) {
  for (double angle : {M_PI / 2, 1e-6}) {
    for (double speed : {0.1, 1.0, 10.0, 100.0}) {
      Simulation sim(3, 1);
      sim.verbose = false;
      std::vector<Vec3> a, b;
      const Vec3 dir(std::cos(angle), std::sin(angle), 0);
      for (int i = 0; i < 9; ++i) {
        a.emplace_back(i - 4.0, 0, 0);
        b.push_back(Vec3(0, 0, 1.5) + (i - 4.0) * dir);
      }
      sim.add_chain("a", a, 1.0, false);
      sim.add_chain("b", b, 1.0, false);
      sim.add_bond("spring", P({{"k", 1e3}}));
      sim.add_bond("rod/straight", P({{"YI", 10.0}}));
      sim.add_pair("contact/segment", P({{"radius", 0.5}, {"stiffness", 1e3}, {"skin", 0.5}}));
      for (int i = 9; i < 18; ++i) sim.nodes().v[i] = Vec3(0, 0, -speed);
      sim.set_integrator("verlet", P({}));
      double gap = 1e9;
      RunOptions ro{static_cast<long>(4.0 / speed / 2e-3), 1, [&](Simulation& s) {
                      // centre-line separation along z at the crossing (both middles)
                      gap = std::min(gap, s.nodes().x[13].z() - s.nodes().x[4].z());
                      return false;
                    }};
      const Outcome o = guarded_run(sim, ro);
      report("contact/segment",
             fmt("rods at %.2g rad approaching at speed %g (dt %.3g)", angle, speed, sim.dt), o,
             o.stable ? fmt("closest centre lines %.3g (2a = 1)", gap) : o.message.substr(0, 200));
      if (o.stable) {
        EXPECT_GT(gap, 0.0) << "rods passed through each other";
        EXPECT_GT(sim.nodes().x[13].z(), sim.nodes().x[4].z());
      }
      if (speed <= 1.0) {
        EXPECT_TRUE(o.stable) << o.message;
      }
    }
  }
}

#ifdef SLENDER_HAVE_SHELL
// Very thin shells: a free disc (R = 1) with e-cone growth switched on at phi_e = 1, for
// h from 0.02 down to 1e-3 R, damped Newmark with dt = "auto" (the stiffest element and
// the membrane wave bound it, so it hardly changes with h). The energy stays bounded
// (it only decays under damping) and no node leaves the scale of the disc.
TEST(StressCases, VeryThinShells) {
  for (double h : {0.02, 0.005, 0.001}) {
    auto sim = std::make_unique<Simulation>(3, 4);
    sim->verbose = false;
    shell::add_surface(*sim, "s", shell::make_disc(1.0, 3), 1e-4);
    sim->add_growth("g", "econe", P({{"phi_e", 1.0}}));
    sim->add_shell("koiter", P({{"mesh", std::string("s")},
                                {"thickness", h},
                                {"growth", std::string("g")},
                                {"boundary", std::string("mirror")}}));
    sim->set_integrator("newmark", P({{"damping", 5.0}}));
    Outcome o = run_case(*sim, 3000, 100);
    double far = 0;
    for (auto& x : sim->nodes().x) far = std::max(far, x.norm());
    report("shell koiter", fmt("free disc, h = %g R, e-cone growth phi_e = 1", h), o,
           fmt("dt %.3g, energy %.3g -> %.3g", sim->dt, o.e0, o.e_end) +
               fmt(" (max %.3g), farthest node %.3g", o.e_max, far));
    EXPECT_TRUE(o.stable) << o.message;
    EXPECT_LE(o.e_max, o.e0 * (1 + 1e-6));
    EXPECT_LT(o.e_end, o.e0);
    EXPECT_LT(far, 1.5);
  }
}
#endif
