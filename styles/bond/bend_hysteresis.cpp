// 2D bending with plastic hysteresis (docs/models.md §2.2): kinematic hardening with a
// smooth quadratic transition. Per interior node the plastic curvature kappa_pl is
// a node property ("bend.plastic_curvature"), allocated only by this style.
//
// With x = kappa - kappa_pl the elastic curvature and K_e = k l0:
//   thresholds  x_p^+ = max(kappa_y, x0 + delta), x_p^- = min(-kappa_y, x0 - delta),
//               x0 = -K_h kappa_pl / K_e (the guard keeps M = 0 in the linear zone),
//               x_e^+- = x_p^+- -+ delta;
//   flow        x > x_p^+: kappa_pl += x - x_p^+ (and the mirror image);
//   moment      M = g(x) + K_h kappa_pl, g linear in [x_e^-, x_e^+] with slope K_e and
//               quadratic beyond it, reaching slope K_h at x_p^+- (C1 everywhere).
// The moment enters the nodal forces exactly as the elastic bend2d moment (§2.1).
// Energy reported under "bend" is the recoverable part (1/2 M^2 l0 / K_e in the
// linear zone, §2.7; the exact integral along the reversible transition beyond it);
// the energy made unrecoverable by plastic flow is accumulated exactly as "dissipated".
#include <array>
#include <cmath>
#include <random>

#include "chain_select.hpp"
#include "hinge2d.hpp"
#include "registry.hpp"

namespace slender {

class BendHysteresisBond : public ChainBondStyle {
 public:
  static ParamSpec spec(const std::string& name) {
    ParamSpec s("bond", name,
                "2D bending spring with plastic hysteresis: kinematic hardening, smooth transition "
                "(docs/models.md §2.2)");
    s.real("k", "elastic bending spring k2 = YI/l0 (moment per radian); K_e = k2 l0")
        .required()
        .positive();
    s.real("yield_curvature", "kappa_y: half-width of the elastic range (>= pi/l0: purely elastic)")
        .required()
        .nonnegative();
    s.real("hardening_ratio", "K_h / K_e, the plastic (hardening) slope over the elastic one")
        .def(0.05)
        .min(0.0)
        .max(1.0, true);
    s.real("transition", "delta: width of the quadratic transition (default kappa_y / 2)")
        .nonnegative();
    s.boolean("guard", "widen the elastic range so that M = 0 stays in its linear part").def(true);
    s.boolean("saturate",
              "the literal reading of the thesis' Alg. 1 (docs/models.md §2.2): the moment is g(x) "
              "alone, without K_h kappa_pl, so it stops growing once the node flows (the hardening "
              "slope acts only inside the transition)")
        .def(false);
    s.real("initial_plastic",
           "random initial kappa_pl, uniform in +-value (seeded symmetry breaking)")
        .def(0.0)
        .nonnegative();
    s.real("damping",
           "bending dashpot gamma_r: the moment gains gamma_r dzeta/dt (docs/models.md §2.1)")
        .def(0.0)
        .nonnegative();
    declare_node_fields(s);
    declare_chains(s);
    s.output("dissipated", "energy dissipated by plastic flow since the start");
    s.output("work",
             "work done on the hinges since the start: dissipated plus the change of recoverable "
             "energy");
    s.output("recoverable",
             "recoverable bending energy at the last force evaluation (as reported under bend)");
    return s;
  }

