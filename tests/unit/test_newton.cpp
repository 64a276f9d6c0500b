// Exact Hessians of the force styles (checked against central differences of their forces)
// and Newton-Raphson statics (docs/models.md §9). Covers src/hessian.hpp,
// styles/integrator/newton.cpp, src/continuation.cpp, styles/fix/moment2d.cpp and the
// add_hessian of spring, bend2d and the fixes.
#include <Eigen/Dense>
#include <cmath>
#include <cstdio>

#include "context.hpp"
#include "continuation.hpp"
#include "helpers.hpp"
#include "hessian.hpp"
#include "statics.hpp"

using namespace slender;
using namespace slender::test;

namespace {

// A clamped 2D wire along x with EI = 1, EA = 1e5, length L = 1 from the staggered clamp
// (the cantilever of examples/validation/cantilever2d.lua), nodes + 1 nodes, a force on the
// tip.
std::unique_ptr<Simulation> cantilever(int nodes, Vec3 tip_force, double lateral = 0.0) {
  auto sim = std::make_unique<Simulation>(2, 1);
  sim->verbose = false;
  const double h = 1.0 / (nodes - 0.5);
  std::vector<Vec3> pts;
  for (int i = 0; i <= nodes; ++i) {
    const double x = -h / 2 + i * h;
    pts.emplace_back(x, lateral * x * x, 0.0);
  }
  sim->add_chain("beam", pts, h, false);
  sim->add_bond("spring", P({{"k", 1e5 / h}}));
  sim->add_bond("bend2d", P({{"k", 1.0 / h}}));
  sim->set_group("base", {0, 1});
  sim->set_group("tip", {nodes});
  sim->add_fix("clamp", "clamp", P({{"group", std::string("base")}}));
  sim->add_fix("load", "force/constant",
               P({{"group", std::string("tip")},
                  {"force", std::vector<double>{tip_force.x(), tip_force.y()}}}));
  return sim;
}

}  // namespace

TEST(Hessian, SpringMatchesFiniteDifferencesOfItsForces) {
  for (int dim : {2, 3})
    for (bool closed : {false, true}) {
      Simulation sim(dim, 1);
      sim.add_chain("w", wiggly_chain(7, dim, 3, 0.4), 1.0, closed);
      sim.add_bond("spring", P({{"k", 40.0}}));
      EXPECT_LT(fd_hessian_error(sim), 1e-7) << "dim " << dim << " closed " << closed;
    }
}

TEST(Hessian, Bend2dMatchesFiniteDifferencesOfItsForces) {
  for (bool closed : {false, true}) {
    Simulation sim(2, 1);
    // turning angles up to about 1 rad, past the series branch of the angle
    sim.add_chain("w", wiggly_chain(8, 2, 11, 0.45), 1.0, closed);
    sim.add_bond("bend2d", P({{"k", 3.0}}));
    EXPECT_LT(fd_hessian_error(sim), 1e-7) << "closed " << closed;
  }
}

TEST(Hessian, WireWithLoadsMatchesFiniteDifferences) {
  auto sim = cantilever(9, Vec3(0.3, -2.0, 0), 0.4);
  EXPECT_LT(fd_hessian_error(*sim), 1e-7);
}

TEST(Newton, CantileverConvergesQuadraticallyToTheLbfgsAnswer) {
  // alpha = P L^2 / EI = 3: a large deflection
  auto newton = cantilever(21, Vec3(0, -3.0, 0));
  auto lbfgs = cantilever(21, Vec3(0, -3.0, 0));
  const long it = newton->minimize(1e-8, 200, "newton");
  EXPECT_LT(newton->max_force(), 1e-8);
  EXPECT_LT(it, 40);
  const long it_lbfgs = lbfgs->minimize(1e-8, 200000, "lbfgs");
  ASSERT_LT(lbfgs->max_force(), 1e-8);
  EXPECT_GT(it_lbfgs, 5 * it);
  const Vec3 tn = newton->nodes().x[21], tl = lbfgs->nodes().x[21];
  EXPECT_LT((tn - tl).norm(), 1e-6);
  EXPECT_LT(tn.y(), -0.5);  // bent far (the elastica's tip drops 0.79 L at alpha = 3)
  EXPECT_EQ(newton->time, 0.0);

  // the last iterations: |f| falls at least quadratically once it is small
  auto sim = cantilever(21, Vec3(0, -3.0, 0));
  sim->set_integrator("newton", {});
  auto* integ = sim->integrator();
  integ->setup(*sim);
  std::vector<double> fmax{sim->max_force()};
  for (int k = 0; k < 40 && fmax.back() > 1e-8; ++k) {
    integ->step(*sim);
    fmax.push_back(sim->max_force());
  }
  ASSERT_LT(fmax.back(), 1e-8);
  int quadratic = 0;
  for (size_t k = 1; k < fmax.size(); ++k)
    if (fmax[k - 1] < 1e-2 && fmax[k] > 1e-9) {
      EXPECT_LT(fmax[k], 100.0 * fmax[k - 1] * fmax[k - 1]) << "iteration " << k;
      ++quadratic;
    }
  EXPECT_GE(quadratic, 1);
}

