#include "continuation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "simulation.hpp"
#include "statics.hpp"

namespace slender {

namespace {
std::string g6(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}
}  // namespace

ContinuationResult continuation(Simulation& sim, const ContinuationOptions& opt) {
  Style* fix = sim.find_style(opt.load);
  if (!fix)
    throw InputError(
        "continuation: load must name a fix, a shell or a growth, and there is no style '" +
        opt.load + "'");
  if (!(opt.ds > 0) || !(opt.ds_max >= opt.ds) || !(opt.ds_min > 0) || !(opt.ds_min <= opt.ds))
    throw InputError("continuation: the steps need 0 < ds_min <= ds <= ds_max, got ds_min = " +
                     g6(opt.ds_min) + ", ds = " + g6(opt.ds) + ", ds_max = " + g6(opt.ds_max));
  if (!(opt.lambda_min <= opt.lambda0 && opt.lambda0 <= opt.lambda_max))
    throw InputError("continuation: lambda0 = " + g6(opt.lambda0) +
                     " lies outside [lambda_min, lambda_max] = [" + g6(opt.lambda_min) + ", " +
                     g6(opt.lambda_max) + "]");
  require_positions_only(sim, "continuation");
  if (!fix->set_continuation_parameter(opt.lambda0))
    throw InputError(
        "continuation: " + std::string(fix->family_name()) + " '" + opt.load + "' (" +
        fix->style_name() +
        ") has no load to scale (force/constant, moment2d, prescribe and koiter have; growth "
        "econe walks phi_e)");

  auto& n = sim.nodes();
  const size_t N = n.n_owned();
  ++sim.state_epoch;
  StaticSystem sys(sim);
  auto set_lambda = [&](double l) { fix->set_continuation_parameter(l); };
  // the reference load q on the free components: the forces at lambda = 1 less those at 0
  // (the load is linear in lambda)
  set_lambda(1.0);
  sim.compute_forces();
  sys.assemble();
  Eigen::VectorXd q = sys.forces();
  set_lambda(0.0);
  sim.compute_forces();
  q -= sys.forces();
  if (!(q.norm() > 0)) {
    set_lambda(opt.lambda0);
    throw InputError("continuation: the load of '" + opt.load + "' acts on no free component");
  }
  double lambda = opt.lambda0;
  set_lambda(lambda);
  sim.compute_forces();
  // q = df/dlambda at the current state (a follower load, e.g. an end moment, turns with
  // the nodes; a prescribed motion moves the held nodes, on which the forces depend
  // nonlinearly): a forward difference over a small step of lambda, the state's forces
  // restored (exact to round-off for a load linear in lambda)
  auto load_vector = [&] {
    const Eigen::VectorXd f0 = sys.forces();
    const double eps = 1e-6 * std::max(1.0, std::abs(lambda));
    set_lambda(lambda + eps);
    sim.compute_forces();
    Eigen::VectorXd dq = (sys.forces() - f0) / eps;
    set_lambda(lambda);
    sim.compute_forces();
    return dq;
  };
  auto apply = [&](const Eigen::VectorXd& dx) {
    const std::vector<Vec3> d = sys.per_node(dx);
    for (size_t i = 0; i < N; ++i) n.x[i] += d[i];
  };

  // the start: Newton at fixed lambda
  int it0 = 0;
  for (; sim.max_force() >= opt.ftol; ++it0) {
    sys.assemble();
    if (it0 >= opt.max_iterations || sys.factorize() < 0)
      throw InputError("continuation: the start (lambda0 = " + g6(lambda) +
                       ") is not an equilibrium that Newton reaches in " +
                       std::to_string(opt.max_iterations) + " iterations (largest force " +
                       g6(sim.max_force()) +
                       "); relax it first, e.g. sim:minimize{method = \"newton\"}");
    apply(sys.solve(sys.forces()));
    sim.compute_forces();
  }
  sys.assemble();
  long neg = sys.factorize();
  if (neg < 0) throw InputError("continuation: the stiffness matrix is singular at the start");
  q = load_vector();
  Eigen::VectorXd v = sys.solve(q);
  // lambda is weighed like the displacement a unit of it causes at the start (§9.4)
  const double psi2 = v.squaredNorm();
  if (!(psi2 > 0) || !std::isfinite(psi2))
    throw InputError("continuation: the load causes no displacement at the start");
  Eigen::VectorXd tx;
  double tl = 0.0;
  auto tangent = [&](const Eigen::VectorXd& w, Eigen::VectorXd& t, double& l) {
    const double norm = std::sqrt(w.squaredNorm() + psi2);
    t = w / norm;
    l = 1.0 / norm;
  };
  tangent(v, tx, tl);
  if (!(opt.lambda_max > lambda)) {  // only downwards is open
    tx = -tx;
    tl = -tl;
  }

  ContinuationResult res;
  res.lambda = lambda;
  ContinuationPoint pt{0, lambda, neg, it0, 0.0, "", lambda};
  if (opt.callback && opt.callback(sim, pt)) return res;
  double ds = opt.ds;
  std::vector<Vec3> x0, x1;
  bool switched = false, skip_event = false;
  // From (x0, l0) along the unit tangent (t, t_l), by the arc length step: the tangent
  // predictor, then Newton on the forces and the arc-length condition
  // t . u + psi^2 t_l dl = step (linear, so it stays satisfied). Leaves the state at the
  // solution and returns the iterations, or -1 where it does not converge.
  Eigen::VectorXd u;
  double dl = 0.0;
  auto correct = [&](double l0, const Eigen::VectorXd& t, double t_l, double step) {
    for (size_t i = 0; i < N; ++i) n.x[i] = x0[i];
    u = step * t;
    dl = step * t_l;
    apply(u);
    lambda = l0 + dl;
    set_lambda(lambda);
    sim.compute_forces();
    for (int it = 0; it < opt.max_iterations; ++it) {
      if (sim.max_force() < opt.ftol) return it;
      sys.assemble();
      if (sys.factorize() < 0) return -1;
      q = load_vector();
      const Eigen::VectorXd a = sys.solve(sys.forces()), b = sys.solve(q);
      const double den = t.dot(b) + psi2 * t_l;
      const double g = t.dot(u) + psi2 * t_l * dl - step;
      if (!(std::abs(den) > 0)) return -1;
      const double ddl = (-g - t.dot(a)) / den;
      const Eigen::VectorXd du = a + ddl * b;
      if (!du.allFinite()) return -1;
      u += du;
      dl += ddl;
      apply(du);
      lambda = l0 + dl;
      set_lambda(lambda);
      sim.compute_forces();
    }
    return sim.max_force() < opt.ftol ? opt.max_iterations : -1;
  };
  for (long k = 1; k <= opt.points; ++k) {
    x0.assign(n.x.begin(), n.x.begin() + static_cast<long>(N));
    const double l0 = lambda;
    int iters = -1;
    while ((iters = correct(l0, tx, tl, ds)) < 0) {
      ds *= 0.5;
      if (ds < opt.ds_min) {
        for (size_t i = 0; i < N; ++i) n.x[i] = x0[i];
        lambda = l0;
        set_lambda(lambda);
        sim.compute_forces();
        throw InputError("continuation: the corrector did not converge from lambda = " + g6(l0) +
                         " even with the step ds_min = " + g6(opt.ds_min) +
                         " (raise max_iterations or ftol, or lower ds_min); the state is the "
                         "last converged point");
      }
    }
    const double ds_used = ds;
    // stability and the next tangent at the new point, oriented along the step just taken
    sys.assemble();
    const long nneg = sys.factorize();
    Eigen::VectorXd tx1;
    double tl1 = 0.0;
    if (nneg >= 0) {
      q = load_vector();
      tangent(sys.solve(q), tx1, tl1);
    } else {  // exactly singular: the secant
      const double norm = std::sqrt(u.squaredNorm() + psi2 * dl * dl);
      tx1 = u / norm;
      tl1 = dl / norm;
    }
    if (tx1.dot(u) + psi2 * tl1 * dl < 0) {
      tx1 = -tx1;
      tl1 = -tl1;
    }
    std::string event;
    double critical = lambda;
    bool switch_now = false;
    if (skip_event) {  // the first step on a new branch: its inertia is the new reference
      skip_event = false;
      if (nneg >= 0) neg = nneg;
    } else if (nneg >= 0 && nneg != neg) {
      const bool limit = tl1 * tl < 0;
      event = limit ? "limit point" : "bifurcation point";
      ++(limit ? res.limit_points : res.bifurcation_points);
      // locate it: bisect the arc length from the last point until the count of negative
      // pivots changes within a step of 1e-6 of this one's
      x1.assign(n.x.begin(), n.x.begin() + static_cast<long>(N));
      const double l1 = lambda;
      double lo = 0.0, hi = ds_used;
      while (hi - lo > 1e-6 * ds_used) {
        const double mid = 0.5 * (lo + hi);
        if (correct(l0, tx, tl, mid) < 0) break;
        sys.assemble();
        const long m = sys.factorize();
        if (m == neg)
          lo = mid;
        else
          hi = mid;
        critical = lambda;
      }
      switch_now = !limit && opt.switch_branch && !switched;
      if (!switch_now) {
        for (size_t i = 0; i < N; ++i) n.x[i] = x1[i];
        lambda = l1;
        set_lambda(lambda);
        sim.compute_forces();
      }
      if (sim.verbose)
        std::printf("continuation: %s at lambda = %s (negative pivots %ld -> %ld)\n", event.c_str(),
                    g6(critical).c_str(), neg, nneg);
      neg = nneg;
    }
    tx = tx1;
    tl = tl1;
    if (switch_now) {
      // Branch switching (§9.4): from the bisected critical state, along the null vector
      // of K (inverse iteration), with lambda held at first: the bifurcated branch of a
      // symmetric (pitchfork) bifurcation leaves the critical point that way.
      switched = true;
      skip_event = true;
      sys.assemble();
      double shift = 0.0;
      while (sys.factorize(shift) < 0)
        shift = shift == 0.0 ? 1e-12 * sys.diagonal_scale() : 10 * shift;
      Eigen::VectorXd phi(sys.size());
      for (long i = 0; i < phi.size(); ++i) phi[i] = 1.0 + 0.5 * std::sin(1.7 * double(i) + 0.3);
      for (int it = 0; it < 20; ++it) {
        phi = sys.solve(phi);
        phi /= phi.norm();
      }
      long big = 0;
      phi.cwiseAbs().maxCoeff(&big);
      if (phi[big] < 0) phi = -phi;  // a sign that does not depend on the round-off
      tx = phi;
      tl = 0.0;
      if (sim.verbose)
        std::printf("continuation: switching to the bifurcated branch at lambda = %s\n",
                    g6(lambda).c_str());
    }
    if (iters <= 3)
      ds = std::min(1.5 * ds, opt.ds_max);
    else if (iters > 8)
      ds = std::max(0.6 * ds, opt.ds_min);
    res.points = k;
    res.lambda = lambda;
    pt = ContinuationPoint{k, lambda, neg, iters, ds_used, event, critical};
    if (opt.callback && opt.callback(sim, pt)) break;
    if (lambda > opt.lambda_max || lambda < opt.lambda_min) break;
  }
  for (auto& vel : n.v) vel.setZero();
  if (sim.verbose)
    std::printf(
        "continuation: %ld points, lambda %s at the end, %ld limit and %ld bifurcation "
        "points crossed\n",
        res.points, g6(res.lambda).c_str(), res.limit_points, res.bifurcation_points);
  return res;
}

}  // namespace slender
