// L-BFGS energy minimiser (Nocedal & Wright, Numerical Optimization, Alg. 7.4 and 7.5):
// quasi-Newton steps on the node positions from the last `memory` position and force
// changes, with a backtracking (Armijo) line search on the potential energy. It needs
// forces that are the exact gradient of the recorded energy, which every style is
// finite-difference tested for; velocity-dependent forces vanish (the nodes are held
// at rest) and friction springs keep the force they had. Used by sim:minimize{method =
// "lbfgs"}; far fewer force evaluations than FIRE on stiff, smooth problems (shells).
// With precondition = "hessian" the two-loop recursion's initial inverse Hessian is the
// factorised exact Hessian, shifted until positive definite (docs/models.md §9.3): the
// thin shell's membrane and bending stiffnesses, (L/h)^2 apart, stop setting the count of
// iterations.
#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>

#include "registry.hpp"
#include "simulation.hpp"
#include "statics.hpp"

namespace slender {

class LbfgsMinimizer : public IntegratorStyle {
 public:
  static ParamSpec spec(const std::string& name) {
    ParamSpec s("integrator", name,
                "L-BFGS minimiser of the potential energy over the node positions (for "
                "sim:minimize{method = \"lbfgs\"}); nodes stay at rest, so dashpots vanish and "
                "friction springs keep their force; scenes with rod frames need \"fire\"");
    declare_time_step(s, "scene time step kept for the fixes (the minimiser does not use it)");
    s.integer("memory", "number of position/force-change pairs kept").def(10.0).min(1).max(100000);
    s.add("max_move", ParamType::RealOrAuto,
          "largest displacement of a node per iteration (length); set it below the contact "
          "distance in scenes with contact, so that no step jumps through a contact. \"auto\": "
          "unlimited")
        .def(std::string("auto"))
        .positive();
    s.string("precondition",
             "none: the initial inverse Hessian of the two-loop recursion is a scalar (the last "
             "pair's s.y / y.y); hessian: (K + mu I)^-1, the exact Hessian K of every force "
             "style factorised by sparse LDL^T with the smallest shift mu of a Levenberg ladder "
             "that makes it positive definite, at the start of the minimisation, every "
             "precondition_every iterations and after a restart (docs/models.md §9.3); for "
             "ill-conditioned scenes such as thin shells")
        .def(std::string("none"))
        .choices({"none", "hessian"});
    s.integer("precondition_every",
              "iterations between refactorisations of the preconditioner: a Hessian far from "
              "the current state (a large rotation since) preconditions badly (0: only at the "
              "start and after a restart)")
        .def(200.0)
        .min(0);
    s.output("restarts", "number of restarts from steepest descent after a failed line search");
    s.output("factorizations", "number of preconditioner factorisations (precondition = hessian)");
    s.output("evaluations", "number of force evaluations in the iterations");
    return s;
  }
  LbfgsMinimizer(Simulation&, const ParamValues& p)
      : memory_(static_cast<size_t>(p.integer("memory"))),
        precondition_(p.str("precondition") == "hessian"),
        precondition_every_(p.integer("precondition_every")),
        max_move_(p.is_auto("max_move") ? std::numeric_limits<double>::infinity()
                                        : p.real("max_move")) {
    read_time_step(p);
  }
  double stability_limit() const override { return 2.0; }
  bool advances_time() const override { return false; }

  void setup(Simulation& sim) override {
    require_positions_only(sim, "integrator 'lbfgs'");
    history_.clear();
    // before any curvature pair: the explicit-dynamics step, x += (dt^2 / m) f, which is
    // stable for the stiffest mode (dt from the scene's frequency estimate)
    const double dt = sim.suggest_dt(0.5);
    double m = 0.0;
    const auto& n = sim.nodes();
    for (size_t i = 0; i < n.n_owned(); ++i) m = std::max(m, n.mass[i]);
    gamma0_ = dt > 0 && m > 0 ? dt * dt / m : 1.0;
    if (!sim.forces_valid) sim.compute_forces();
    if (precondition_) {
      system_ = &sim.static_system();
      factor();  // names a style without a Hessian before the first step
    }
  }