TEST(Newton, KeepingTheFactorizationReachesTheSameStateWithFewerFactorizations) {
  // modified Newton (keep_factorization): the same equilibrium as plain Newton, with a
  // factorisation kept over the iterations that still converge fast
  auto solve = [](double keep, double& factorizations, int& iterations) {
    auto sim = cantilever(21, Vec3(0, -3.0, 0));
    sim->set_integrator("newton", P({{"keep_factorization", keep}}));
    auto* integ = sim->integrator();
    integ->setup(*sim);
    for (iterations = 0; iterations < 200 && sim->max_force() > 1e-9; ++iterations)
      integ->step(*sim);
    factorizations = integ->value("factorizations");
    EXPECT_LT(sim->max_force(), 1e-9) << "keep " << keep;
    return Vec3(sim->nodes().x[21]);
  };
  double f_plain = 0, f_kept = 0;
  int it_plain = 0, it_kept = 0;
  const Vec3 plain = solve(0.0, f_plain, it_plain);
  const Vec3 kept = solve(0.5, f_kept, it_kept);
  EXPECT_LT((plain - kept).norm(), 1e-7);
  EXPECT_LT(f_kept, f_plain);
  EXPECT_LT(f_kept, it_kept);  // some iterations solved with an earlier factorisation
}

TEST(Newton, ReassemblyOnTheKeptPatternEqualsAFreshAssembly) {
  // StaticSystem adds the values of a repeated pattern into its kept matrix: the matrix and
  // the inertia must be those a fresh assembly gives
  auto sim = cantilever(11, Vec3(0, -3.0, 0), 0.3);
  sim->compute_forces();
  StaticSystem kept(*sim);
  kept.assemble();
  for (int i = 2; i <= 11; ++i) sim->nodes().x[i].y() -= 0.05 * i * i / 121.0;
  sim->compute_forces();
  const Eigen::SparseMatrix<double> again = kept.assemble();
  StaticSystem fresh(*sim);
  const Eigen::SparseMatrix<double> first = fresh.assemble();
  ASSERT_EQ(again.rows(), first.rows());
  EXPECT_GT(first.norm(), 0.0);
  EXPECT_EQ((Eigen::MatrixXd(again) - Eigen::MatrixXd(first)).norm(), 0.0);
  EXPECT_EQ(kept.factorize(), fresh.factorize());
  EXPECT_EQ(kept.factorize(1e3), fresh.factorize(1e3));
  const Eigen::VectorXd r = Eigen::VectorXd::LinSpaced(first.rows(), -1.0, 1.0);
  EXPECT_LT((kept.solve(r) - fresh.solve(r)).norm(), 1e-12 * fresh.solve(r).norm());
}

TEST(Newton, BucklesPastEulersLoadOntoTheElasticaAndCountsTheUnstableMode) {
  // Clamped-free column under an axial tip load P = 1.1518 P_cr, P_cr = pi^2 EI / (4 L^2):
  // the elastica buckles with end slope 60 degrees, k = sin 30 degrees, and the tip moves
  // sideways by delta = 2 k L / K(k) = 0.5932 L (Timoshenko & Gere, inextensible).
  const double k = 0.5, Kk = std::comp_ellint_1(k);
  const double ratio = std::pow(2.0 * Kk / M_PI, 2.0);
  const double P = ratio * M_PI * M_PI / 4.0;
  auto sim = cantilever(41, Vec3(-P, 0, 0), 1e-4);  // a small bow breaks the symmetry
  sim->set_integrator("newton", {});
  auto* integ = sim->integrator();
  integ->setup(*sim);
  // the first iteration compresses the springs (unloaded at the start, they have no
  // geometric stiffness yet); then the near-straight column is past its first critical
  // load only: one unstable direction, and the step is shifted
  double most = 0.0, shifted = 0.0;
  for (int k = 0; k < 3; ++k) {
    integ->step(*sim);
    most = std::max(most, integ->value("negative_pivots"));
    shifted = std::max(shifted, integ->value("shift"));
  }
  EXPECT_EQ(most, 1.0);
  EXPECT_GT(shifted, 0.0);
  sim->set_integrator("verlet", {});
  const long it = sim->minimize(1e-8, 400, "newton");
  EXPECT_LT(it, 400);
  ASSERT_LT(sim->max_force(), 1e-8);
  const double delta = std::abs(sim->nodes().x[41].y());
  EXPECT_NEAR(delta, 2.0 * k / Kk, 0.01);
  // the buckled state is stable: a step there finds no negative pivot
  sim->set_integrator("newton", {});
  sim->integrator()->setup(*sim);
  sim->integrator()->step(*sim);
  EXPECT_EQ(sim->integrator()->value("negative_pivots"), 0.0);
  EXPECT_EQ(sim->integrator()->value("shift"), 0.0);
}

