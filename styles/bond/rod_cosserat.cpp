// Quaternion Cosserat rod (docs/models.md §4, after Spillmann & Teschner): besides the
// node positions, one unit quaternion per edge (stored at the edge's first node,
// generalised coordinates "rod.q" integrated by verlet or gear) gives the material
// frame. Energies: bending and torsion from the discrete Darboux vector against the
// rest value kbar (§4.3), and the penalty C/2 |e_rest| |t - d3|^2 tying d3 to the
// edge tangent; stretching is the `spring` style. Rotational inertia: a quaternion
// carries the scalar mass m_q = 4 I_r |e_rest| with I_r = rho J per length (§4.4).
// A new edge (injection, or a chain's first binding) is born with its neighbour's
// frame carried over onto its own tangent by the smallest rotation, so a growing
// rod keeps its twist continuous.
// With director = "tangent" the penalty's limit C -> infinity is taken instead (§4.6):
// before every evaluation each frame is carried onto its edge's tangent by the smallest
// rotation, the frames' torques about axes across the edge act on the edge's nodes, and
// only the spin about the tangent stays a dynamic degree of freedom. This removes the
// stiffest mode of the penalty form (C on the tiny frame inertia), which limits the step.
#include <array>
#include <cmath>

#include "chain_select.hpp"
#include "quaternion_rod.hpp"
#include "registry.hpp"

namespace slender {

class CosseratRodBond : public ChainBondStyle {
 public:
  static ParamSpec spec(const std::string& name) {
    ParamSpec s("bond", name,
                "quaternion Cosserat rod: bending, torsion and intrinsic curvature from edge "
                "quaternions, d3 tied to the tangent (docs/models.md §4)");
    s.real("YI", "bending stiffness Y I").required().positive();
    s.real("GJ", "torsional stiffness G J").required().positive();
    s.string("director",
             "how d3 follows the edge tangent: penalty (the energy C/2 |e| |t - d3|^2, "
             "docs/models.md §4.3) or tangent (exactly, the limit C -> infinity: the frames "
             "keep only their spin about the tangent, §4.6; integrator verlet or fire)")
        .def(std::string("penalty"))
        .choices({"penalty", "tangent"});
    s.real("coupling",
           "C: stiffness of the penalty tying d3 to the tangent (docs/models.md §4.3: C = YA); "
           "required with director = penalty, refused with director = tangent")
        .positive();
    s.vector("rest_curvature", "kbar = (k1, k2, k3): rest Darboux vector in the material frame")
        .def(std::vector<double>{0, 0, 0})
        .length(3, 3);
    s.real("rot_inertia", "I_r: rotational inertia per length, rho J (docs/models.md §4.4)")
        .required()
        .positive();
    s.real("inertia_scale", "multiplies m_q (quasi-static runs whose step it limits)")
        .def(1.0)
        .positive();
    s.real("rot_damping", "gamma_q: generalised force -gamma_q dq/dt on every quaternion")
        .def(0.0)
        .nonnegative();
    s.boolean("node_energy", "keep each vertex's bending energy in the node property bend.energy")
        .def(false);
    declare_chains(s);
    s.output("misalignment",
             "largest |t - d3| over the edges: how far d3 strays from the edge tangent");
    return s;
  }
  CosseratRodBond(Context& sim, const ParamValues& p)
      : ChainBondStyle(sim, p),
        tangent_(p.str("director") == "tangent"),
        K_(p.real("YI"), p.real("YI"), p.real("GJ")),
        C_(p.has("coupling") ? p.real("coupling") : 0.0),
        kbar_(p.vec3("rest_curvature")),
        Ir_(p.real("rot_inertia") * p.real("inertia_scale")),
        gamma_q_(p.real("rot_damping")),
        coords_(&sim.coordinates("rod.q")) {
    if (sim.dimension() != 3)
      throw InputError("bond style 'rod/cosserat' needs a 3D simulation (dimension = 3)");
    if (!tangent_ && !p.has("coupling"))
      throw InputError(
          "bond style 'rod/cosserat': 'coupling' (C, e.g. 20 YA) is required with director = "
          "\"penalty\"; director = \"tangent\" ties d3 to the tangent exactly without it");
    if (tangent_ && p.has("coupling"))
      throw InputError(
          "bond style 'rod/cosserat': 'coupling' has no meaning with director = \"tangent\" "
          "(d3 follows the tangent exactly); remove it, or use director = \"penalty\"");
    // the frames move with the positions inside the force evaluation: an integrator with
    // its own history of q (gear) cannot run them
    if (tangent_) coords_->follows_positions = coords_->keep_speed = true;
    born_ = &sim.nodes().require<int>("rod.q.born", 0);
    if (p.boolean("node_energy")) node_energy_ = &sim.nodes().require<double>("bend.energy", 0.0);
  }
  const char* energy_category() const override { return "bend"; }

