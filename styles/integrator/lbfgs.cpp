// L-BFGS energy minimiser (Nocedal & Wright, Numerical Optimization, Alg. 7.4 and 7.5):
// quasi-Newton steps on the node positions from the last `memory` position and force
// changes, with a backtracking (Armijo) line search on the potential energy. It needs
// forces that are the exact gradient of the recorded energy, which every style is
// finite-difference tested for; velocity-dependent forces vanish (the nodes are held
// at rest) and friction springs keep the force they had. Used by sim:minimize{method =
// "lbfgs"}; far fewer force evaluations than FIRE on stiff, smooth problems (shells).
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
    s.output("restarts", "number of restarts from steepest descent after a failed line search");
    s.output("evaluations", "number of force evaluations in the iterations");
    return s;
  }
  LbfgsMinimizer(Simulation&, const ParamValues& p)
      : memory_(static_cast<size_t>(p.integer("memory"))),
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
    const double gamma = history_.empty() ? gamma0_
                                          : dot(history_.back().s, history_.back().y) /
                                                dot(history_.back().y, history_.back().y);
    for (auto& v : d) v *= gamma;
    for (size_t k = 0; k < history_.size(); ++k) {
      const double b = history_[k].rho * dot(history_[k].y, d);
      axpy(a[k] - b, history_[k].s, d);
    }
    double slope = -dot(n.f, d);  // g . d
    if (!(slope < 0)) {           // not downhill: forget the curvature, steepest descent
      history_.clear();
      for (size_t i = 0; i < N; ++i) d[i] = gamma0_ * n.f[i];
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
    return IntegratorStyle::value(key);
  }

 private:
  struct Pair {
    std::vector<Vec3> s, y;
    double rho = 0.0;
  };
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