// L-BFGS with the factorised exact Hessian as its initial inverse Hessian
// (precondition = "hessian"): a cantilever with EA / EI = 1e5 is ill-conditioned, which
// sets plain L-BFGS's count of iterations; preconditioned, it reaches the same equilibrium
// in a small fraction of them.
TEST(LbfgsPreconditioner, ReachesTheSameEquilibriumInFewerIterations) {
  auto solve = [](const std::string& precondition, int& iterations, double& factorizations) {
    auto sim = cantilever(21, Vec3(0, -3.0, 0));
    sim->set_integrator("lbfgs", P({{"precondition", precondition}, {"precondition_every", 20.0}}));
    auto* integ = sim->integrator();
    integ->setup(*sim);
    for (iterations = 0; iterations < 100000 && sim->max_force() > 1e-9; ++iterations)
      integ->step(*sim);
    EXPECT_LT(sim->max_force(), 1e-9) << precondition;
    factorizations = integ->value("factorizations");
    return Vec3(sim->nodes().x[21]);
  };
  int it_plain = 0, it_pre = 0;
  double fac_plain = 0, fac_pre = 0;
  const Vec3 plain = solve("none", it_plain, fac_plain);
  const Vec3 pre = solve("hessian", it_pre, fac_pre);
  std::printf(
      "cantilever to 1e-9: %d L-BFGS iterations plain, %d preconditioned (%g factorisations)\n",
      it_plain, it_pre, fac_pre);
  EXPECT_LT((plain - pre).norm(), 1e-6);
  EXPECT_GT(std::abs(pre.y()), 0.1);  // a large deflection, not the straight start
  EXPECT_EQ(fac_plain, 0.0);
  EXPECT_GE(fac_pre, 1.0);
  EXPECT_LT(10 * it_pre, it_plain);
}

// Past Euler's load the straight column's Hessian has a negative pivot: the preconditioner
// takes the Levenberg ladder's shift, stays positive definite, and L-BFGS still finds the
// buckled elastica (tip deflection 2 k L / K(k), Newton's test above).
TEST(LbfgsPreconditioner, ShiftsAnIndefiniteHessianAndFindsTheBuckledColumn) {
  const double k = 0.5, Kk = std::comp_ellint_1(k);
  const double load = std::pow(2.0 * Kk / M_PI, 2.0) * M_PI * M_PI / 4.0;
  auto sim = cantilever(41, Vec3(-load, 0, 0), 1e-4);
  sim->compute_forces();
  sim->minimize(1e-6, 5, "newton");  // compressed springs: the straight column is unstable
  RawParams p = P({{"precondition", std::string("hessian")}, {"precondition_every", 20.0}});
  sim->set_integrator("verlet", {});
  const long it = sim->minimize(1e-8, 20000, "lbfgs", p);
  EXPECT_LT(it, 20000);
  ASSERT_LT(sim->max_force(), 1e-8);
  EXPECT_NEAR(std::abs(sim->nodes().x[41].y()), 2.0 * k / Kk, 0.01);
  EXPECT_GT(sim->static_system().last_shift(), 0.0);  // the ladder was climbed
}

#ifdef SLENDER_HAVE_HDF5
// The preconditioner's Levenberg shift carries from one minimisation to the next (the
// ladder starts from a tenth of it), so it goes into checkpoints: a ramp resumed from one
// continues as the uninterrupted ramp does, bit for bit.
TEST(LbfgsPreconditioner, AResumedRampContinuesBitForBit) {
  const double load = 1.3 * M_PI * M_PI / 4.0;  // past Euler's load: shifted factorisations
  auto make = [&] { return cantilever(21, Vec3(-load, 0, 0), 1e-3); };
  const RawParams p = P({{"precondition", std::string("hessian")}, {"precondition_every", 20.0}});
  auto ramp = [&](Simulation& sim, int from, int to) {
    for (int k = from; k < to; ++k) {
      sim.modify_style("load", P({{"force", std::vector<double>{-load * (1 + 0.05 * k), 0.0}}}));
      sim.minimize(1e-8, 20000, "lbfgs", p);
    }
  };
  auto a = make();
  a->set_integrator("verlet", {});
  ramp(*a, 0, 2);
  a->write_checkpoint("lbfgs_preconditioned_ramp.h5");
  EXPECT_GT(a->static_system().last_shift(), 0.0);
  ramp(*a, 2, 4);
  auto b = make();
  b->set_integrator("verlet", {});
  b->read_checkpoint("lbfgs_preconditioned_ramp.h5");
  ramp(*b, 2, 4);
  for (std::size_t i = 0; i < a->nodes().size(); ++i) EXPECT_EQ(a->nodes().x[i], b->nodes().x[i]);
  std::remove("lbfgs_preconditioned_ramp.h5");
}
#endif

