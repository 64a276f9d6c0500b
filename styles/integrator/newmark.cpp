// Explicit Newmark (docs/models.md §6.5, (5.16)-(5.19)) with beta = 0:
//   x+ = x + dt v + dt^2/2 a,   (1 + gamma dt c) a+ = f(x+)/m - c (v + (1 - gamma) dt a),
//   v+ = v + dt ((1 - gamma) a + gamma a+),
// with mass-proportional damping C = c M. gamma = 1 (the thesis) is first order and
// damps high frequencies; gamma = 1/2 is central differences. Stable for
// omega dt <= 1/sqrt(gamma/2).
//
// Adaptive step (our choice, docs/models.md §6.5 [C]): the Zienkiewicz–Xie local error
// of Newmark, e = dt^2 (1/6 - beta) (a+ - a), measured as eta = max_I |e_I| / l_min
// (l_min: the shortest edge of the scene). A step with eta > tol is rejected and
// retried with dt/2; otherwise the next dt is dt * min(1.2, max(0.5, 0.9 (tol/eta)^(1/3))),
// never above the stable step of the stiff terms. Every change is logged with its reason.
#include <cmath>
#include <cstdio>
#include <fstream>

#include "registry.hpp"
#include "shell/trimesh.hpp"
#include "simulation.hpp"

namespace slender {

class NewmarkIntegrator : public IntegratorStyle {
 public:
  static ParamSpec spec(const std::string& name) {
    ParamSpec s("integrator", name,
                "explicit Newmark (beta = 0) with mass-proportional damping and an optional "
                "adaptive step (docs/models.md §6.5)");
    declare_time_step(s,
                      "time step (the first one when adaptive), or \"auto\" = safety * "
                      "sqrt(2/gamma) / omega_max");
    s.real("gamma", "Newmark gamma: 1 (thesis, damping, 1st order) .. 0.5 (central differences)")
        .def(1.0)
        .min(0.5)
        .max(1.0);
    s.real("damping", "mass-proportional damping c (C = c M), per time unit")
        .def(0.0)
        .nonnegative();
    s.boolean("adaptive", "adapt dt to the local error estimate").def(false);
    s.real("tol", "tolerance eta_tol of the error estimate (fraction of l_min)")
        .def(1e-3)
        .positive();
    s.real("dt_min", "smallest step the adaptive control may take").def(1e-12).positive();
    s.string("log", "file that records every change of dt with its reason");
    s.output("rejected", "number of steps rejected by the adaptive control");
    s.output("eta", "error estimate of the last step over the shortest edge (0 unless adaptive)");
    s.output("dt_cap", "stable step of the stiff terms, the cap on the adaptive dt");
    s.output("dt_next", "time step the next step takes");
    return s;
  }
  NewmarkIntegrator(Simulation&, const ParamValues& p)
      : gamma_(p.real("gamma")),
        c_(p.real("damping")),
        adaptive_(p.boolean("adaptive")),
        tol_(p.real("tol")),
        dt_min_(p.real("dt_min")) {
    read_time_step(p);
    if (p.has("log")) {
      log_.open(p.str("log"));
      if (!log_) throw InputError("integrator 'newmark': cannot write log '" + p.str("log") + "'");
      log_ << "step,time,dt,eta,reason\n";
    }
  }
  double stability_limit() const override { return 1.0 / std::sqrt(0.5 * gamma_); }

  void setup(Simulation& sim) override {
    if (!sim.extra_coordinates().empty())
      throw InputError(
          "integrator 'newmark' does not integrate quaternion coordinates; use "
          "verlet or gear for Cosserat rods");
    a_ = &sim.nodes().require<Vec3>("newmark.a", Vec3::Zero());
    // the stable step of the stiff terms caps the adaptive control
    const double w = sim.omega_max();
    cap_ = w > 0 ? safety() * stability_limit() / w : sim.dt;
    if (requested_dt() > 0) cap_ = std::max(cap_, requested_dt());
    if (next_dt_ <= 0 || !adaptive_)
      next_dt_ = sim.dt;
    else
      next_dt_ = std::min(next_dt_, cap_);
    lmin_ = shortest_edge(sim);
    if (epoch_ != sim.state_epoch || !initialised_) {
      // start (or restart after outside changes) from the current forces
      for (size_t i = 0; i < sim.nodes().n_owned(); ++i) (*a_)[i] = accel(sim, i);
      epoch_ = sim.state_epoch;
      initialised_ = true;
    }
    // a deck that runs in short chunks starts many runs: log a start only when it
    // changes the step or its cap
    if (!started_ || next_dt_ != logged_dt_ || cap_ != logged_cap_)
      note(sim, next_dt_, 0.0, "run start (stable cap " + std::to_string(cap_) + ")");
    started_ = true;
    logged_cap_ = cap_;
  }

