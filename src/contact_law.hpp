// The contact law shared by wire-wire (pair) and wire-wall (fix) contacts,
// docs/models.md §2.3: normal repulsion k (d - dist)^p with a normal dashpot (never
// attractive), and stick-slip Coulomb friction with a tangential stick spring.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "nodes.hpp"
#include "params.hpp"
#include "threads.hpp"

namespace slender {

// Per-contact history: a stuck contact carries the stick-spring elongation xi; a
// slipping one its last slip direction.
struct FrictionState {
  Vec3 xi = Vec3::Zero();
  bool stick = false;
  bool active = false;  // in contact at the last evaluation
};

// The stiffness the contacts of one evaluation put on each node: Gershgorin row sums of
// their Hessian (normal tangent stiffness plus the stick spring). sqrt(max_i k_i / m_i)
// bounds the contacts' highest frequency as the packing has it now (several contacts per
// node, deep overlaps), where max_frequency() assumes one contact at a nominal overlap.
class NodeStiffness {
 public:
  // The row sums one thread adds (a kernel on T threads adds into part(tid); prepare(T)
  // first, outside the parallel region).
  // Each part on its own cache lines: two threads pushing to neighbouring parts' lists
  // would otherwise write the same line at every contact (false sharing).
  class alignas(64) Part {
   public:
    // No branch on the hot path: prepare() sized the row sums to every node. (A list of
    // the touched nodes cost a mispredicted branch per contact.)
    void add(int i, double k) { k_[static_cast<std::size_t>(i)] += k; }

   private:
    friend class NodeStiffness;
    std::vector<double> k_;
  };
  // Before an evaluation on `threads` threads over `n` nodes (outside the parallel region).
  void prepare(int threads, std::size_t n) {
    used_ = static_cast<std::size_t>(std::max(threads, 1));
    if (parts_.size() < used_) parts_.resize(used_);
    for (std::size_t t = 0; t < used_; ++t)
      if (parts_[t].k_.size() != n) parts_[t].k_.assign(n, 0.0);
  }
  Part& part(int tid) { return parts_[static_cast<std::size_t>(tid)]; }
  void add(int i, double k) { parts_[0].add(i, k); }
  // Closes one evaluation: the measured omega, and the row sums cleared for the next.
  // The threads' row sums are added in thread order (deterministic for a thread count),
  // on the threads' node ranges (a serial pass would pull every part onto one core).
  void finish(const std::vector<double>& mass) {
    std::vector<double>& k0 = parts_[0].k_;
    std::array<double, kMaxThreads> w2{};
    const int T = parallel_ranges(
        static_cast<int>(used_), k0.size(),
        [&](int tid, std::size_t begin, std::size_t end) {
          double m = 0.0;
          for (std::size_t t = 1; t < used_; ++t) {
            std::vector<double>& kt = parts_[t].k_;
            for (std::size_t u = begin; u < end; ++u) {
              k0[u] += kt[u];
              kt[u] = 0.0;
            }
          }
          for (std::size_t u = begin; u < end; ++u) {
            if (k0[u] != 0.0) m = std::max(m, k0[u] / mass[u]);
            k0[u] = 0.0;
          }
          w2[static_cast<std::size_t>(tid)] = m;
        },
        kMinLightItemsPerThread);
    double m = 0.0;
    for (int t = 0; t < T; ++t) m = std::max(m, w2[static_cast<std::size_t>(t)]);
    omega_ = std::sqrt(m);
  }
  double omega() const { return omega_; }
  void set_omega(double w) { omega_ = w; }

 private:
  std::vector<Part> parts_ = std::vector<Part>(1);
  std::size_t used_ = 1;
  double omega_ = 0.0;
};

struct ContactLaw {
  double stiffness = 0.0;        // k_c
  double exponent = 2.0;         // p: 2 is the thesis' quadratic law
  double damping = 0.0;          // d_c, normal dashpot coefficient
  double mu_static = 0.0;        // mu_st
  double mu_dynamic = 0.0;       // mu_d
  double stick_stiffness = 0.0;  // k_st
  double slip_velocity = 0.0;    // v_th: a slipping contact slower than this sticks again
  bool new_stick_always = true;  // a new contact sticks (else only when slower than v_th)

  // Declares the law's parameters on a style's spec (shared by pair and wall).
  // A style that derives the stiffness itself (per contact) makes it optional.
  static void declare(ParamSpec& s, double default_exponent = 2.0, bool stiffness_required = true) {
    auto& k = s.real("stiffness", "normal stiffness k_c: F_N = k_c overlap^p").positive();
    if (stiffness_required) k.required();
    s.real("exponent",
           "normal force law exponent p (2: quadratic as in 2D, docs/models.md §2.3; 1: "
           "linear as the 3D rods, §5.1)")
        .def(default_exponent)
        .min(1.0)
        .max(3.0);
    s.real("damping", "normal dashpot d_c (force per normal velocity)").def(0.0).nonnegative();
    s.real("mu_static", "static friction coefficient mu_st (0: frictionless)")
        .def(0.0)
        .nonnegative();
    s.real("mu_dynamic", "dynamic friction coefficient mu_d (default 0.9 mu_static)").nonnegative();
    s.real("stick_stiffness", "tangential stick spring k_st (default k_c d / 10)").positive();
    s.real("slip_velocity", "v_th: slipping contacts slower than this stick again")
        .def(1e-4)
        .nonnegative();
    declare_new_contacts(s);
  }
  // The key that says how a new contact starts (also declared by the shell contact, whose
  // other friction keys scale differently).
  static void declare_new_contacts(ParamSpec& s) {
    s.string("new_contacts",
             "how a contact starts: \"stick\" (always, with an unstretched stick spring) or "
             "\"by_speed\" (it sticks only when its tangential speed is below slip_velocity, "
             "else it starts slipping; docs/models.md §2.3)")
        .def("stick")
        .choices({"stick", "by_speed"});
  }
  static ContactLaw from(const ParamValues& p, double length_scale) {
    ContactLaw c;
    c.stiffness = p.has("stiffness") ? p.real("stiffness") : 0.0;
    c.exponent = p.real("exponent");
    c.damping = p.real("damping");
    c.mu_static = p.real("mu_static");
    c.mu_dynamic = p.has("mu_dynamic") ? p.real("mu_dynamic") : 0.9 * c.mu_static;
    c.stick_stiffness =
        p.has("stick_stiffness") ? p.real("stick_stiffness") : 0.1 * c.stiffness * length_scale;
    c.slip_velocity = p.real("slip_velocity");
    c.new_stick_always = p.str("new_contacts") == "stick";
    if (c.mu_dynamic > c.mu_static)
      throw InputError("contact law: mu_dynamic (" + std::to_string(c.mu_dynamic) +
                       ") must not exceed mu_static (" + std::to_string(c.mu_static) + ")");
    return c;
  }
  bool frictional() const { return mu_static > 0.0; }