  // new edges get their frames before the first evaluation, so that a fix set up after
  // the bonds (prescribe with frames) finds them
  void setup(Context& sim) override {
    ChainBondStyle::setup(sim);  // binds the chains
    for (auto* c : chains(sim)) bind_edges(sim, *c);
  }
  double compute(Context& sim) override {
    if (tangent_) return compute_tangent(sim);
    const auto& x = sim.nodes().x;
    auto& q = coords_->q->values();
    auto& fq = coords_->f->values();
    double bend = 0.0, twist = 0.0, couple = 0.0, max_ec_per_length = 0.0;
    if (node_energy_)
      for (auto& e : node_energy_->values()) e = 0.0;
    for (auto* c : chains(sim)) {
      bind_edges(sim, *c);
      const int ne = c->n_edges();
      // edges: the coupling moves both nodes (forces into the thread's buffer) and turns
      // the edge's own frame (its tail's quaternion: one edge per slot, no conflict)
      std::array<double, kMaxThreads> max_part{};
      couple += sim.parallel_node_forces(
          static_cast<size_t>(ne), [&](int tid, size_t begin, size_t end, Vec3* f) {
            double c_part = 0.0, m_part = 0.0;
            for (size_t k = begin; k < end; ++k) {
              const int e = static_cast<int>(k);
              const int a = c->edge_tail(e), b = c->edge_head(e);
              const double ec =
                  qrod::coupling(q[a], x[a], x[b], c->rest_length[k], C_, fq[a], f[a], f[b]);
              c_part += ec;
              // |t - d3| from E_c = C/2 |e_rest| |t - d3|^2 (docs/models.md §4.3 asks for < 1e-2):
              // the largest E_c / |e_rest| here, one root after the loop (a root per edge
              // cost a tenth of this function)
              m_part = std::max(m_part, ec / c->rest_length[k]);
              if (gamma_q_ > 0) fq[a] -= gamma_q_ * (*coords_->v)[a];
            }
            max_part[static_cast<size_t>(tid)] = m_part;
            return c_part;
          });
      for (double m : max_part) max_ec_per_length = std::max(max_ec_per_length, m);
      hinges(sim, *c, fq, bend, twist);
    }
    misalignment_ = std::sqrt(2.0 * max_ec_per_length / C_);
    sim.add_energy("twist", twist);
    sim.add_energy("coupling", couple);
    return bend;
  }

  double value(const std::string& key) const override {
    if (key == "misalignment") return misalignment_;  // max |t - d3| over the edges
    return ChainBondStyle::value(key);
  }

  double max_frequency(const Context& sim) const override {
    auto ch = select_chains(sim, names_);
    if (ch.empty()) return 0.0;
    const double l0 = min_rest(ch), m = min_mass(sim, ch);
    const double mq = 4.0 * Ir_ * l0;
    // the coupling moves nodes like a transverse spring C / l0, and turns a
    // quaternion with stiffness ~ 4 C l0 (|J3| ~ 2); bending and torsion couple
    // neighbouring quaternions with ~ 4 K / l0 each side (zig-zag: x 4)
    if (tangent_) {
      // no penalty: bending turns the edges (on the nodes' masses, as a rod without
      // frames), torsion spins the frames
      const double wq2 = 16.0 * K_.z() / l0 / mq;
      return std::max(bend_frequency(sim, K_.x() / l0), 2.0 * std::sqrt(wq2));
    }
    const double wx = 2.0 * std::sqrt(C_ / (l0 * m));
    const double wq2 = (4.0 * C_ * l0 + 16.0 * K_.maxCoeff() / l0) / mq;
    return std::max(wx, 2.0 * std::sqrt(wq2));
  }