TEST(Newton, NamesTheStyleWithoutAHessian) {
  Simulation sim(2, 1);
  sim.verbose = false;
  sim.add_chain("w", wiggly_chain(6, 2, 2, 0.2), 1.0, false);
  sim.add_bond("spring", P({{"k", 10.0}}));
  sim.add_bond("bend2d/hysteresis", P({{"k", 1.0}, {"yield_curvature", 0.5}}));
  try {
    sim.minimize(1e-8, 10, "newton");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bond style 'bend2d/hysteresis' has none"),
              std::string::npos)
        << e.what();
  }
}

TEST(Continuation, FollowsTheVonMisesTrussThroughBothLimitPoints) {
  // two springs k from the supports (-a, 0) and (a, 0) to an apex at (0, h), loaded downwards
  // by lambda: along the path P(w) = 2 k (L0 - L) (h - w) / L with L = sqrt(a^2 + (h - w)^2)
  // for the apex's descent w; P rises to a limit point, falls below zero as the truss snaps
  // through, and rises again past the second limit point once it hangs inverted.
  const double a = 1.0, h = 0.5, k = 100.0, L0 = std::hypot(a, h);
  auto load = [&](double w) {
    const double L = std::hypot(a, h - w);
    return 2.0 * k * (L0 - L) * (h - w) / L;
  };
  // the analytic limit load (the maximum of P over 0 < w < h)
  double pmax = 0.0;
  for (int i = 1; i < 200000; ++i) pmax = std::max(pmax, load(h * i / 200000.0));
  Simulation sim(2, 1);
  sim.verbose = false;
  sim.add_chain("truss", {Vec3(-a, 0, 0), Vec3(0, h, 0), Vec3(a, 0, 0)}, 1.0, false);
  sim.add_bond("spring", P({{"k", k}}));
  sim.set_group("supports", {0, 2});
  sim.set_group("apex", {1});
  sim.add_fix("hold", "clamp", P({{"group", std::string("supports")}}));
  sim.add_fix("push", "force/constant",
              P({{"group", std::string("apex")}, {"force", std::vector<double>{0.0, -1.0}}}));
  ContinuationOptions opt;
  opt.load = "push";
  opt.ds = 0.02;
  opt.ds_max = 0.05;
  opt.points = 2000;
  opt.ftol = 1e-10;
  double worst = 0.0, top = 0.0, bottom = 0.0;
  std::vector<long> pivots;
  std::vector<std::string> events;
  std::vector<double> criticals;
  opt.callback = [&](Simulation& s, const ContinuationPoint& p) {
    const double w = h - s.nodes().x[1].y();
    worst = std::max(worst, std::abs(p.lambda - load(w)) / pmax);
    EXPECT_NEAR(s.nodes().x[1].x(), 0.0, 1e-9);
    if (w < h) top = std::max(top, p.lambda);
    bottom = std::min(bottom, p.lambda);
    if (pivots.empty() || pivots.back() != p.negative_pivots) pivots.push_back(p.negative_pivots);
    if (!p.event.empty()) {
      events.push_back(p.event);
      criticals.push_back(p.critical_lambda);
    }
    return w > 2.5 * h;  // well past the inverted state
  };
  const ContinuationResult r = continuation(sim, opt);
  EXPECT_LT(worst, 1e-9);  // every converged point lies on the analytic path
  EXPECT_LE(top, pmax * (1 + 1e-9));
  EXPECT_GT(top, 0.97 * pmax);      // the path went over the top...
  EXPECT_LT(bottom, -0.97 * pmax);  // ... and down to the mirrored limit point
  EXPECT_EQ(r.limit_points, 2);
  EXPECT_EQ(r.bifurcation_points, 0);
  EXPECT_EQ(pivots, (std::vector<long>{0, 1, 0}));
  EXPECT_EQ(events, (std::vector<std::string>{"limit point", "limit point"}));
  // located by bisection: the limit loads +-P_max
  ASSERT_EQ(criticals.size(), 2u);
  EXPECT_NEAR(criticals[0], pmax, 1e-6 * pmax);
  EXPECT_NEAR(criticals[1], -pmax, 1e-6 * pmax);
  EXPECT_GT(r.lambda, 0.0);  // rising again on the hanging branch
}

