// Velocity Verlet (kick-drift-kick). Second order, symplectic, stable for omega dt < 2.
#include "registry.hpp"
#include "simulation.hpp"

namespace slender {

class VelocityVerletIntegrator : public IntegratorStyle {
 public:
  static ParamSpec spec(const std::string& name) {
    ParamSpec s("integrator", name, "velocity Verlet, 2nd order, symplectic (omega dt < 2)");
    declare_time_step(s, "time step, or \"auto\" = safety * 2 / omega_max");
    s.boolean("adaptive",
              "set dt before every step to safety * 2 / omega, with omega from the contacts as "
              "they are (several per node, deep overlaps; never above dt)")
        .def(false);
    s.boolean("trust_measured",
              "with adaptive: the contacts' measured stiffness alone sets their share of omega, "
              "also below the nominal estimate (a contact at a tenth of a diameter of overlap), "
              "so that dt = \"auto\" grows up to the stable step of the terms that measure "
              "nothing (bonds, damping) while the contacts are soft or absent; no node then "
              "moves more than safety times a tenth of the shortest rest length per step "
              "(a contact beginning within a step stays near the nominal overlap; "
              "docs/performance.md)")
        .def(false);
    return s;
  }
  VelocityVerletIntegrator(Simulation&, const ParamValues& p)
      : adaptive_(p.boolean("adaptive")), trust_measured_(p.boolean("trust_measured")) {
    read_time_step(p);
    if (trust_measured_ && !adaptive_)
      throw InputError("integrator 'verlet': trust_measured needs adaptive = true");
  }
  bool adaptive() const override { return adaptive_; }
  bool trusts_measured() const override { return trust_measured_; }
  double stability_limit() const override { return 2.0; }
  void setup(Simulation&) override {}
  void step(Simulation& sim) override {
    auto& n = sim.nodes();
    const double h = sim.dt;
    const size_t N = n.n_owned();
    const int T = sim.threads();
    // nodes are independent here: one contiguous range per thread (threads.hpp)
    parallel_ranges(
        T, N,
        [&](int, size_t begin, size_t end) {
          for (size_t i = begin; i < end; ++i) {
            n.v[i] += (0.5 * h / n.mass[i]) * n.f[i];
            n.x[i] += h * n.v[i];
          }
          // generalised coordinates (rod quaternions) the same way, then back onto |q| = 1
          for (auto& c : sim.extra_coordinates())
            for (size_t i = begin; i < end; ++i) {
              if ((*c->fixed)[i]) continue;
              Vec4& v = (*c->v)[i];
              v += (0.5 * h / (*c->m)[i]) * (*c->f)[i];
              (*c->q)[i] += h * v;
              if (c->unit) c->constrain(i, {&v});
            }
        },
        kMinLightItemsPerThread);
    sim.compute_forces();
    parallel_ranges(
        T, N,
        [&](int, size_t begin, size_t end) {
          for (size_t i = begin; i < end; ++i) n.v[i] += (0.5 * h / n.mass[i]) * n.f[i];
          for (auto& c : sim.extra_coordinates())
            for (size_t i = begin; i < end; ++i) {
              if ((*c->fixed)[i]) continue;
              Vec4& v = (*c->v)[i];
              v += (0.5 * h / (*c->m)[i]) * (*c->f)[i];
              if (c->unit) v -= v.dot((*c->q)[i]) * (*c->q)[i];
            }
        },
        kMinLightItemsPerThread);
    sim.end_of_step();
  }

 private:
  bool adaptive_ = false, trust_measured_ = false;
};

}  // namespace slender

SLENDER_REGISTER_STYLE(slender::IntegratorStyle, "verlet", slender::VelocityVerletIntegrator)
