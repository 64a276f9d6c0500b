// Segment-segment contact of 3D rods (docs/models.md §5.1). Broad phase: the shared
// linked cells over edge midpoints and a pair list of edge pairs closer than
// 2a + skin, rebuilt when a node moved more than skin/2 (or every N steps).
// Dense phase: the closest points S1, S2 of the two segments (clamped, with a
// parallel fallback at the middle of the overlap), overlap 2a - |S1 - S2| along
// n = (S1 - S2)/|S1 - S2|, the shared contact law (linear Hertz-cylinder force
// E* overlap by default, dashpot, stick-slip friction in the tangent plane), and
// the lever rule onto the four nodes, so that momentum is conserved exactly.
#include <algorithm>
#include <array>
#include <cmath>

#include "cell_grid.hpp"
#include "chain_select.hpp"
#include "contact_hessian.hpp"
#include "contact_law.hpp"
#include "pair_history.hpp"
#include "registry.hpp"
#include "segment_geometry.hpp"

namespace slender {

class SegmentContactPair : public PairStyle {
 public:
  static ParamSpec spec(const std::string& name) {
    ParamSpec s("pair", name,
                "3D segment-segment contact of rods: Hertz-cylinder repulsion, dashpot, stick-slip "
                "Coulomb friction (docs/models.md §5.1)");
    s.real("radius", "rod radius a: contact when two segments are closer than 2a")
        .def(1.0)
        .positive();
    ContactLaw::declare(s, 1.0, false);
    s.real("youngs_modulus",
           "Y: stiffness E* = 2 pi Y (l1 + l2) / (8 (1 - nu^2)) from the rest lengths of the two "
           "edges (instead of a fixed 'stiffness')")
        .positive();
    s.real("poisson", "Poisson ratio nu for E*").def(0.33).min(0.0).max(0.5, true);
    RebuildSchedule::declare(s, "pair-list skin: pairs closer than 2a + skin are listed");
    s.integer("exclude",
              "skip edge pairs within this many edges along the same chain (default ceil(2a / "
              "l0) + 1)")
        .min(0)
        .max(1000000);
    s.add("chains", ParamType::StringList, "chains that touch each other (default: all)")
        .def(std::vector<std::string>{});
    s.output("contacts", "number of segment pairs in contact at the last evaluation");
    s.output("pairs", "number of edge pairs in the pair list");
    s.output("builds", "number of pair-list builds since the start");
    s.output("omega", "contact frequency measured at the last evaluation, sqrt(max_i k_i / m_i)");
    return s;
  }

  SegmentContactPair(Context& sim, const ParamValues& p)
      : a_(p.real("radius")),
        law_(ContactLaw::from(p, 2.0 * p.real("radius"))),
        schedule_(p),
        names_(p.strings("chains")) {
    if (sim.dimension() != 3)
      throw InputError("pair style 'contact/segment' needs a 3D simulation (dimension = 3)");
    const bool has_k = p.has("stiffness"), has_y = p.has("youngs_modulus");
    if (has_k == has_y)
      throw InputError("pair style 'contact/segment': give either 'stiffness' or 'youngs_modulus'");
    if (has_y) {
      const double nu = p.real("poisson");
      estar_per_length_ = 2.0 * M_PI * p.real("youngs_modulus") / (8.0 * (1.0 - nu * nu));
    }
    auto chains = select_chains(sim, names_);
    const double l0 = chains.empty() ? 2.0 * a_ : min_rest(chains);
    // a radius of a million rest lengths or more would exclude every pair of any wire that
    // fits in memory (and overflow the count): a deck error, not a contact (fuzz finding)
    const double along = std::ceil(2.0 * a_ / l0) + 1.0;
    if (!p.has("exclude") && !(along <= 1e6))
      throw InputError("pair style 'contact/segment': radius = " + std::to_string(a_) + " is " +
                       std::to_string(a_ / l0) + " rest lengths (l0 = " + std::to_string(l0) +
                       "): contacts within 2 radii along a chain are skipped, so no pair would "
                       "be left; the radius must be a fraction of the wire's length");
    exclude_ = p.has("exclude") ? static_cast<int>(p.integer("exclude")) : static_cast<int>(along);
    // defaults as in 2D with k_c -> E* of two rest edges (§5.1): k_st = k / 10
    nominal_k_ = has_y ? estar_per_length_ * 2.0 * l0 : law_.stiffness;
    if (!p.has("stick_stiffness")) law_.stick_stiffness = 0.1 * nominal_k_;
  }

