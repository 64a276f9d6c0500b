// Gear predictor-corrector for second-order ODEs in Nordsieck form (docs/models.md §3.4):
// r_k = dt^k/k! x^(k), k < q. Predict with Pascal's triangle, evaluate forces at the
// predicted position and velocity, correct every r_k with c_k times the
// acceleration mismatch. q = 5 (2D rods) and q = 6 (3D rods); q = 4 also offered.
#include <array>
#include <cmath>

#include "registry.hpp"
#include "simulation.hpp"

namespace slender {

class GearIntegrator : public IntegratorStyle {
 public:
  static ParamSpec spec(const std::string& name) {
    ParamSpec s("integrator", name,
                "Gear predictor-corrector, Nordsieck form with q stored values (docs/models.md "
                "§3.4)");
    s.integer("values", "stored values q: derivatives 0..q-1 (5: 2D wires, 6: 3D rods)")
        .def(5.0)
        .min(4)
        .max(6);
    declare_time_step(s, "time step, or \"auto\" = safety * limit / omega_max");
    return s;
  }
  GearIntegrator(Simulation& sim, const ParamValues& p)
      : q_(static_cast<int>(p.integer("values"))) {
    read_time_step(p);
    static const double c4[] = {1.0 / 6, 5.0 / 6, 1.0, 1.0 / 3};
    static const double c5[] = {19.0 / 120, 3.0 / 4, 1.0, 1.0 / 2, 1.0 / 12};
    static const double c6[] = {3.0 / 20, 251.0 / 360, 1.0, 11.0 / 18, 1.0 / 6, 1.0 / 60};
    const double* c = q_ == 4 ? c4 : q_ == 5 ? c5 : c6;
    for (int k = 0; k < q_; ++k) c_[k] = c[k];
    for (int k = 2; k < q_; ++k)
      r_[k] = &sim.nodes().require<Vec3>("gear.r" + std::to_string(k), Vec3::Zero());
    bind_extra(sim);
  }
  void coordinates_added(Simulation& sim) override { bind_extra(sim); }
  // Largest omega dt with |amplification| <= 1 on an undamped oscillator,
  // measured by tests/unit/test_integrators.cpp.
  double stability_limit() const override { return q_ == 4 ? 1.41 : q_ == 5 ? 0.42 : 0.48; }

  void setup(Simulation& sim) override {
    auto& n = sim.nodes();
    bind_extra(sim);
    if (initialized_ && epoch_ == sim.state_epoch && h_ == sim.dt) return;
    if (initialized_ && epoch_ == sim.state_epoch && h_ != sim.dt) {
      // keep the history, rescale the Nordsieck vector to the new step
      const double s = sim.dt / h_;
      for (int k = 2; k < q_; ++k) {
        const double sk = std::pow(s, k);
        for (auto& v : r_[k]->values()) v *= sk;
        for (auto& xr : xr_)
          for (auto& v : xr[k]->values()) v *= sk;
      }
    } else {
      // start from rest history: r2 from the current forces, higher derivatives zero
      for (size_t i = 0; i < n.size(); ++i) {
        (*r_[2])[i] = (0.5 * sim.dt * sim.dt / n.mass[i]) * n.f[i];
        for (int k = 3; k < q_; ++k) (*r_[k])[i].setZero();
      }
      auto& cs = sim.extra_coordinates();
      for (size_t s = 0; s < cs.size(); ++s)
        for (size_t i = 0; i < n.size(); ++i) {
          (*xr_[s][2])[i] = (0.5 * sim.dt * sim.dt / (*cs[s]->m)[i]) * (*cs[s]->f)[i];
          for (int k = 3; k < q_; ++k) (*xr_[s][k])[i].setZero();
        }
    }
    h_ = sim.dt;
    epoch_ = sim.state_epoch;
    initialized_ = true;
  }

  void step(Simulation& sim) override {
    // the value count is a template parameter so that the sweeps below unroll
    if (q_ == 4) return step_q<4>(sim);
    if (q_ == 5) return step_q<5>(sim);
    return step_q<6>(sim);
  }
  template <int Q>
  void step_q(Simulation& sim) {
    auto& n = sim.nodes();
    const double h = sim.dt;
    const size_t N = n.n_owned();
    std::array<Vec3*, Q> rk{};
    for (int k = 2; k < Q; ++k) rk[k] = r_[k]->values().data();
    // predict: r_k <- sum_{m>=k} C(m,k) r_m, done in place (Horner-like sweeps)
    for (size_t i = 0; i < N; ++i) {
      std::array<Vec3, Q> r;
      r[0] = n.x[i];
      r[1] = h * n.v[i];
      for (int k = 2; k < Q; ++k) r[k] = rk[k][i];
      for (int j = 0; j < Q - 1; ++j)
        for (int k = Q - 2; k >= j; --k) r[k] += r[k + 1];
      n.x[i] = r[0];
      n.v[i] = r[1] / h;
      for (int k = 2; k < Q; ++k) rk[k][i] = r[k];
    }
    predict_extra<Q>(sim);
    sim.compute_forces();
    for (int k = 2; k < Q; ++k) rk[k] = r_[k]->values().data();  // in case storage moved
    const double half_h2 = 0.5 * h * h;
    for (size_t i = 0; i < N; ++i) {
      const Vec3 delta = (half_h2 / n.mass[i]) * n.f[i] - rk[2][i];
      n.x[i] += c_[0] * delta;
      n.v[i] += (c_[1] / h) * delta;
      for (int k = 2; k < Q; ++k) rk[k][i] += c_[k] * delta;
    }
    correct_extra<Q>(sim);
    sim.end_of_step();
  }