  BendHysteresisBond(Context& sim, const ParamValues& p)
      : ChainBondStyle(sim, p),
        k_(p.real("k")),
        ky_(p.real("yield_curvature")),
        ratio_(p.real("hardening_ratio")),
        delta_(p.has("transition") ? p.real("transition") : 0.5 * p.real("yield_curvature")),
        guard_(p.boolean("guard")),
        memory_(p.boolean("saturate") ? 0.0 : ratio_),
        gamma_(p.real("damping")) {
    if (sim.dimension() != 2)
      throw InputError("bond style 'bend2d/hysteresis' needs a 2D simulation (dimension = 2)");
    if (delta_ > ky_)
      throw InputError("bond style 'bend2d/hysteresis': transition (" + std::to_string(delta_) +
                       ") must not exceed yield_curvature (" + std::to_string(ky_) + ")");
    auto chains = select_chains(sim, names_);
    auto& n = sim.nodes();
    kpl_ = &n.require<double>("bend.plastic_curvature", 0.0);
    fields_.bind(sim, p);
    const double amp = p.real("initial_plastic");
    if (amp > 0) {
      std::uniform_real_distribution<double> u(-amp, amp);
      for (auto* c : chains)
        for (int h = 0; h < c->n_hinges(); ++h) {
          int a, m, b;
          c->hinge(h, a, m, b);
          (*kpl_)[m] = u(sim.rng());
        }
    }
    setup(sim);
    // the starting state is the reference of the work accounting
    for (auto* c : chains_)
      for (int h = 0; h < c->n_hinges(); ++h) {
        int a, m, b;
        c->hinge(h, a, m, b);
        const double l0 = hinge_rest_length(*c, h);
        const double kappa =
            Hinge2d(sim.nodes().x[a], sim.nodes().x[m], sim.nodes().x[b]).zeta / l0;
        double kpl = (*kpl_)[m];  // a copy: no flow is committed here
        double stored = 0.0;
        moment(kappa, kpl, k_ * l0, &stored);
        recoverable0_ += stored * l0;
      }
    recoverable_ = recoverable0_;
  }
  void setup(Context& sim) override {
    ChainBondStyle::setup(sim);
    kpl_ = sim.nodes().find<double>("bend.plastic_curvature");
    fields_.rebind(sim);
  }
  const char* energy_category() const override { return "bend"; }

  // Moment at curvature kappa; updates kappa_pl by plastic flow (docs/models.md §2.2,
  // steps 1-4). *stored gets the recoverable energy per unit rest length: the
  // integral of M(x) at fixed kappa_pl from the zero-moment point x0 (in the linear
  // zone, thanks to the guard) to x, i.e. 1/2 K_e (x - x0)^2 -+ c (x - x_e)^3 / 3.
  // *dissipated gets the energy per unit rest length that this step's plastic flow
  // made unrecoverable: with W the work along the path (elastic to the yield point
  // x_y, then flow along M = g(x_y) + K_h kappa_pl) and E the recoverable energy,
  // W - dE = dkappa_pl (g(x_y) - K_m x_y) + 1/2 K_m (1 - K_m/K_e) d(kappa_pl^2), with
  // K_m = K_h the slope that plastic flow adds to the moment (K_m = 0 with saturate: then
  // the moment plateaus at g(x_y) and all of M dkappa_pl is dissipated).
  double moment(double kappa, double& kpl, double Ke, double* stored = nullptr,
                double* dissipated = nullptr) const {
    // K_m / K_e is memory_: no division per hinge (they set this loop's pace)
    const double Km = memory_ * Ke;
    const double x0 = -memory_ * kpl;
    double xp = ky_, xm = -ky_;
    if (guard_) {
      xp = std::max(ky_, x0 + delta_);
      xm = std::min(-ky_, x0 - delta_);
    }
    const double kpl_old = kpl;
    double x = kappa - kpl;
    if (x > xp) {
      kpl += x - xp;
      x = xp;
    } else if (x < xm) {
      kpl += x - xm;
      x = xm;
    }
    double g = Ke * x, cubic = 0.0;
    if (delta_ > 0) {
      const double xe = xp - delta_, xem = xm + delta_, c = Ke * curve_;
      if (x > xe) {
        const double y = x - xe;  // (std::pow here cost 12 % of a crumpling run)
        g -= c * y * y;
        cubic = -c * y * y * y / 3.0;
      } else if (x < xem) {
        const double y = x - xem;
        g += c * y * y;
        cubic = c * y * y * y / 3.0;
      }
    }
    const double M = g + Km * kpl;
    if (dissipated) {
      *dissipated = kpl == kpl_old ? 0.0
                                   : (kpl - kpl_old) * (g - Km * x) +
                                         0.5 * Km * (1 - memory_) * (kpl * kpl - kpl_old * kpl_old);
    }
    if (stored) {
      // zero-moment point of the (possibly just updated) branch
      const double z = -memory_ * kpl;
      *stored = 0.5 * Ke * (x - z) * (x - z) + cubic;
    }
    return M;
  }