  void setup(Context& sim) override {
    chains_ = select_chains(sim, names_);
    edges_.clear();
    for (size_t c = 0; c < chains_.size(); ++c) {
      const Chain& ch = *chains_[c];
      for (int e = 0; e < ch.n_edges(); ++e)
        edges_.push_back(
            Edge{ch.edge_tail(e), ch.edge_head(e), static_cast<int>(c), e, ch.rest_length[e]});
    }
    // a list read from a checkpoint knows its edges by number, in the numbering of now
    if (tails_from_ids_)
      for (auto& e : list_)
        if (static_cast<size_t>(std::max(e.e1, e.e2)) < edges_.size()) {
          e.t1 = edges_[static_cast<size_t>(e.e1)].a;
          e.t2 = edges_[static_cast<size_t>(e.e2)].a;
        }
    tails_from_ids_ = false;
    need_build_ = true;
    bound_ = true;
  }

  double compute(Context& sim) override {
    if (!bound_ || topology_changed()) setup(sim);
    if (schedule_.due(sim, need_build_)) build(sim);
    const auto& x = sim.nodes().x;
    const auto& v = sim.nodes().v;
    const double dt = sim.dt(), reach = 2.0 * a_, reach2 = reach * reach;
    stiffness_.prepare(sim.threads(), sim.nodes().size());
    std::array<int, kMaxThreads> count{};
    // each listed pair is one work item: its friction history is its own, its forces go
    // to the thread's buffer (threads.hpp)
    const double energy = sim.parallel_node_forces(
        list_.size(), [&](int tid, std::size_t begin, std::size_t end, Vec3* f) {
          ContactLaw law = law_;
          NodeStiffness::Part& stiff = stiffness_.part(tid);
          double energy_part = 0.0;
          int n_contacts = 0;
          for (std::size_t k = begin; k < end; ++k) {
            Entry& c = list_[k];
            const Edge& e1 = edges_[static_cast<size_t>(c.e1)];
            const Edge& e2 = edges_[static_cast<size_t>(c.e2)];
            double s, t;
            closest_points(x[e1.a], x[e1.b], x[e2.a], x[e2.b], s, t);
            const Vec3 p1 = x[e1.a] + s * (x[e1.b] - x[e1.a]);
            const Vec3 p2 = x[e2.a] + t * (x[e2.b] - x[e2.a]);
            const Vec3 d12 = p1 - p2;
            // most listed pairs are apart: test the squared distance before taking the root
            const double dist2 = d12.squaredNorm();
            if (dist2 >= reach2 || dist2 == 0.0) {
              c.st.active = false;
              c.st.stick = false;
              c.st.xi.setZero();
              continue;
            }
            const double dist = std::sqrt(dist2);
            const Vec3 n = d12 / dist;
            const Vec3 vrel = ((1 - s) * v[e1.a] + s * v[e1.b]) - ((1 - t) * v[e2.a] + t * v[e2.b]);
            if (estar_per_length_ > 0) law.stiffness = estar_per_length_ * (e1.rest + e2.rest);
            double e_contact = 0.0;
            const Vec3 F = law.force(reach - dist, n, vrel, dt, c.st, nullptr, &e_contact);
            f[e1.a] += (1 - s) * F;
            f[e1.b] += s * F;
            f[e2.a] -= (1 - t) * F;
            f[e2.b] -= t * F;
            // Hessian k w w^T with w = (1-s, s, -(1-t), -t), |w|_1 = 2: row sums 2 k |w_j|
            const double kc = law.contact_stiffness(reach - dist, c.st);
            stiff.add(e1.a, 2 * (1 - s) * kc);
            stiff.add(e1.b, 2 * s * kc);
            stiff.add(e2.a, 2 * (1 - t) * kc);
            stiff.add(e2.b, 2 * t * kc);
            energy_part += e_contact;
            ++n_contacts;
          }
          count[static_cast<std::size_t>(tid)] = n_contacts;
          return energy_part;
        });
    contacts_ = 0;
    for (int c : count) contacts_ += c;
    stiffness_.finish(sim.nodes().mass);
    return energy;
  }