  // overlap^exponent; the common exponents avoid std::pow, which dominated the
  // contact loop of dense packings (thousands of contacts per step)
  double power(double overlap) const {
    if (exponent == 2.0) return overlap * overlap;
    if (exponent == 1.0) return overlap;
    if (exponent == 1.5) return overlap * std::sqrt(overlap);
    return std::pow(overlap, exponent);
  }
  // Normal force magnitude without the dashpot, and the matching energy.
  double elastic_force(double overlap) const { return stiffness * power(overlap); }
  double energy(double overlap) const {
    return stiffness * power(overlap) * overlap / (exponent + 1.0);
  }
  // Stiffness a contact in state st puts on its bodies (normal tangent plus the stick
  // spring while it sticks), for the measured stable step.
  double contact_stiffness(double overlap, const FrictionState& st) const {
    return tangent_stiffness(overlap) + (st.stick ? stick_stiffness : 0.0);
  }
  // Stiffness dF/doverlap at a reference overlap, for the stable time step.
  double tangent_stiffness(double overlap) const {
    // per contact and step for the measured stable step: the common exponents avoid pow
    if (exponent == 2.0) return 2.0 * stiffness * overlap;
    if (exponent == 1.0) return stiffness;
    if (exponent == 1.5) return 1.5 * stiffness * std::sqrt(overlap);
    return exponent * stiffness * std::pow(overlap, exponent - 1.0);
  }

  // Force on the first body for an overlap along the unit normal n (pointing from
  // the second body to the first) with relative velocity v = v_1 - v_2. Updates the
  // friction history; returns the normal force magnitude in *normal.
  Vec3 force(double overlap, const Vec3& n, const Vec3& v, double dt, FrictionState& st,
             double* normal = nullptr, double* elastic_energy = nullptr) const {
    const double vn = v.dot(n);
    const double fe = elastic_force(overlap);
    if (elastic_energy) *elastic_energy = fe * overlap / (exponent + 1.0);
    const double fn = std::max(0.0, fe - damping * vn);
    if (normal) *normal = fn;
    return fn * n + friction(fn, n, v, dt, st);
  }

  // Stick-slip friction on the first body for a normal force fn along n and the
  // relative velocity v = v_1 - v_2 (its normal part is ignored); updates st.
  // Magnitudes are compared squared: a stuck contact that stays stuck (most contacts
  // of a packing) takes no square root, which was half of this function's time.
  Vec3 friction(double fn, const Vec3& n, const Vec3& v, double dt, FrictionState& st) const {
    if (!frictional()) {
      st.active = true;
      return Vec3::Zero();
    }
    const double vn = v.dot(n);
    const Vec3 vt = v - vn * n;
    const double vt2 = vt.squaredNorm();
    const double limit = mu_static * fn, limit2 = limit * limit;
    const bool slow = vt2 < slip_velocity * slip_velocity;
    if (!st.active) {
      // a new contact: stuck, or (new_contacts = "by_speed") stuck only when slow
      st.stick = new_stick_always || slow;
      st.xi.setZero();
    } else if (!st.stick && slow) {
      st.stick = true;
      st.xi.setZero();
    }
    st.active = true;
    if (st.stick) {
      st.xi += vt * dt;
      st.xi -= st.xi.dot(n) * n;  // the spring lies in the tangent plane
      const Vec3 ft = -stick_stiffness * st.xi;
      if (ft.squaredNorm() <= limit2) return ft;
      st.stick = false;
      st.xi.setZero();
    }
    if (vt2 > 0.0) {
      const Vec3 dir = vt / std::sqrt(vt2);
      // While slipping, xi holds the last slip direction. A tangential velocity that
      // reversed passed through rest within the step: the contact sticks again.
      // (Otherwise the full dynamic force flips every step and pumps energy in.)
      if (st.xi.dot(dir) < 0.0) {
        st.stick = true;
        st.xi = vt * dt;
        st.xi -= st.xi.dot(n) * n;
        const Vec3 ft = -stick_stiffness * st.xi;
        if (ft.squaredNorm() <= limit2) return ft;
        st.stick = false;
      }
      st.xi = dir;
      return -(mu_dynamic * fn) * dir;
    }
    return Vec3::Zero();
  }
};

}  // namespace slender