  // Generalised coordinates (rod quaternions): their own Nordsieck arrays.
  void bind_extra(Simulation& sim) {
    xr_.clear();
    for (auto& c : sim.extra_coordinates()) {
      if (c->follows_positions)
        throw InputError("integrator 'gear' cannot run the frames '" + c->name +
                         "': a style moves them with the positions (bond rod/cosserat with "
                         "director = \"tangent\"); use verlet");
      std::array<Property<Vec4>*, 6> a{};
      for (int k = 2; k < q_; ++k)
        a[k] =
            &sim.nodes().require<Vec4>("gear." + c->name + ".r" + std::to_string(k), Vec4::Zero());
      xr_.push_back(a);
    }
  }
  // Raw pointers hoisted out of the node loops: through the Property pointers the
  // compiler reloads every base address per node (the quaternion sweeps cost as much
  // as the rod forces before). Same arithmetic, same order: results are unchanged.
  template <int Q>
  void predict_extra(Simulation& sim) {
    const double h = sim.dt;
    auto& cs = sim.extra_coordinates();
    if (xr_.size() != cs.size()) bind_extra(sim);
    const size_t N = sim.nodes().n_owned();
    for (size_t s = 0; s < cs.size(); ++s) {
      const Coordinates& c = *cs[s];
      Vec4* const q = c.q->values().data();
      Vec4* const v = c.v->values().data();
      const int* const fixed = c.fixed->values().data();
      std::array<Vec4*, Q> rk{};
      for (int k = 2; k < Q; ++k) rk[k] = xr_[s][k]->values().data();
      for (size_t i = 0; i < N; ++i) {
        if (fixed[i]) continue;
        std::array<Vec4, Q> r;
        r[0] = q[i];
        r[1] = h * v[i];
        for (int k = 2; k < Q; ++k) r[k] = rk[k][i];
        for (int j = 0; j < Q - 1; ++j)
          for (int k = Q - 2; k >= j; --k) r[k] += r[k + 1];
        q[i] = r[0];
        v[i] = r[1] / h;
        for (int k = 2; k < Q; ++k) rk[k][i] = r[k];
      }
    }
  }
  template <int Q>
  void correct_extra(Simulation& sim) {
    const double h = sim.dt, half_h2 = 0.5 * h * h;
    auto& cs = sim.extra_coordinates();
    const size_t N = sim.nodes().n_owned();
    for (size_t s = 0; s < cs.size(); ++s) {
      const Coordinates& c = *cs[s];
      Vec4* const q = c.q->values().data();
      Vec4* const v = c.v->values().data();
      const Vec4* const f = c.f->values().data();
      const double* const m = c.m->values().data();
      const int* const fixed = c.fixed->values().data();
      std::array<Vec4*, Q> rk{};
      for (int k = 2; k < Q; ++k) rk[k] = xr_[s][k]->values().data();
      for (size_t i = 0; i < N; ++i) {
        if (fixed[i]) continue;
        const Vec4 delta = (half_h2 / m[i]) * f[i] - rk[2][i];
        q[i] += c_[0] * delta;
        v[i] += (c_[1] / h) * delta;
        for (int k = 2; k < Q; ++k) rk[k][i] += c_[k] * delta;
        if (c.unit) {
          std::array<Vec4*, 6> d{};
          d[0] = &v[i];
          for (int k = 2; k < Q; ++k) d[k - 1] = &rk[k][i];
          c.constrain(i, {d[0], d[1], d[2], d[3], d[4]});
        }
      }
    }
  }

  void save_state(StateMap& st) const override {
    st["gear"] = {initialized_ ? 1.0 : 0.0, h_, static_cast<double>(epoch_)};
  }
  void load_state(const StateMap& st) override {
    auto& g = saved_array(st, "gear", 3);
    initialized_ = g[0] != 0.0;
    h_ = g[1];
    epoch_ = saved_long(g[2]);
  }

 private:
  int q_;
  std::array<double, 6> c_{};
  std::array<Property<Vec3>*, 6> r_{};
  std::vector<std::array<Property<Vec4>*, 6>> xr_;
  bool initialized_ = false;
  double h_ = 0.0;
  long epoch_ = -1;
};

}  // namespace slender

SLENDER_REGISTER_STYLE(slender::IntegratorStyle, "gear", slender::GearIntegrator)