  // The Hessian of the contacts at the current positions (docs/models.md §9.9; the energy
  // k/(p+1) overlap^(p+1) of the segments' distance, src/contact_hessian.hpp). Friction's
  // stick springs have no energy of the positions alone: none then.
  bool add_hessian(Context& sim, Hessian& H) const override {
    if (law_.frictional()) return false;
    const auto& x = sim.nodes().x;
    const double reach = 2.0 * a_;
    ContactLaw law = law_;
    for (const Entry& c : list_) {
      const Edge& e1 = edges_[static_cast<size_t>(c.e1)];
      const Edge& e2 = edges_[static_cast<size_t>(c.e2)];
      double s, t;
      closest_points(x[e1.a], x[e1.b], x[e2.a], x[e2.b], s, t);
      const Vec3 d12 = (x[e1.a] + s * (x[e1.b] - x[e1.a])) - (x[e2.a] + t * (x[e2.b] - x[e2.a]));
      const double dist = d12.norm();
      if (!(dist < reach) || dist == 0.0) continue;
      if (estar_per_length_ > 0) law.stiffness = estar_per_length_ * (e1.rest + e2.rest);
      const double overlap = reach - dist;
      // r = (1-s) a1 + s b1 - (1-t) a2 - t b2; s, t free where inside their segments
      const bool fs = s > 0.0 && s<1.0, ft = t> 0.0 && t < 1.0;
      Eigen::MatrixXd dc(4, int(fs) + int(ft));
      int m = 0;
      if (fs) dc.col(m++) << -1.0, 1.0, 0.0, 0.0;
      if (ft) dc.col(m++) << 0.0, 0.0, 1.0, -1.0;
      add_distance_hessian<4>(
          H, {e1.a, e1.b, e2.a, e2.b}, x, Eigen::Vector4d(1 - s, s, -(1 - t), -t), dc,
          -law.elastic_force(overlap), law.tangent_stiffness(overlap), sim.dimension());
    }
    return true;
  }
  double max_frequency(const Context& sim) const override {
    auto chains = select_chains(sim, names_);
    if (chains.empty()) return 0.0;
    const double m = min_mass(sim, chains);
    // two nodes on the contact spring at an overlap of a tenth of a radius
    ContactLaw law = law_;
    law.stiffness = nominal_k_;
    const double k =
        law.tangent_stiffness(0.1 * a_) + (law.frictional() ? law.stick_stiffness : 0.0);
    return std::sqrt(2.0 * k / m);
  }
  std::string neighbor_structure() const override { return "linked cells + segment pair list"; }
  double measured_frequency() const override { return stiffness_.omega(); }
  double value(const std::string& key) const override {
    if (key == "contacts") return contacts_;
    if (key == "omega") return stiffness_.omega();
    if (key == "pairs") return static_cast<double>(list_.size());
    if (key == "builds") return schedule_.builds();
    return PairStyle::value(key);
  }
  void save_state(StateMap& st) const override {
    std::vector<double> flat;
    for (auto& e : list_)
      flat.insert(flat.end(), {double(e.e1), double(e.e2), e.st.xi.x(), e.st.xi.y(), e.st.xi.z(),
                               e.st.stick ? 1.0 : 0.0, e.st.active ? 1.0 : 0.0});
    st["history"] = flat;
    save_measured(st, {double(contacts_), stiffness_.omega()});
    schedule_.save(st);
  }
  // the guard's copy (see contact/node-edge)
  void keep() override {
    kept_list_ = list_;
    kept_contacts_ = contacts_;
    kept_omega_ = stiffness_.omega();
  }
  void restore_kept() override {
    list_ = kept_list_;
    contacts_ = kept_contacts_;
    stiffness_.set_omega(kept_omega_);
    need_build_ = true;
  }
  void load_state(const StateMap& st) override {
    list_.clear();
    auto& h = saved_array(st, "history");
    for (size_t k = 0; k + 7 <= h.size(); k += 7) {
      Entry e;
      e.e1 = saved_index(h[k]);
      e.e2 = saved_index(h[k + 1]);
      e.st.xi = Vec3(h[k + 2], h[k + 3], h[k + 4]);
      e.st.stick = h[k + 5] != 0;
      e.st.active = h[k + 6] != 0;
      list_.push_back(e);
    }
    if (auto* m = load_measured(st, 2)) {
      contacts_ = saved_int((*m)[0]);
      stiffness_.set_omega((*m)[1]);
    } else if (auto* m1 = load_measured(st, 1)) {
      contacts_ = saved_int((*m1)[0]);
    }
    tails_from_ids_ = true;
    schedule_.load(st);
  }
  std::string check_loaded(const Context& sim) const override {
    std::size_t edges = 0;
    for (auto* c : select_chains(sim, names_)) edges += static_cast<std::size_t>(c->n_edges());
    for (std::size_t k = 0; k < list_.size(); ++k) {
      const Entry& e = list_[k];
      if (e.e1 < 0 || e.e2 < 0 || static_cast<std::size_t>(std::max(e.e1, e.e2)) >= edges ||
          !e.st.xi.allFinite())
        return "pair " + std::to_string(k + 1) + " of the history (edges " +
               std::to_string(e.e1 + 1) + ", " + std::to_string(e.e2 + 1) +
               ") is not a pair of the " + std::to_string(edges) + " edges, or holds NaN";
    }
    return "";
  }

 private:
  struct Edge {
    int a, b, chain, index;
    double rest;
  };
  struct Entry {
    int e1 = 0, e2 = 0;
    int t1 = 0, t2 = 0;  // the edges' first nodes: edge numbers change when a chain grows
    FrictionState st;
  };