  void step(Simulation& sim) override {
    auto& n = sim.nodes();
    auto& a = *a_;
    const size_t N = n.n_owned();
    double h = next_dt_;
    if (adaptive_) {
      x0_ = n.x;
      v0_ = n.v;
    }
    anew_.resize(N);
    double eta = 0;
    for (;;) {
      sim.dt = h;
      for (size_t i = 0; i < N; ++i) n.x[i] += h * n.v[i] + (0.5 * h * h) * a[i];
      sim.compute_forces();
      eta = 0;
      for (size_t i = 0; i < N; ++i) {
        const Vec3 damp = c_ * (n.v[i] + ((1 - gamma_) * h) * a[i]);
        anew_[i] = (n.f[i] / n.mass[i] - damp) / (1 + gamma_ * h * c_);
        if (adaptive_) eta = std::max(eta, (anew_[i] - a[i]).norm());
      }
      eta *= h * h / 6.0 / lmin_;
      if (adaptive_ && eta > tol_ && h > dt_min_) {
        n.x = x0_;
        n.v = v0_;
        ++rejected_;
        h = std::max(0.5 * h, dt_min_);
        note(sim, h, eta, "rejected: error estimate above tol");
        continue;
      }
      break;
    }
    for (size_t i = 0; i < N; ++i) {
      n.v[i] += h * ((1 - gamma_) * a[i] + gamma_ * anew_[i]);
      a[i] = anew_[i];
    }
    last_eta_ = eta;
    sim.end_of_step();
    if (adaptive_) {
      double factor = eta > 0 ? 0.9 * std::cbrt(tol_ / eta) : 1.2;
      factor = std::min(1.2, std::max(0.5, factor));
      double next = h * factor;
      std::string why = factor >= 1 ? "error estimate below tol" : "error estimate near tol";
      if (next > cap_) {
        next = cap_;
        why = "stable-step cap";
      }
      if (std::abs(next - logged_dt_) > 0.2 * logged_dt_) note(sim, next, eta, why);
      next_dt_ = next;
    }
  }

  double value(const std::string& key) const override {
    if (key == "rejected") return static_cast<double>(rejected_);
    if (key == "eta") return last_eta_;
    if (key == "dt_cap") return cap_;
    if (key == "dt_next") return next_dt_;
    return IntegratorStyle::value(key);
  }
  void save_state(StateMap& s) const override { s["next_dt"] = {next_dt_}; }
  void load_state(const StateMap& s) override {
    if (auto it = s.find("next_dt"); it != s.end() && !it->second.empty()) next_dt_ = it->second[0];
    initialised_ = true;  // the accelerations came back with the node properties
  }

 private:
  // a = (f/m - c v) / (1 + gamma dt c): the start-up acceleration of the scheme
  Vec3 accel(Simulation& sim, size_t i) const {
    auto& n = sim.nodes();
    return (n.f[i] / n.mass[i] - c_ * n.v[i]) / (1 + gamma_ * sim.dt * c_);
  }
  static double shortest_edge(Simulation& sim) {
    double l = sim.topology().min_rest_length();
    for (auto& s : sim.topology().surfaces) l = std::min(l, shell::reference_edges(*s.mesh).min);
    return l < 1e299 ? l : 1.0;
  }
  void note(Simulation& sim, double dt, double eta, const std::string& why) {
    logged_dt_ = dt;
    if (log_.is_open()) {
      log_ << sim.step << ',' << sim.time << ',' << dt << ',' << eta << ",\"" << why << "\"\n";
      log_.flush();
    }
  }

  double gamma_, c_;
  bool adaptive_;
  double tol_, dt_min_;
  Property<Vec3>* a_ = nullptr;
  double cap_ = 0, next_dt_ = 0, lmin_ = 1, last_eta_ = 0, logged_dt_ = 0;
  long rejected_ = 0, epoch_ = -1;
  bool initialised_ = false, started_ = false;
  double logged_cap_ = 0;
  std::vector<Vec3> x0_, v0_, anew_;
  std::ofstream log_;
};

}  // namespace slender

SLENDER_REGISTER_STYLE(slender::IntegratorStyle, "newmark", slender::NewmarkIntegrator)