TEST(Continuation, FindsEulersBifurcationOnAStraightColumn) {
  // a perfectly straight clamped-free column under a compressive tip load lambda: the
  // straight state stays an equilibrium, and one direction becomes unstable at
  // P_cr = pi^2 EI / (4 L^2) without lambda turning back: a bifurcation point
  auto sim = cantilever(31, Vec3(-1.0, 0, 0));
  ContinuationOptions opt;
  opt.load = "load";
  opt.ds = 1e-5;  // the axial shortening is small (EA = 1e5): small arc-length steps
  opt.ds_max = 2e-5;
  opt.points = 1000;
  opt.lambda_max = 4.0;
  std::vector<double> at;
  double before = 0.0;
  opt.callback = [&](Simulation&, const ContinuationPoint& p) {
    if (p.event == "bifurcation point") at = {before, p.critical_lambda, p.lambda};
    before = p.lambda;
    return false;
  };
  const ContinuationResult r = continuation(*sim, opt);
  EXPECT_EQ(r.bifurcation_points, 1);
  EXPECT_EQ(r.limit_points, 0);
  ASSERT_EQ(at.size(), 3u);
  const double pcr = M_PI * M_PI / 4.0;
  EXPECT_LT(at[0], at[1]);
  EXPECT_LT(at[1], at[2]);
  // the discrete column's critical load, within its discretisation error of Euler's
  EXPECT_NEAR(at[1], pcr, 2e-3 * pcr);
  EXPECT_NEAR(sim->nodes().x[31].y(), 0.0, 1e-9);  // still straight
}

TEST(Continuation, RefusesAFixWithoutALoad) {
  auto sim = cantilever(5, Vec3(0, -1, 0));
  ContinuationOptions opt;
  opt.load = "clamp";
  EXPECT_THROW(continuation(*sim, opt), InputError);
  opt.load = "nothing";
  EXPECT_THROW(continuation(*sim, opt), InputError);
}

// The e-cone growth's excess angle is a continuation parameter (docs/models.md §9.4); a
// growth without one is refused, and a refused start leaves the parameter where it was.
TEST(Continuation, WalksTheEconeExcessAngleAndRefusesOtherGrowths) {
  auto sim = cantilever(5, Vec3(0, -1, 0));
  sim->add_growth("cone", "econe", P({{"phi_e", 0.3}}));
  sim->add_growth("iso", "isotropic", P({{"factor", 1.1}}));
  Style* cone = sim->find_style("cone");
  ASSERT_TRUE(cone->set_continuation_parameter(2.5));
  EXPECT_EQ(cone->value("phi_e"), 2.5);
  EXPECT_FALSE(cone->set_continuation_parameter(-7.0));  // below -2 pi: no cone
  EXPECT_EQ(cone->value("phi_e"), 2.5);
  ContinuationOptions opt;
  opt.load = "iso";
  try {
    continuation(*sim, opt);
    ADD_FAILURE() << "an isotropic growth was walked";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("econe walks phi_e"), std::string::npos) << e.what();
  }
  // the cantilever's forces do not depend on a growth no shell uses: refused, phi_e put back
  opt.load = "cone";
  opt.lambda0 = 2.5;
  EXPECT_THROW(continuation(*sim, opt), InputError);
  EXPECT_EQ(cone->value("phi_e"), 2.5);
}

TEST(Continuation, SwitchesOntoTheBuckledBranchAndFollowsTheElastica) {
  // the column of the last test, switched onto the bifurcated branch at P_cr: along it the
  // elastica gives lambda / P_cr = (2 K(k) / pi)^2 for the tip's lateral deflection
  // delta / L = 2 k / K(k) (Timoshenko & Gere; increasing in k up to k = 0.5 and beyond)
  auto sim = cantilever(41, Vec3(-1.0, 0, 0));
  const double pcr = M_PI * M_PI / 4.0;
  auto elastica_load = [&](double delta) {
    double lo = 0.0, hi = 0.6;
    for (int i = 0; i < 100; ++i) {
      const double k = 0.5 * (lo + hi);
      (2 * k / std::comp_ellint_1(k) < delta ? lo : hi) = k;
    }
    const double k = 0.5 * (lo + hi);
    return pcr * std::pow(2 * std::comp_ellint_1(k) / M_PI, 2.0);
  };
  ContinuationOptions opt;
  opt.load = "load";
  opt.ds = 1e-5;
  opt.ds_max = 0.05;
  opt.points = 2000;
  opt.lambda_max = 4.0;  // below the second critical load, 9 P_cr
  opt.switch_branch = true;
  bool on_branch = false;
  int checked = 0;
  double worst = 0.0, delta_max = 0.0;
  opt.callback = [&](Simulation& s, const ContinuationPoint& p) {
    if (p.event == "bifurcation point") {
      on_branch = true;
      return false;
    }
    if (!on_branch) return false;
    const double delta = std::abs(s.nodes().x[41].y());
    EXPECT_EQ(p.negative_pivots, 0) << "the buckled branch is stable, lambda " << p.lambda;
    if (delta > 0.05) {  // away from the critical point, where both sides are flat
      worst = std::max(worst, std::abs(p.lambda - elastica_load(delta)) / pcr);
      ++checked;
    }
    delta_max = std::max(delta_max, delta);
    return delta > 0.55;
  };
  const ContinuationResult r = continuation(*sim, opt);
  EXPECT_EQ(r.bifurcation_points, 1);
  EXPECT_TRUE(on_branch);
  EXPECT_GE(checked, 5);
  EXPECT_GT(delta_max, 0.55);
  EXPECT_LT(worst, 5e-4);  // measured 1.0e-4 at 41 nodes, the discretisation error of P_cr
}

