// FIRE energy minimiser (Bitzek et al. 2006, with the FIRE 2.0 ordering): damped
// dynamics whose velocity is steered along the force, with an adaptive step.
// Generalised coordinates (rod quaternions) move with the nodes: one power test for
// all, but each family is steered along its own force with its own norms, since a
// quaternion's velocity and force are not in the units of a node's.
#include <cmath>

#include "registry.hpp"
#include "simulation.hpp"

namespace slender {

class FireIntegrator : public IntegratorStyle {
 public:
  static ParamSpec spec(const std::string& name) {
    ParamSpec s("integrator", name, "FIRE minimiser: inertial relaxation to a static equilibrium");
    declare_time_step(s, "initial time step, or \"auto\"");
    s.real("dt_max", "largest step as a multiple of the initial one").def(10.0).min(1.0);
    s.real("alpha", "initial velocity-mixing parameter").def(0.1).positive().max(1.0);
    s.integer("n_min", "downhill steps before the step may grow").def(5.0).min(0);
    s.real("f_inc", "step growth factor").def(1.1).min(1.0);
    s.real("f_dec", "step shrink factor on an uphill step").def(0.5).positive().max(1.0);
    s.real("f_alpha", "alpha decay factor").def(0.99).positive().max(1.0);
    s.real("dt_min", "smallest step as a multiple of the initial one")
        .def(0.02)
        .positive()
        .max(1.0);
    return s;
  }
  FireIntegrator(Simulation&, const ParamValues& p)
      : dtmax_factor_(p.real("dt_max")),
        alpha0_(p.real("alpha")),
        nmin_(p.integer("n_min")),
        finc_(p.real("f_inc")),
        fdec_(p.real("f_dec")),
        falpha_(p.real("f_alpha")),
        dtmin_factor_(p.real("dt_min")) {
    read_time_step(p);
  }
  double stability_limit() const override { return 2.0; }
  void setup(Simulation& sim) override {
    if (initialized_) {
      sim.dt = h_;
      return;
    }
    h_ = sim.dt;
    hmax_ = dtmax_factor_ * h_;
    const double stable = sim.suggest_dt(0.5);
    if (stable > 0) hmax_ = std::min(hmax_, stable);
    hmax_ = std::max(hmax_, h_);
    hmin_ = dtmin_factor_ * h_;
    alpha_ = alpha0_;
    npos_ = 0;
    initialized_ = true;
  }
  void step(Simulation& sim) override {
    auto& n = sim.nodes();
    const size_t N = n.n_owned();
    auto& cs = sim.extra_coordinates();
    // a quaternion's force counts only along |q| = 1: its radial part does no work
    for (auto& c : cs)
      if (c->unit)
        for (size_t i = 0; i < N; ++i) {
          Vec4& f = (*c->f)[i];
          f -= f.dot((*c->q)[i]) * (*c->q)[i];
        }
    auto free = [](const Coordinates& c, size_t i) { return !(*c.fixed)[i]; };
    double P = 0.0;
    for (size_t i = 0; i < N; ++i) P += n.f[i].dot(n.v[i]);
    for (auto& c : cs)
      for (size_t i = 0; i < N; ++i)
        if (free(*c, i)) P += (*c->f)[i].dot((*c->v)[i]);
    // P = 0 (at rest, e.g. right after a reset) is not uphill
    if (P >= 0) {
      if (++npos_ > nmin_) {
        h_ = std::min(h_ * finc_, hmax_);
        alpha_ *= falpha_;
      }
    } else {
      npos_ = 0;
      h_ = std::max(h_ * fdec_, hmin_);
      alpha_ = alpha0_;
      for (size_t i = 0; i < N; ++i) {
        n.x[i] -= 0.5 * h_ * n.v[i];
        n.v[i].setZero();
      }
      for (auto& c : cs)
        for (size_t i = 0; i < N; ++i)
          if (free(*c, i)) {
            (*c->q)[i] -= 0.5 * h_ * (*c->v)[i];
            (*c->v)[i].setZero();
            if (c->unit) c->constrain(i, {});
          }
    }
    sim.dt = h_;
    double vnorm = 0.0, fnorm = 0.0;
    for (size_t i = 0; i < N; ++i) {
      n.v[i] += (h_ / n.mass[i]) * n.f[i];
      vnorm += n.v[i].squaredNorm();
      fnorm += n.f[i].squaredNorm();
    }
    vnorm = std::sqrt(vnorm);
    fnorm = std::sqrt(fnorm);
    const double mix = fnorm > 0 ? alpha_ * vnorm / fnorm : 0.0;
    for (size_t i = 0; i < N; ++i) {
      n.v[i] = (1.0 - alpha_) * n.v[i] + mix * n.f[i];
      n.x[i] += h_ * n.v[i];
    }
    for (auto& c : cs) {
      double vq = 0.0, fq = 0.0;
      for (size_t i = 0; i < N; ++i)
        if (free(*c, i)) {
          (*c->v)[i] += (h_ / (*c->m)[i]) * (*c->f)[i];
          vq += (*c->v)[i].squaredNorm();
          fq += (*c->f)[i].squaredNorm();
        }
      const double mq = fq > 0 ? alpha_ * std::sqrt(vq / fq) : 0.0;
      for (size_t i = 0; i < N; ++i)
        if (free(*c, i)) {
          Vec4& v = (*c->v)[i];
          v = (1.0 - alpha_) * v + mq * (*c->f)[i];
          (*c->q)[i] += h_ * v;
          if (c->unit) c->constrain(i, {&v});
        }
    }
    sim.compute_forces();
    sim.end_of_step();
  }
  void save_state(StateMap& st) const override {
    st["fire"] = {initialized_ ? 1.0 : 0.0, h_, hmax_, alpha_, static_cast<double>(npos_), hmin_};
  }
  void load_state(const StateMap& st) override {
    auto& g = saved_array(st, "fire", 6);
    initialized_ = g[0] != 0.0;
    h_ = g[1];
    hmax_ = g[2];
    alpha_ = g[3];
    npos_ = saved_long(g[4]);
    hmin_ = g[5];
  }

 private:
  double dtmax_factor_, alpha0_;
  long nmin_;
  double finc_, fdec_, falpha_, dtmin_factor_;
  bool initialized_ = false;
  double h_ = 0, hmax_ = 0, hmin_ = 0, alpha_ = 0;
  long npos_ = 0;
};

}  // namespace slender

SLENDER_REGISTER_STYLE(slender::IntegratorStyle, "fire", slender::FireIntegrator)