  void step(Simulation& sim) override {
    auto& n = sim.nodes();
    const size_t N = n.n_owned();
    // g = -f; d = -H g by the two-loop recursion (buffers kept between iterations)
    auto& d = d_;
    auto& a = a_;
    d.assign(n.f.begin(), n.f.begin() + static_cast<long>(N));  // -g
    a.resize(history_.size());
    for (size_t k = history_.size(); k-- > 0;) {
      a[k] = history_[k].rho * dot(history_[k].s, d);
      axpy(-a[k], history_[k].y, d);
    }
    if (precondition_) {
      if (precondition_every_ > 0 && since_factor_ >= precondition_every_) factor();
      ++since_factor_;
      apply_preconditioner(d);
    } else {
      const double gamma = history_.empty() ? gamma0_
                                            : dot(history_.back().s, history_.back().y) /
                                                  dot(history_.back().y, history_.back().y);
      for (auto& v : d) v *= gamma;
    }
    for (size_t k = 0; k < history_.size(); ++k) {
      const double b = history_[k].rho * dot(history_[k].y, d);
      axpy(a[k] - b, history_[k].s, d);
    }
    double slope = -dot(n.f, d);  // g . d
    if (!(slope < 0)) {           // not downhill: forget the curvature, steepest descent
      history_.clear();
      if (precondition_) {
        d.assign(n.f.begin(), n.f.begin() + static_cast<long>(N));
        apply_preconditioner(d);
      } else {
        for (size_t i = 0; i < N; ++i) d[i] = gamma0_ * n.f[i];
      }
      slope = -dot(n.f, d);
    }
    double dmax = 0.0;
    for (auto& v : d) dmax = std::max(dmax, v.norm());
    double alpha = dmax > max_move_ ? max_move_ / dmax : 1.0;

    auto& x0 = x0_;
    auto& f0 = f0_;
    x0.assign(n.x.begin(), n.x.begin() + static_cast<long>(N));
    f0.assign(n.f.begin(), n.f.begin() + static_cast<long>(N));
    const double e0 = sim.potential_energy();
    const double c1 = 1e-4, noise = 1e-13 * std::max(std::abs(e0), 1e-300);
    bool accepted = false;
    for (int tries = 0; tries < 40 && !accepted; ++tries) {
      for (size_t i = 0; i < N; ++i) n.x[i] = x0[i] + alpha * d[i];
      sim.compute_forces();
      ++evaluations_;
      const double e1 = sim.potential_energy();
      // Armijo; near the minimum the energy change drowns in round-off, then a step
      // that lowers the slope along d is taken instead
      accepted = e1 <= e0 + c1 * alpha * slope ||
                 (std::abs(e1 - e0) <= noise && std::abs(dot(n.f, d)) <= std::abs(slope));
      if (!accepted) alpha *= 0.5;
    }
    if (!accepted) {
      // no decrease along d even for tiny steps: go back and restart from steepest descent
      for (size_t i = 0; i < N; ++i) n.x[i] = x0[i];
      sim.compute_forces();
      ++evaluations_;
      history_.clear();
      ++restarts_;
      if (precondition_) factor();
      sim.end_of_step();
      return;
    }
    // the new pair is built in spare_, which takes over the storage of the pair that
    // leaves the memory
    Pair& p = spare_;
    p.s.resize(N);
    p.y.resize(N);
    for (size_t i = 0; i < N; ++i) {
      p.s[i] = alpha * d[i];
      p.y[i] = f0[i] - n.f[i];  // change of the gradient
    }
    const double sy = dot(p.s, p.y);
    // keep only pairs with positive curvature (a nonconvex stretch would break H > 0)
    if (sy > 1e-12 * std::sqrt(dot(p.s, p.s) * dot(p.y, p.y))) {
      p.rho = 1.0 / sy;
      history_.push_back(std::move(p));
      spare_ = Pair{};
      if (history_.size() > memory_) {
        spare_ = std::move(history_.front());
        history_.pop_front();
      }
    }
    sim.end_of_step();
  }

  double value(const std::string& key) const override {
    if (key == "restarts") return static_cast<double>(restarts_);
    if (key == "evaluations") return static_cast<double>(evaluations_);
    if (key == "factorizations") return static_cast<double>(factorizations_);
    return IntegratorStyle::value(key);
  }

 private:
  struct Pair {
    std::vector<Vec3> s, y;
    double rho = 0.0;
  };
  // K (+ mu I) at the current state, factorised: mu up a ladder of tenfold shifts until no
  // pivot is negative (a free body's rigid motions and a state away from equilibrium make K
  // singular or indefinite), from 0, or from a tenth of the shift the last factorisation
  // (of this minimisation or the scene's last one) settled on, not below 1e-8 of the
  // largest diagonal entry: consecutive load increments need similar shifts, and each rung
  // is a factorisation.
  void factor() {
    system_->assemble();
    const double scale = system_->diagonal_scale();
    const double last = system_->last_shift();
    double mu = last > 0.0 ? std::max(0.1 * last, 1e-8 * scale) : 0.0;
    for (int tries = 0;; ++tries) {
      const long negative = system_->factorize(mu);
      ++factorizations_;
      if (negative == 0) break;
      if (tries > 60)
        throw InputError(
            "integrator 'lbfgs': the preconditioner's Hessian stays singular however it is "
            "shifted (NaN in the state?)");
      mu = mu == 0.0 ? 1e-8 * scale : 10.0 * mu;
    }
    system_->set_last_shift(mu);
    since_factor_ = 0;
  }
  // d <- (K + mu I)^-1 d over the free components (held ones 0)
  void apply_preconditioner(std::vector<Vec3>& d) const {
    const std::vector<Vec3> r = system_->per_node(system_->solve(system_->gather(d)));
    for (size_t i = 0; i < d.size(); ++i) d[i] = r[i];
  }
  static double dot(const std::vector<Vec3>& u, const std::vector<Vec3>& v) {
    double r = 0.0;
    const size_t N = std::min(u.size(), v.size());
    for (size_t i = 0; i < N; ++i) r += u[i].dot(v[i]);
    return r;
  }
  static void axpy(double a, const std::vector<Vec3>& x, std::vector<Vec3>& y) {
    for (size_t i = 0; i < y.size(); ++i) y[i] += a * x[i];
  }

  size_t memory_;
  bool precondition_;
  long precondition_every_;
  StaticSystem* system_ = nullptr;
  long since_factor_ = 0, factorizations_ = 0;
  double max_move_;
  double gamma0_ = 1.0;
  std::deque<Pair> history_;
  Pair spare_;
  std::vector<Vec3> d_, x0_, f0_;
  std::vector<double> a_;
  long restarts_ = 0, evaluations_ = 0;
};

}  // namespace slender

SLENDER_REGISTER_STYLE(slender::IntegratorStyle, "lbfgs", slender::LbfgsMinimizer)