TEST(EndMomentFix, ForcesAndHessianMatchItsEnergy) {
  for (const char* end : {"head", "tail"}) {
    Simulation sim(2, 1);
    sim.add_chain("w", wiggly_chain(6, 2, 7, 0.4), 1.0, false);
    sim.add_bond("spring", P({{"k", 30.0}}));
    sim.add_fix("turn", "moment2d",
                P({{"chain", std::string("w")}, {"end", std::string(end)}, {"moment", 0.7}}));
    EXPECT_LT(fd_force_error(sim), 1e-6) << end;
    EXPECT_LT(fd_hessian_error(sim), 1e-7) << end;
    // a moment alone: no net force, and the torque about any point is M
    sim.compute_forces();
    Vec3 net = Vec3::Zero();
    double torque = 0.0;
    Simulation bare(2, 1);
    bare.add_chain("w", wiggly_chain(6, 2, 7, 0.4), 1.0, false);
    bare.add_fix("turn", "moment2d",
                 P({{"chain", std::string("w")}, {"end", std::string(end)}, {"moment", 0.7}}));
    bare.compute_forces();
    for (size_t i = 0; i < bare.nodes().size(); ++i) {
      net += bare.nodes().f[i];
      const Vec3& x = bare.nodes().x[i];
      torque += x.x() * bare.nodes().f[i].y() - x.y() * bare.nodes().f[i].x();
    }
    EXPECT_LT(net.norm(), 1e-12);
    EXPECT_NEAR(torque, 0.7, 1e-12);
  }
}

TEST(EndMomentFix, RollsAClampedWireIntoAFullCircle) {
  // pure bending: an end moment M bends the cantilever into an arc of curvature M / EI, its
  // tip at (sin(kappa L) / kappa, (1 - cos(kappa L)) / kappa); continuation in the load
  // factor of M0 = 2 pi EI / L closes the circle at lambda = 1
  const int N = 41;
  auto sim = cantilever(N, Vec3(0, 0, 0));
  sim->add_fix("roll", "moment2d", P({{"chain", std::string("beam")}, {"moment", 2 * M_PI}}));
  ContinuationOptions opt;
  opt.load = "roll";
  opt.ds = 0.05;
  opt.ds_max = 0.2;
  opt.lambda_max = 1.0;
  opt.points = 500;
  double worst = 0.0, last = 0.0;
  opt.callback = [&](Simulation& s, const ContinuationPoint& p) {
    EXPECT_EQ(p.negative_pivots, 0);
    const double kappa = 2 * M_PI * std::min(p.lambda, 1.0);
    if (p.lambda > 1.0 || kappa < 1e-9) return false;
    const Vec3 tip = s.nodes().x[N];
    const Vec3 ref(std::sin(kappa) / kappa, (1 - std::cos(kappa)) / kappa, 0.0);
    worst = std::max(worst, (tip - ref).norm());
    last = p.lambda;
    return false;
  };
  const ContinuationResult r = continuation(*sim, opt);
  EXPECT_GT(r.lambda, 1.0);
  EXPECT_GT(last, 0.8);
  EXPECT_LT(worst, 1e-3);  // O(h^2) of the discrete arc: measured 4.7e-4
  EXPECT_EQ(r.limit_points + r.bifurcation_points, 0);
}

TEST(Hessian, StraightRodMatchesFiniteDifferencesOfItsForces) {
  for (bool closed : {false, true}) {
    Simulation sim(3, 1);
    sim.add_chain("r", wiggly_chain(7, 3, 13, 0.45), 1.0, closed);
    sim.add_bond("rod/straight", P({{"YI", 2.0}}));
    sim.add_bond("spring", P({{"k", 50.0}}));
    EXPECT_LT(fd_hessian_error(sim), 1e-7) << "closed " << closed;
  }
}