  double compute(Context& sim) override {
    const auto& x = sim.nodes().x;
    const auto& v = sim.nodes().v;
    double energy = 0.0;
    // each thread's dissipated energy is added after the kernel, in thread order
    std::array<double, kMaxThreads> lost_part{};
    fields_.clear();
    for (auto* c : chains(sim)) {
      const int T = threads_for(static_cast<std::size_t>(c->n_hinges()), sim.threads());
      energy += sim.parallel_chain_forces(
          static_cast<std::size_t>(c->n_hinges()), c->closed, c->n_nodes(), c->closed ? -1 : 0,
          c->closed ? 1 : 2, [&](int tid, std::size_t begin, std::size_t end, ChainForces& f) {
            // summed in a register and stored once per range: a running total in memory
            // (this style's members, or neighbouring array slots) shared its cache line
            // with the other thread's, written at every hinge
            double e_part = 0.0, lost_sum = 0.0;
            for (std::size_t k = begin; k < end; ++k) {
              const int h = static_cast<int>(k);
              int a, m, b;
              c->hinge(h, a, m, b);
              const double l0 = hinge_rest_length(*c, h), Ke = k_ * l0;
              const Hinge2d g(x[a], x[m], x[b]);
              const double zeta = g.zeta;
              const double kappa = zeta / l0;
              double& kpl = (*kpl_)[m];
              double stored = 0.0, lost = 0.0;
              const double M = moment(kappa, kpl, Ke, &stored, &lost);
              lost_sum += lost * l0;
              // the dashpot adds gamma_r dzeta/dt (docs/models.md §2.1)
              const double Mt = gamma_ > 0 ? M + gamma_ * g.rate(v, a, m, b) : M;
              g.apply(f, c->hinge_first_position(h), a, m, b, Mt);
              e_part += stored * l0;
              fields_.set(m, kappa, stored * l0);
            }
            lost_part[static_cast<std::size_t>(tid)] = lost_sum;
            return e_part;
          });
      for (int t = 0; t < T; ++t) dissipated_ += lost_part[static_cast<std::size_t>(t)];
    }
    recoverable_ = energy;
    return energy;
  }
  // the elastic slope is the stiffest (K_h < K_e): as bend2d
  double max_frequency(const Context& sim) const override { return bend_frequency(sim, k_); }
  double value(const std::string& key) const override {
    if (key == "work") return dissipated_ + recoverable_ - recoverable0_;
    if (key == "recoverable") return recoverable_;
    if (key == "dissipated") return dissipated_;
    return BondStyle::value(key);
  }
  void save_state(StateMap& st) const override {
    st["energy"] = {dissipated_, recoverable_, recoverable0_};
  }
  void load_state(const StateMap& st) override {
    auto& w = saved_array(st, "energy", 3);
    dissipated_ = w[0];
    recoverable_ = w[1];
    recoverable0_ = w[2];
  }

 private:
  double k_, ky_, ratio_, delta_;
  double curve_ = delta_ > 0 ? (1 - ratio_) / (2 * delta_) : 0.0;  // c / K_e of the transition
  bool guard_;
  double memory_;  // K_m / K_e: K_h / K_e, or 0 with saturate
  double gamma_;
  Property<double>* kpl_ = nullptr;
  HingeNodeFields fields_;
  double dissipated_ = 0.0, recoverable_ = 0.0, recoverable0_ = 0.0;
};

}  // namespace slender

SLENDER_REGISTER_STYLE(slender::BondStyle, "bend2d/hysteresis", slender::BendHysteresisBond)