  bool topology_changed() const {
    size_t ne = 0;
    for (auto* c : chains_) ne += static_cast<size_t>(c->n_edges());
    return ne != edges_.size();
  }
  bool excluded(const Edge& e, const Edge& o) const {
    if (e.chain != o.chain) return false;
    const Chain& ch = *chains_[static_cast<size_t>(e.chain)];
    int g = std::abs(e.index - o.index);
    if (ch.closed) g = std::min(g, ch.n_edges() - g);
    return g <= exclude_;
  }

  void build(Context& sim) {
    auto& x = sim.nodes().x;
    const double cutoff = 2.0 * a_ + schedule_.skin();
    double lmax = 0.0;
    Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
    mid_.resize(edges_.size());
    half_.resize(edges_.size());
    for (size_t k = 0; k < edges_.size(); ++k) {
      const Edge& e = edges_[k];
      half_[k] = 0.5 * (x[e.b] - x[e.a]).norm();
      lmax = std::max(lmax, 2.0 * half_[k]);
      lo = lo.cwiseMin(x[e.a]).cwiseMin(x[e.b]);
      hi = hi.cwiseMax(x[e.a]).cwiseMax(x[e.b]);
      mid_[k] = 0.5 * (x[e.a] + x[e.b]);
    }
    // two segments within the cutoff have midpoints within cutoff + lmax
    grid_.build(lo, hi, cutoff + lmax, 3, mid_);
    old_.swap(list_);
    list_.clear();
    const double cut2 = cutoff * cutoff;
    // the edges are cut into one range per thread, each thread lists its edges' pairs in
    // the serial order, and the lists are joined in thread order: the same list as serial
    parallel_list(sim.threads(), edges_.size(), list_, part_lists_,
                  [&](size_t begin, size_t end, std::vector<Entry>& out) {
                    for (size_t k = begin; k < end; ++k) {
                      const Edge& e = edges_[k];
                      const size_t first = out.size();
                      grid_.for_each_near(mid_[k], [&](int j) {
                        if (static_cast<size_t>(j) <= k) return;  // each pair once
                        // two segments within the cutoff have midpoints within cutoff +
                        // the half lengths: most cell neighbours fail this cheap test (the
                        // bound is widened by 1e-9 so rounding never drops a pair)
                        const double reach =
                            (cutoff + half_[k] + half_[static_cast<size_t>(j)]) * (1.0 + 1e-9);
                        if ((mid_[static_cast<size_t>(j)] - mid_[k]).squaredNorm() > reach * reach)
                          return;
                        const Edge& o = edges_[static_cast<size_t>(j)];
                        if (excluded(e, o)) return;
                        double s, t;
                        closest_points(x[e.a], x[e.b], x[o.a], x[o.b], s, t);
                        const Vec3 d =
                            (x[e.a] + s * (x[e.b] - x[e.a])) - (x[o.a] + t * (x[o.b] - x[o.a]));
                        if (d.squaredNorm() < cut2) {
                          Entry en;
                          en.e1 = static_cast<int>(k);
                          en.e2 = j;
                          en.t1 = e.a;
                          en.t2 = o.a;
                          out.push_back(en);
                        }
                      });
                      std::sort(out.begin() + static_cast<long>(first), out.end(),
                                [](const Entry& a, const Entry& b) { return a.e2 < b.e2; });
                    }
                  });
    // carry the friction history of pairs that stay listed, matched by the edges' tail
    // nodes (a chain fed at its front renumbers its edges)
    carry_pair_history(
        old_, list_, [](const Entry& e) { return id_pair_key(e.t1, e.t2, true); },
        [](const Entry& e) { return e.st.active || e.st.stick; },
        [](const Entry& from, Entry& to) { to.st = from.st; });
    schedule_.built(sim);
    need_build_ = false;
  }

  bool tails_from_ids_ = false;
  double a_;
  ContactLaw law_;
  RebuildSchedule schedule_;
  int exclude_ = 3;
  double estar_per_length_ = 0.0, nominal_k_ = 0.0;
  std::vector<std::string> names_;
  std::vector<const Chain*> chains_;
  std::vector<Edge> edges_;
  std::vector<Entry> list_, old_;
  std::vector<std::vector<Entry>> part_lists_;  // per thread, while the list is built
  CellGrid grid_;
  std::vector<Vec3> mid_;
  std::vector<double> half_;  // half the length of each edge at the last build
  bool need_build_ = true, bound_ = false;
  std::vector<Entry> kept_list_;
  int kept_contacts_ = 0;
  double kept_omega_ = 0.0;
  int contacts_ = 0;
  NodeStiffness stiffness_;
};

}  // namespace slender

SLENDER_REGISTER_STYLE(slender::PairStyle, "contact/segment", slender::SegmentContactPair)