 private:
  // director = "tangent" (docs/models.md §4.6): frames carried onto their tangents, the
  // hinges' torques across each edge turned into forces on its nodes, the spin kept.
  double compute_tangent(Context& sim) {
    const auto& x = sim.nodes().x;
    auto& q = coords_->q->values();
    auto& v = coords_->v->values();
    auto& fq = coords_->f->values();
    const auto& fixed = coords_->fixed->values();
    double bend = 0.0, twist = 0.0;
    if (node_energy_)
      for (auto& e : node_energy_->values()) e = 0.0;
    hinge_force_.assign(q.size(), Vec4::Zero());
    for (auto* c : chains(sim)) {
      bind_edges(sim, *c);
      const size_t ne = static_cast<size_t>(c->n_edges());
      // 1. every frame onto its tangent (a held frame too: the nozzle holds its spin); the
      // spin rate is carried along
      parallel_ranges(threads_for(ne, sim.threads()), ne, [&](int, size_t begin, size_t end) {
        for (size_t k = begin; k < end; ++k) {
          const int e = static_cast<int>(k);
          const int a = c->edge_tail(e);
          const Vec3 t = (x[c->edge_head(e)] - x[a]).normalized();
          const double spin = v[a].dot(qrod::rotation_map(q[a]) * qrod::d3(q[a]));
          q[a] = qrod::carried_onto(q[a], t);
          if (!fixed[a]) v[a] = spin * (qrod::rotation_map(q[a]) * t);
        }
      });
      // 2. bending and torsion on the frames
      hinges(sim, *c, hinge_force_, bend, twist);
      // 3. a torque across the edge turns the edge (forces on its nodes, e x F = torque);
      // the torque about the tangent spins the frame
      sim.parallel_node_forces(ne, [&](int, size_t begin, size_t end, Vec3* f) {
        for (size_t k = begin; k < end; ++k) {
          const int e = static_cast<int>(k);
          const int a = c->edge_tail(e), b = c->edge_head(e);
          const Vec3 d = x[b] - x[a];
          const double len = d.norm();
          const Vec3 t = d / len;
          const Vec3 tau = qrod::torque(q[a], hinge_force_[a]);
          const Vec3 fb = tau.cross(t) / len;
          f[b] += fb;
          f[a] -= fb;
          const Vec4 g = qrod::rotation_map(q[a]) * t;  // unit: dq of a unit spin is g / 2
          fq[a] += (2.0 * tau.dot(t)) * g;
          if (gamma_q_ > 0) fq[a] -= gamma_q_ * v[a];
        }
        return 0.0;
      });
    }
    misalignment_ = 0.0;
    sim.add_energy("twist", twist);
    sim.add_energy("coupling", 0.0);
    return bend;
  }