TEST(Newton, BucklesA3dRodOntoTheElastica) {
  // the column of BucklesPastEulersLoadOntoTheElastica as a discrete elastic rod in 3D
  // (rod/straight): Newton from a slightly bowed state to the buckled elastica
  const double k = 0.5, Kk = std::comp_ellint_1(k);
  const double load = std::pow(2.0 * Kk / M_PI, 2.0) * M_PI * M_PI / 4.0;
  const int N = 41;
  const double h = 1.0 / (N - 0.5);
  Simulation sim(3, 1);
  sim.verbose = false;
  std::vector<Vec3> pts;
  for (int i = 0; i <= N; ++i) {
    const double x = -h / 2 + i * h;
    pts.emplace_back(x, 1e-4 * x * x, 0.0);
  }
  sim.add_chain("rod", pts, h, false);
  sim.add_bond("spring", P({{"k", 1e5 / h}}));
  sim.add_bond("rod/straight", P({{"YI", 1.0}}));
  sim.set_group("base", {0, 1});
  sim.set_group("tip", {N});
  sim.add_fix("clamp", "clamp", P({{"group", std::string("base")}}));
  sim.add_fix("load", "force/constant",
              P({{"group", std::string("tip")}, {"force", std::vector<double>{-load, 0.0, 0.0}}}));
  const long it = sim.minimize(1e-8, 400, "newton");
  EXPECT_LT(it, 400);
  ASSERT_LT(sim.max_force(), 1e-8);
  EXPECT_NEAR(std::abs(sim.nodes().x[N].y()), 2.0 * k / Kk, 0.01);
  EXPECT_NEAR(sim.nodes().x[N].z(), 0.0, 1e-6);  // it stays in its plane
}

// Contact Hessians (src/contact_hessian.hpp): the distance's envelope over the closest
// point's free parameters. 2D node-edge: a wire lying across another, its nodes pressed
// onto the other's edges inside them and near their ends (a clamped parameter), at two
// exponents of the law.
TEST(Hessian, NodeEdgeContactMatchesFiniteDifferencesOfItsForces) {
  for (double p : {2.0, 1.0}) {
    Simulation sim(2, 1);
    sim.verbose = false;
    sim.add_chain("a", {Vec3(0, 0, 0), Vec3(1, 0.05, 0), Vec3(2, -0.02, 0), Vec3(3, 0, 0)}, 1.0,
                  false);
    sim.add_chain("b",
                  {Vec3(0.4, 0.8, 0), Vec3(1.35, 0.72, 0), Vec3(2.2, 0.9, 0), Vec3(3.3, 0.75, 0)},
                  1.0, false);
    sim.add_bond("spring", P({{"k", 40.0}}));
    sim.add_pair("contact/node-edge",
                 P({{"diameter", 1.0}, {"stiffness", 300.0}, {"exponent", p}, {"skin", 0.3}}));
    sim.compute_forces();
    EXPECT_GE(sim.find_style("contact/node-edge")->value("contacts"), 4) << p;
    EXPECT_LT(fd_hessian_error(sim), 1e-6) << "exponent " << p;
  }
}

// 3D segment contact: two rods crossing at a skew angle (both parameters free), and a
// rod ending against another's side (one parameter at its end).
TEST(Hessian, SegmentContactMatchesFiniteDifferencesOfItsForces) {
  for (double p : {1.0, 2.0}) {
    Simulation sim(3, 1);
    sim.verbose = false;
    sim.add_chain("a", {Vec3(-1, 0, 0), Vec3(0.1, 0.05, 0), Vec3(1.2, 0, 0.03)}, 1.0, false);
    sim.add_chain("b", {Vec3(0.2, -1, 0.8), Vec3(-0.1, 0.2, 0.75), Vec3(0.3, 1.1, 0.85)}, 1.0,
                  false);
    sim.add_chain("c", {Vec3(1.0, 0.1, 2.5), Vec3(1.05, 0.0, 1.3), Vec3(0.95, 0.05, 0.6)}, 1.0,
                  false);
    sim.add_bond("spring", P({{"k", 40.0}}));
    sim.add_pair("contact/segment",
                 P({{"radius", 0.5}, {"stiffness", 300.0}, {"exponent", p}, {"skin", 0.3}}));
    sim.compute_forces();
    EXPECT_GE(sim.find_style("contact/segment")->value("contacts"), 3) << p;
    EXPECT_LT(fd_hessian_error(sim), 1e-6) << "exponent " << p;
  }
}

