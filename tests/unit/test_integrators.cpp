// Integrator tests on a harmonic oscillator: convergence order when dt halves,
// the declared stability limits, FIRE convergence, and damping.
#include <cmath>

#include "helpers.hpp"

using namespace slender;
using namespace slender::test;

namespace {

// Node 1 on a spring k to a clamped node 0; x(t) = 1 + A cos(omega t), omega = sqrt(k/m).
std::unique_ptr<Simulation> oscillator(const std::string& integ, RawParams ip, double k, double A) {
  auto sim = std::make_unique<Simulation>(2, 1);
  sim->verbose = false;
  sim->add_chain("s", {Vec3(0, 0, 0), Vec3(1, 0, 0)}, 1.0, false);
  sim->add_bond("spring", P({{"k", k}}));
  sim->set_group("anchor", {0});
  sim->add_fix("hold", "clamp", P({{"group", std::string("anchor")}}));
  sim->nodes().x[1].x() = 1.0 + A;
  sim->set_integrator(integ, ip);
  sim->guard.every = 0;
  sim->guard.ke_factor = 1e300;
  sim->guard.max_step_fraction = 1e300;
  return sim;
}

double error_after(const std::string& integ, RawParams ip, double dt, double T) {
  const double k = 4.0, A = 0.1, w = 2.0;
  ip["dt"] = dt;
  auto sim = oscillator(integ, ip, k, A);
  const long steps = std::lround(T / dt);
  // largest error over the trajectory: a single end time can sit on a zero crossing
  double worst = 0.0;
  sim->run(RunOptions{steps, 1, [&](Simulation& s) {
                        worst = std::max(
                            worst, std::abs(s.nodes().x[1].x() - (1.0 + A * std::cos(w * s.time))));
                        return false;
                      }});
  return worst;
}

// Largest amplitude reached over many periods, relative to the start.
double growth(const std::string& integ, RawParams ip, double wdt) {
  const double k = 1.0;
  ip["dt"] = wdt;  // omega = 1
  auto sim = oscillator(integ, ip, k, 1e-3);
  double amax = 0;
  sim->run(RunOptions{4000, 1, [&](Simulation& s) {
                        amax = std::max(amax, std::abs(s.nodes().x[1].x() - 1.0));
                        return !std::isfinite(amax) || amax > 1.0;
                      }});
  return amax / 1e-3;
}

double measured_order(const std::string& integ, RawParams ip, double dt) {
  const double T = 2.0;
  const double e1 = error_after(integ, ip, dt, T), e2 = error_after(integ, ip, dt / 2, T);
  return std::log2(e1 / e2);
}

}  // namespace

TEST(Integrators, VelocityVerletIsSecondOrder) {
  EXPECT_NEAR(measured_order("verlet", {}, 0.02), 2.0, 0.1);
}

TEST(Integrators, GearOrders) {
  // On the oscillator q = 4 converges as dt^4. q = 5 and 6 start from rest with
  // zero third and higher derivatives; that start-up error limits their
  // asymptotic order to ~4 too, but their error is far smaller at practical dt.
  const double o4 = measured_order("gear", P({{"values", 4.0}}), 0.02);
  const double o5 = measured_order("gear", P({{"values", 5.0}}), 0.01);
  const double o6 = measured_order("gear", P({{"values", 6.0}}), 0.01);
  std::printf("measured orders: gear4 %.3f gear5 %.3f gear6 %.3f\n", o4, o5, o6);
  EXPECT_NEAR(o4, 4.0, 0.2);
  EXPECT_GT(o5, 3.8);
  EXPECT_GT(o6, 3.5);
  const double e4 = error_after("gear", P({{"values", 4.0}}), 0.02, 2.0);
  EXPECT_LT(error_after("gear", P({{"values", 5.0}}), 0.02, 2.0), e4 / 10);
  EXPECT_LT(error_after("gear", P({{"values", 6.0}}), 0.02, 2.0), e4 / 10);
  // a wrong corrector coefficient drops the order to 1-2
  EXPECT_LT(error_after("gear", P({{"values", 5.0}}), 0.02, 2.0),
            error_after("verlet", {}, 0.02, 2.0) / 1000);
}

TEST(Integrators, DeclaredStabilityLimitsHold) {
  for (auto [name, ip] :
       std::vector<std::pair<std::string, RawParams>>{{"verlet", {}},
                                                      {"gear", P({{"values", 4.0}})},
                                                      {"gear", P({{"values", 5.0}})},
                                                      {"gear", P({{"values", 6.0}})}}) {
    auto sim = oscillator(name, ip, 1.0, 0.0);
    const double limit = sim->integrator()->stability_limit();
    double lo = 0.05, hi = 4.0;  // bisection on the measured limit
    for (int it = 0; it < 30; ++it) {
      double mid = 0.5 * (lo + hi);
      (growth(name, ip, mid) < 2.0 ? lo : hi) = mid;
    }
    std::printf(
        "%s %s: measured limit omega dt = %.4f, declared %.4f\n", name.c_str(),
        ip.count("values") ? std::to_string(int(std::get<double>(ip["values"]))).c_str() : "", lo,
        limit);
    EXPECT_LE(limit, lo * 1.001) << name;
    EXPECT_GE(limit, lo * 0.95) << name;
  }
}