  // Bending and torsion at the vertices between consecutive edges (all of them on a
  // closed chain): generalised forces on the frames into out; energies added.
  void hinges(Context& sim, const Chain& c, std::vector<Vec4>& out, double& bend, double& twist) {
    const auto& q = coords_->q->values();
    const int ne = c.n_edges();
    const int nv = c.closed ? ne : ne - 1;
    auto vertex = [&](int k, double& b_sum, double& t_sum) {
      const int ea = k, eb = (k + 1) % ne;
      const int qa = c.edge_tail(ea), qb = c.edge_tail(eb);
      const double l = 0.5 * (c.rest_length[ea] + c.rest_length[eb]);
      // q and -q are the same rotation: the neighbour is taken in the same
      // hemisphere (a closed ring's frames come back as -q after a full turn)
      const double sgn = q[qa].dot(q[qb]) < 0.0 ? -1.0 : 1.0;
      qrod::Quat fb = qrod::Quat::Zero();
      const auto h = qrod::hinge(q[qa], sgn * q[qb], l, K_, kbar_, out[qa], fb);
      out[qb] += sgn * fb;
      b_sum += h.bend;
      t_sum += h.twist;
      if (node_energy_) (*node_energy_)[c.edge_head(ea)] = h.bend;
    };
    const int T = threads_for(static_cast<size_t>(nv), sim.threads());
    if (T <= 1) {
      for (int k = 0; k < nv; ++k) vertex(k, bend, twist);
    } else {
      // vertex k turns frames k and k + 1: the even vertices, then the odd ones, touch
      // disjoint frames (the closing vertex of a ring, which wraps, goes last)
      const int open_part = c.closed ? nv - 1 : nv;
      for (int parity = 0; parity < 2; ++parity) {
        const size_t count = static_cast<size_t>(std::max(0, (open_part - parity + 1) / 2));
        std::array<double, kMaxThreads> b_part{}, t_part{};
        parallel_ranges(T, count, [&](int tid, size_t begin, size_t end) {
          // summed in registers, stored once: the threads' slots share a cache line
          double b_sum = 0.0, t_sum = 0.0;
          for (size_t j = begin; j < end; ++j)
            vertex(parity + 2 * static_cast<int>(j), b_sum, t_sum);
          b_part[static_cast<size_t>(tid)] = b_sum;
          t_part[static_cast<size_t>(tid)] = t_sum;
        });
        for (int t = 0; t < T; ++t) {
          bend += b_part[static_cast<size_t>(t)];
          twist += t_part[static_cast<size_t>(t)];
        }
      }
      if (c.closed) vertex(nv - 1, bend, twist);
    }
  }

  // Gives every edge of the chain its quaternion mass and, for an edge that has
  // none yet, its frame; the node after an open chain's last edge carries no edge.
  void bind_edges(Context& sim, const Chain& c) {
    auto& x = sim.nodes().x;
    auto& q = coords_->q->values();
    auto& born = born_->values();
    const int ne = c.n_edges();
    // born: 1 = the edge has its frame; 2 = the slot of an open chain's last node,
    // which has no edge (held still); 0 = a new edge
    if (!c.closed) {
      const int last = c.nodes.back();
      (*coords_->fixed)[last] = 1;
      born[last] = 2;
    }
    for (int e = 0; e < ne; ++e) {
      const int a = c.edge_tail(e);
      if (born[a] == 1) continue;
      // a former last node now starts an edge: it moves; a new node keeps whatever
      // a fix prescribed (a nozzle that holds the rotation)
      if (born[a] == 2) (*coords_->fixed)[a] = 0;
      const Vec3 t = (x[c.edge_head(e)] - x[a]).normalized();
      // the nearest edge with a frame, before or after this one
      int from = -1;
      if (e > 0 && born[c.edge_tail(e - 1)] == 1) from = e - 1;
      if (from < 0 && e + 1 < ne && born[c.edge_tail(e + 1)] == 1) from = e + 1;
      if (from >= 0) {
        const int n = c.edge_tail(from);
        const Vec3 tn = (x[c.edge_head(from)] - x[n]).normalized();
        const Eigen::Quaterniond r = Eigen::Quaterniond::FromTwoVectors(tn, t);
        q[a] = qrod::mul(qrod::Quat(r.w(), r.x(), r.y(), r.z()), q[n]);
        if (q[a].dot(q[n]) < 0) q[a] = -q[a];  // same hemisphere as the neighbour
      } else {
        q[a] = qrod::aligned_with(t);
      }
      q[a].normalize();
      (*coords_->v)[a].setZero();
      (*coords_->m)[a] = 4.0 * Ir_ * c.rest_length[e];
      born[a] = 1;
    }
  }

  bool tangent_;
  Vec3 K_;
  double C_;
  Vec3 kbar_;
  double Ir_, gamma_q_;
  Coordinates* coords_;
  Property<int>* born_ = nullptr;
  Property<double>* node_energy_ = nullptr;
  double misalignment_ = 0.0;
  std::vector<Vec4> hinge_force_;  // director = tangent: the hinges' forces on the frames
};

}  // namespace slender

SLENDER_REGISTER_STYLE(slender::BondStyle, "rod/cosserat", slender::CosseratRodBond)