// With friction the stick springs carry no energy of the positions: no Hessian, and
// Newton says so rather than solving without them.
TEST(Hessian, FrictionalContactHasNone) {
  Simulation sim(2, 1);
  sim.verbose = false;
  sim.add_chain("a", {Vec3(0, 0, 0), Vec3(1, 0, 0)}, 1.0, false);
  sim.add_pair("contact/node-edge",
               P({{"diameter", 1.0}, {"stiffness", 300.0}, {"mu_static", 0.3}}));
  sim.compute_forces();
  Hessian H;
  EXPECT_FALSE(sim.pairs()[0]->add_hessian(sim.context(), H));
}

// The walls (wall/circle, wall/sphere): a ring pressed into a circular wall from inside,
// and a 3D wire pressed onto a sphere from outside (the side the force softens the other
// way).
TEST(Hessian, WallsMatchFiniteDifferencesOfTheirForces) {
  {
    std::vector<Vec3> pts;
    for (int i = 0; i < 16; ++i) {
      const double a = 2 * M_PI * i / 16;
      pts.emplace_back((5.0 + 0.1 * std::sin(3 * a)) * std::cos(a),
                       (5.0 + 0.1 * std::sin(3 * a)) * std::sin(a), 0);
    }
    Simulation ring(2, 1);
    ring.verbose = false;
    ring.add_chain("ring", pts, 1.0, true);
    ring.add_bond("spring", P({{"k", 40.0}}));
    ring.add_fix("cavity", "wall/circle",
                 P({{"radius", 5.3}, {"diameter", 1.0}, {"stiffness", 200.0}, {"exponent", 2.0}}));
    ring.compute_forces();
    EXPECT_GE(ring.find_style("cavity")->value("contacts"), 8);
    EXPECT_LT(fd_hessian_error(ring), 1e-6);
  }
  Simulation sim(3, 1);
  sim.verbose = false;
  sim.add_chain(
      "w", {Vec3(-1.5, 0.2, 2.3), Vec3(-0.5, 0.1, 2.35), Vec3(0.5, -0.1, 2.3), Vec3(1.5, 0.0, 2.4)},
      1.0, false);
  sim.add_bond("spring", P({{"k", 40.0}}));
  sim.add_fix("ball", "wall/sphere",
              P({{"radius", 2.0},
                 {"diameter", 1.0},
                 {"stiffness", 200.0},
                 {"exponent", 1.0},
                 {"side", std::string("outside")}}));
  sim.compute_forces();
  EXPECT_GE(sim.find_style("ball")->value("contacts"), 2);
  EXPECT_LT(fd_hessian_error(sim), 1e-6);
}

// Newton through contact: a clamped wire pushed down at its middle onto a second clamped
// wire (node-edge contact) comes to the equilibrium FIRE finds, in few iterations.
TEST(Newton, SolvesAWirePressedOntoAnother) {
  auto scene = [](Simulation& sim) {
    sim.verbose = false;
    std::vector<Vec3> top, bottom;
    for (int i = 0; i <= 12; ++i) {
      top.emplace_back(0.5 * i, 1.02, 0);
      bottom.emplace_back(0.5 * i + 0.25, 0.0, 0);
    }
    sim.add_chain("top", top, 1.0, false);
    sim.add_chain("bottom", bottom, 1.0, false);
    sim.add_bond("spring", P({{"k", 2000.0}}));
    sim.add_bond("bend2d", P({{"k", 20.0}}));
    sim.add_pair("contact/node-edge", P({{"diameter", 1.0}, {"stiffness", 500.0}}));
    sim.set_group("ends", {0, 1, 11, 12, 13, 14, 24, 25});
    sim.set_group("middle", {6});
    sim.add_fix("hold", "clamp", P({{"group", std::string("ends")}}));
    sim.add_fix("push", "force/constant",
                P({{"group", std::string("middle")}, {"force", std::vector<double>{0.0, -3.0}}}));
  };
  Simulation newton(2, 1), fire(2, 1);
  scene(newton);
  scene(fire);
  const long it = newton.minimize(1e-9, 100, "newton");
  EXPECT_LT(newton.max_force(), 1e-9);
  EXPECT_LT(it, 30);
  fire.minimize(1e-9, 2000000, "fire");
  ASSERT_LT(fire.max_force(), 1e-9);
  EXPECT_GT(newton.find_style("contact/node-edge")->value("contacts"), 0);
  double worst = 0.0;
  for (size_t i = 0; i < newton.nodes().size(); ++i)
    worst = std::max(worst, (newton.nodes().x[i] - fire.nodes().x[i]).norm());
  EXPECT_LT(worst, 1e-6);
  EXPECT_LT(newton.nodes().x[6].y(), 1.0);  // pressed into the contact
}