TEST(Integrators, FireFindsTheMinimum) {
  auto sim = oscillator("verlet", P({{"dt", 0.05}}), 10.0, 0.3);
  sim->nodes().x[1].y() = 0.4;
  const long steps = sim->minimize(1e-10, 100000);
  EXPECT_LT(steps, 100000);
  EXPECT_NEAR(sim->nodes().x[1].norm(), 1.0, 1e-10);
}

TEST(Integrators, LbfgsFindsTheMinimumWithoutMovingTheClock) {
  auto sim = oscillator("verlet", P({{"dt", 0.05}}), 10.0, 0.3);
  sim->nodes().x[1].y() = 0.4;
  sim->nodes().v[1] = Vec3(1, 2, 0);  // a minimiser starts from rest
  const long steps = sim->minimize(1e-10, 1000, "lbfgs");
  EXPECT_LT(steps, 40);
  EXPECT_NEAR(sim->nodes().x[1].norm(), 1.0, 1e-10);
  EXPECT_EQ(sim->time, 0.0);  // not a time stepper: the scene's clock stands
  EXPECT_EQ(sim->nodes().v[1].norm(), 0.0);
  EXPECT_THROW(sim->minimize(1e-10, 10, "simplex"), InputError);
  // max_move caps each iteration's displacement: 0.3 to go at 0.01 per iteration
  sim->nodes().x[1] = Vec3(1.3, 0, 0);
  sim->forces_valid = false;
  const long capped = sim->minimize(1e-10, 1000, "lbfgs", P({{"max_move", 0.01}}));
  EXPECT_GE(capped, 30);
  EXPECT_LT(capped, 1000);
  EXPECT_NEAR(sim->nodes().x[1].norm(), 1.0, 1e-10);
}

TEST(Integrators, DampedDynamicsRelaxesWithTheScenesIntegratorToBothTolerances) {
  // underdamped oscillator (omega = 3.16, decay rate 0.25): the scene's own verlet and drag
  auto make = [] {
    auto sim = oscillator("verlet", P({{"dt", 0.05}}), 10.0, 0.3);
    sim->add_fix("drag", "damping/viscous", P({{"gamma", 0.5}}));
    return sim;
  };
  auto sim = make();
  // the force alone is below ftol at every swing through equilibrium, so ketol is required
  EXPECT_THROW(sim->minimize(1e-4, 100000, "dynamics"), InputError);
  Simulation bare(2, 1);
  bare.verbose = false;
  bare.add_chain("s", {Vec3(0, 0, 0), Vec3(1, 0, 0)}, 1.0, false);
  EXPECT_THROW(bare.minimize(1e-4, 10, "dynamics", {}, 1e-12), InputError);  // no integrator

  // |f| < 0.5 holds within 0.05 of x = 1: with no kinetic limit the relaxation stops at the
  // first swing through (a quarter period, about 10 steps), at full speed
  auto loose = make();
  EXPECT_LT(loose->minimize(0.5, 100000, "dynamics", {}, 1e300), 20);
  // both together hold only once the amplitude is below about ftol / k = 1e-5:
  // ln(0.3 / 1e-5) / 0.25 = 41 time units
  const long steps = sim->minimize(1e-4, 100000, "dynamics", {}, 1e-10);
  EXPECT_GT(steps * 0.05, 30.0);
  EXPECT_LT(steps, 100000);
  EXPECT_NEAR(sim->nodes().x[1].x(), 1.0, 1e-4 / 10.0);
  EXPECT_NEAR(sim->time, steps * 0.05, 1e-9);            // a time stepper: the clock moved
  EXPECT_EQ(sim->integrator()->style_name(), "verlet");  // still the scene's integrator
  EXPECT_EQ(sim->nodes().v[1].norm(), 0.0);
}

TEST(Integrators, ViscousDampingDecaysAtTheRightRate) {
  // x'' = -w^2 x - (gamma/m) x' with small gamma: amplitude ~ exp(-gamma t / 2m)
  auto sim = oscillator("verlet", P({{"dt", 0.01}}), 4.0, 0.1);
  sim->add_fix("drag", "damping/viscous", P({{"gamma", 0.2}}));
  // exact: x = A e^{-bt} (cos wd t + b/wd sin wd t), b = gamma/2m
  const double b = 0.1, wd = std::sqrt(4.0 - b * b);
  double worst = 0;
  sim->run(RunOptions{1400, 1, [&](Simulation& s) {
                        const double t = s.time;
                        const double exact =
                            0.1 * std::exp(-b * t) * (std::cos(wd * t) + b / wd * std::sin(wd * t));
                        worst = std::max(worst, std::abs(s.nodes().x[1].x() - 1.0 - exact));
                        return false;
                      }});
  EXPECT_LT(worst, 1e-3);  // 1% of the amplitude; without the drag it would be ~0.07
}
