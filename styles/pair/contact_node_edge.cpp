// Node-edge contact of 2D wires (docs/models.md §2.3). Broad phase: linked cells over
// the nodes, a pair list of (node, edge) closer than d + skin, rebuilt when some
// node moved more than skin/2 since the last build (or every N steps if asked).
// Dense phase: closest point p = (1-t) x_j + t x_{j+1}, overlap d - |x_i - p|,
// the shared contact law (normal force, dashpot, stick-slip friction), and the
// force split by the lever rule: node i gets F, the edge nodes -(1-t)F and -tF,
// so momentum is conserved exactly. Friction history lives in the pair list.
#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>

#include "cell_grid.hpp"
#include "chain_select.hpp"
#include "contact_hessian.hpp"
#include "contact_law.hpp"
#include "pair_history.hpp"
#include "registry.hpp"

namespace slender {

namespace {
std::string format_count(double n) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.0f", n);
  return buf;
}
}  // namespace

class NodeEdgeContactPair : public PairStyle {
 public:
  static ParamSpec spec(const std::string& name) {
    ParamSpec s("pair", name,
                "2D node-edge contact: quadratic repulsion, dashpot, stick-slip Coulomb friction "
                "(docs/models.md §2.3)");
    s.real("diameter", "wire diameter d: contact when a node is closer than d to an edge")
        .def(1.0)
        .positive();
    ContactLaw::declare(s);
    RebuildSchedule::declare(s, "pair-list skin: pairs closer than d + skin are listed");
    s.integer("exclude", "skip edges within this many nodes along the same chain")
        .def(2.0)
        .min(0)
        .max(1000000);
    s.add("chains", ParamType::StringList, "chains that touch each other (default: all)")
        .def(std::vector<std::string>{});
    s.output("contacts", "number of node-edge contacts at the last evaluation");
    s.output("pairs", "number of (node, edge) pairs in the pair list");
    s.output("builds", "number of pair-list builds since the start");
    s.output("omega", "contact frequency measured at the last evaluation, sqrt(max_i k_i / m_i)");
    return s;
  }

  NodeEdgeContactPair(Context& sim, const ParamValues& p)
      : d_(p.real("diameter")),
        law_(ContactLaw::from(p, p.real("diameter"))),
        schedule_(p),
        exclude_(static_cast<int>(p.integer("exclude"))),
        names_(p.strings("chains")) {
    if (sim.dimension() != 2)
      throw InputError("pair style 'contact/node-edge' needs a 2D simulation (dimension = 2)");
    select_chains(sim, names_);
  }

  void setup(Context& sim) override {
    chains_ = select_chains(sim, names_);
    // the first edge not excluded along a straight wire at rest starts exclude + 1 rest
    // lengths away: a diameter that reaches it puts the wire in contact with itself before
    // anything moves (the guard would then blame the run, not the deck)
    double lmin = 1e300;
    for (auto* c : chains_)
      if (c->n_edges() > exclude_ + 1)  // a chain that has such a pair at all
        for (double l : c->rest_length) lmin = std::min(lmin, l);
    if (lmin < 1e300 && d_ >= (exclude_ + 1) * lmin)
      throw InputError("pair style 'contact/node-edge': diameter " + std::to_string(d_) +
                       " reaches past the " + std::to_string(exclude_) +
                       " excluded neighbours along a chain (shortest rest length " +
                       std::to_string(lmin) +
                       "): the wire touches itself at rest; raise exclude "
                       "to at least " +
                       // a double: d / l of an absurd diameter overflows an int (found by fuzzing)
                       format_count(std::floor(d_ / lmin)) + " or space the nodes closer");
    edges_.clear();
    const size_t n = sim.nodes().size();
    chain_of_.assign(n, -1);
    pos_in_chain_.assign(n, -1);
    for (size_t c = 0; c < chains_.size(); ++c) {
      const Chain& ch = *chains_[c];
      for (int k = 0; k < ch.n_nodes(); ++k) {
        chain_of_[ch.nodes[k]] = static_cast<int>(c);
        pos_in_chain_[ch.nodes[k]] = k;
      }
      for (int e = 0; e < ch.n_edges(); ++e)
        edges_.push_back(
            Edge{ch.edge_tail(e), ch.edge_head(e), static_cast<int>(c), e, e > 0 || ch.closed});
    }
    // a list read from a checkpoint knows its edges by number, in the numbering of now
    if (tails_from_ids_)
      for (auto& e : list_)
        if (static_cast<size_t>(e.edge) < edges_.size()) e.tail = edges_[e.edge].a;
    tails_from_ids_ = false;
    need_build_ = true;
  }

  double compute(Context& sim) override {
    if (edges_.empty() && !chains_.empty()) setup(sim);
    if (chain_of_.size() != sim.nodes().size() || topology_changed(sim)) setup(sim);
    if (schedule_.due(sim, need_build_)) build(sim);
    auto& x = sim.nodes().x;
    auto& v = sim.nodes().v;
    const double dt = sim.dt();
    double energy = 0.0;
    contacts_ = 0;
    stiffness_.prepare(sim.threads(), sim.nodes().size());
    std::array<int, kMaxThreads> count{};
    // one work item per listed (node, edge) pair; the list is sorted by node and a new
    // contact takes the history of its node's other entries (hand_over), so each thread's
    // range starts at a node's first entry: a node's entries are handled by one thread,
    // in the serial order
    const size_t n_list = list_.size();
    const int T = threads_for(n_list, sim.threads());
    std::array<size_t, kMaxThreads + 1> start{};
    plan_ranges(T, start);
    std::array<size_t, kMaxThreads> n_near{};
    energy = sim.parallel_node_forces(n_list, [&](int tid, size_t, size_t, Vec3* f) {
      NodeStiffness::Part& stiff = stiffness_.part(tid);
      double e_part = 0.0;
      int n_contacts = 0;
      const size_t k0 = start[static_cast<size_t>(tid)], k1 = start[static_cast<size_t>(tid) + 1];
      // Pass 1, over every listed pair, without data-dependent branches (most pairs are
      // apart, and a mispredicted branch per pair cost more than the arithmetic): the
      // last evaluation's state moves to kPrev, and the pairs that may touch, or that
      // have a contact to release, are noted for pass 2. In 2D the z components are 0.
      std::vector<Near>& todo = todo_[static_cast<size_t>(tid)];
      todo.resize(k1 - k0);
      size_t n_todo = 0;
      for (size_t k = k0; k < k1; ++k) {
        Entry& c = list_[k];
        const bool active = c.flags & kActive;
        c.flags = static_cast<std::uint8_t>((c.flags & kStick) | (active ? kPrev : 0));
        const Edge& ed = edges_[c.edge];
        const Vec3& xa = x[ed.a];
        const Vec3& xb = x[ed.b];
        const Vec3& xn = x[c.node];
        const double sx = xb.x() - xa.x(), sy = xb.y() - xa.y();
        const double dx = xn.x() - xa.x(), dy = xn.y() - xa.y();
        const double len2 = sx * sx + sy * sy;
        const double tr = (dx * sx + dy * sy) / (len2 > 0 ? len2 : 1.0);
        const double t = std::min(std::max(len2 > 0 ? tr : 0.0, 0.0), 1.0);
        const double rx = xn.x() - (xa.x() + t * sx), ry = xn.y() - (xa.y() + t * sy);
        const bool shared_vertex = t == 0.0 && ed.skip_at_tail;
        const bool near = rx * rx + ry * ry <= d2_apart_;
        const bool holds = active | ((c.flags & kStick) != 0) | (c.side != 0);
        todo[n_todo] = Near{k, t, sx, sy, rx, ry};
        n_todo += static_cast<size_t>((!shared_vertex) & (near | holds));
      }
      n_near[static_cast<size_t>(tid)] = n_todo;
      // Pass 2, in list order: the contacts, and the releases.
      for (size_t q = 0; q < n_todo; ++q) {
        const Near& g = todo[q];
        const size_t k = g.k;
        Entry& c = list_[k];
        const bool prev = c.flags & kPrev;
        const Edge& ed = edges_[c.edge];
        const double t = g.t;
        const Vec3 seg(g.sx, g.sy, 0.0);
        const Vec3 r(g.rx, g.ry, 0.0);
        // (d2_apart_ lies a few ulps above d^2, so the exact test below decides the rest)
        const double r2 = g.rx * g.rx + g.ry * g.ry;
        if (r2 > d2_apart_) {
          release(k, prev);
          continue;
        }
        double dist = std::sqrt(r2);
        // which side of the edge the node is on; a contact remembers the side it was
        // made from, so an overloaded node pushed past the centre line is pushed back
        // (overlap d + distance) instead of being pulled through the wire
        // Only an interior closest point has a side: around a vertex or a free wire
        // end the side changes without crossing anything.
        const double cross = seg.x() * r.y() - seg.y() * r.x();
        const int side = cross > 0 ? 1 : -1;
        const bool interior = t > 0.0 && t < 1.0;
        const bool crossed = interior && prev && c.side != 0 && side != c.side && dist < d_;
        if ((dist >= d_ && !crossed) || dist == 0.0) {
          release(k, prev);
          continue;
        }
        Vec3 nrm = r / dist;
        if (crossed) {
          nrm = -nrm;
          dist = -dist;
        } else {
          c.side = static_cast<std::int8_t>(interior ? side : 0);
        }
        const Vec3 vrel = v[c.node] - ((1 - t) * v[ed.a] + t * v[ed.b]);
        FrictionState st;
        st.xi = xi_[k];
        st.stick = c.flags & kStick;
        st.active = prev;
        if (!prev) hand_over(k, st);
        double e_contact = 0.0;
        const Vec3 F = law_.force(d_ - dist, nrm, vrel, dt, st, nullptr, &e_contact);
        xi_[k] = st.xi;
        c.flags = static_cast<std::uint8_t>((c.flags & kPrev) | (st.stick ? kStick : 0) |
                                            (st.active ? kActive : 0));
        f[c.node] += F;
        f[ed.a] -= (1 - t) * F;
        f[ed.b] -= t * F;
        // Hessian k w w^T with w = (1, -(1-t), -t): row sums 2k, 2(1-t)k, 2tk
        const double kc = law_.contact_stiffness(d_ - dist, st);
        stiff.add(c.node, 2 * kc);
        stiff.add(ed.a, 2 * (1 - t) * kc);
        stiff.add(ed.b, 2 * t * kc);
        e_part += e_contact;
        ++n_contacts;
      }
      count[static_cast<size_t>(tid)] = n_contacts;
      return e_part;
    });
    for (int c : count) contacts_ += c;
    stiffness_.finish(sim.nodes().mass);
    if (T > 1) balance(T, start, n_near);
    return energy;
  }

  // The Hessian of the contacts of the last evaluation (docs/models.md §9.9; the energy
  // k/(p+1) overlap^(p+1) of the node's distance to its edge, src/contact_hessian.hpp).
  // Friction's stick springs have no energy of the positions alone: none then.
  bool add_hessian(Context& sim, Hessian& H) const override {
    if (law_.frictional()) return false;
    const auto& x = sim.nodes().x;
    for (const Entry& c : list_) {
      if (!(c.flags & kActive)) continue;
      const Edge& ed = edges_[c.edge];
      const Vec3 seg = x[ed.b] - x[ed.a];
      const double len2 = seg.squaredNorm();
      const double t = len2 > 0 ? std::clamp((x[c.node] - x[ed.a]).dot(seg) / len2, 0.0, 1.0) : 0.0;
      const Vec3 r = x[c.node] - (x[ed.a] + t * seg);
      const double dist = r.norm();
      const bool interior = t > 0.0 && t < 1.0;
      const int side = seg.x() * r.y() - seg.y() * r.x() > 0 ? 1 : -1;
      // pushed past the centre line (compute(): the overlap is then d + distance)
      const double sigma = interior && c.side != 0 && side != c.side ? -1.0 : 1.0;
      const double overlap = d_ - sigma * dist;
      if (!(overlap > 0.0)) continue;
      Eigen::MatrixXd dc(3, interior ? 1 : 0);
      if (interior) dc << 0.0, 1.0, -1.0;
      add_distance_hessian<3>(H, {c.node, ed.a, ed.b}, x, Eigen::Vector3d(1.0, -(1 - t), -t), dc,
                              -sigma * law_.elastic_force(overlap), law_.tangent_stiffness(overlap),
                              sim.dimension());
    }
    return true;
  }
  double max_frequency(const Context& sim) const override {
    double m = 1e300;
    for (auto* c : select_chains(sim, names_))
      for (int i : c->nodes) m = std::min(m, sim.nodes().mass[i]);
    if (m >= 1e300) return 0.0;
    // two bodies on the contact spring at an overlap of a tenth of a diameter
    const double k =
        law_.tangent_stiffness(0.1 * d_) + (law_.frictional() ? law_.stick_stiffness : 0.0);
    return std::sqrt(2.0 * k / m);
  }
  std::string neighbor_structure() const override { return "linked cells + node-edge pair list"; }
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
    for (size_t k = 0; k < list_.size(); ++k) {
      const Entry& e = list_[k];
      flat.insert(flat.end(), {double(e.node), double(e.edge), xi_[k].x(), xi_[k].y(),
                               (e.flags & kStick) ? 1.0 : 0.0, (e.flags & kActive) ? 1.0 : 0.0,
                               double(e.side)});
    }
    st["history"] = flat;
    save_measured(st, {double(contacts_), stiffness_.omega()});
    schedule_.save(st);
    // the threads' cut, so that a restart adds the forces in the same order
    std::vector<double> cut{double(cut_threads_)};
    for (int t = 1; t < cut_threads_; ++t) cut.push_back(cut_node_[static_cast<size_t>(t)]);
    st["thread_cut"] = cut;
  }
  // the guard's copy: the list as it was (its tails intact), rebuilt from the restored
  // positions at the next evaluation with this history
  void keep() override {
    kept_list_ = list_;
    kept_xi_ = xi_;
    kept_contacts_ = contacts_;
    kept_omega_ = stiffness_.omega();
  }
  void restore_kept() override {
    list_ = kept_list_;
    xi_ = kept_xi_;
    contacts_ = kept_contacts_;
    stiffness_.set_omega(kept_omega_);
    need_build_ = true;
  }
  void load_state(const StateMap& st) override {
    list_.clear();
    xi_.clear();
    auto& h = saved_array(st, "history");
    for (size_t k = 0; k + 7 <= h.size(); k += 7) {
      Entry e;
      e.node = saved_index(h[k]);
      e.edge = saved_index(h[k + 1]);
      e.flags =
          static_cast<std::uint8_t>((h[k + 4] != 0 ? kStick : 0) | (h[k + 5] != 0 ? kActive : 0));
      e.side = static_cast<std::int8_t>(std::abs(h[k + 6]) <= 1 ? h[k + 6] : 2);
      list_.push_back(e);
      xi_.emplace_back(h[k + 2], h[k + 3], 0);
    }
    if (auto* m = load_measured(st, 2)) {
      contacts_ = saved_int((*m)[0]);
      stiffness_.set_omega((*m)[1]);
    } else if (auto* m1 = load_measured(st, 1)) {
      contacts_ = saved_int((*m1)[0]);
    }
    tails_from_ids_ = true;
    schedule_.load(st);
    // (older checkpoints have no cut: equal ranges until the first evaluation)
    cut_threads_ = 0;
    if (auto it = st.find("thread_cut"); it != st.end() && !it->second.empty()) {
      const int T = saved_int(it->second[0]);
      if (T >= 2 && T <= kMaxThreads && it->second.size() == static_cast<size_t>(T)) {
        cut_threads_ = T;
        for (int t = 1; t < T; ++t)
          cut_node_[static_cast<size_t>(t)] = saved_int(it->second[static_cast<size_t>(t)]);
      }
    }
  }
  std::string check_loaded(const Context& sim) const override {
    std::size_t edges = 0;
    for (auto* c : select_chains(sim, names_)) edges += static_cast<std::size_t>(c->n_edges());
    const std::size_t n = sim.nodes().size();
    for (std::size_t k = 0; k < list_.size(); ++k) {
      const Entry& e = list_[k];
      if (e.node < 0 || static_cast<std::size_t>(e.node) >= n || e.edge < 0 ||
          static_cast<std::size_t>(e.edge) >= edges || std::abs(e.side) > 1 || !xi_[k].allFinite())
        return "pair " + std::to_string(k + 1) + " of the history (node " +
               std::to_string(e.node + 1) + ", edge " + std::to_string(e.edge + 1) +
               ") is not a node and an edge of its chains (" + std::to_string(n) + " nodes, " +
               std::to_string(edges) + " edges), or holds NaN";
    }
    return "";
  }

 private:
  struct Edge {
    int a, b, chain, index;
    // a closest point at the tail vertex belongs to the previous edge (not the first edge
    // of an open chain)
    bool skip_at_tail;
  };
  // One listed (node, edge) pair, 16 bytes: the evaluation reads every entry every step and
  // most are apart, so the hot fields sit together and the stick spring (xi_, by the same
  // index) is touched only by contacts. With the friction state inside each entry (56
  // bytes) the list outgrew the core's cache at N = 10^4.
  struct Entry {
    int node = 0, edge = 0;
    int tail = 0;            // the edge's first node: edge numbers change when a chain grows
    std::uint8_t flags = 0;  // kActive, kPrev, kStick
    std::int8_t side = 0;    // +1 / -1: side of the edge the contact was made from; 0: none
  };
  // in contact at the last evaluation / at the one before (while evaluating) / stuck
  static constexpr std::uint8_t kActive = 1, kPrev = 2, kStick = 4;

  // A listed pair out of contact forgets its stick spring and its side. One that was not in
  // contact at the last evaluation has nothing to forget (its xi is never read before a
  // new contact sets it: FrictionState restarts an inactive contact), so its line is not
  // written.
  void release(size_t k, bool prev) {
    Entry& c = list_[k];
    if (!prev && !(c.flags & kStick) && c.side == 0) return;
    c.flags = static_cast<std::uint8_t>(c.flags & ~kStick);
    xi_[k].setZero();
    c.side = 0;
  }
  // The threads' ranges of the list. Most of an evaluation's cost is in the pairs that touch
  // (pass 2), and contacts cluster along the wire, so equal ranges of entries left one thread
  // waiting for the other (measured: 40 % more work on one of two threads at N = 12 000).
  // The cut of the last evaluation (balance()) is kept as node numbers: the list is sorted by
  // node, so a cut is found again after a rebuild, and it falls on a node's first entry (a
  // node's entries stay on one thread, as hand_over needs). Without one: equal ranges.
  // Deterministic: the cut depends on the state only, not on timings.
  void plan_ranges(int T, std::array<size_t, kMaxThreads + 1>& start) const {
    const size_t n = list_.size();
    auto node_start = [&](size_t i) {
      while (i > 0 && i < n && list_[i].node == list_[i - 1].node) ++i;
      return i;
    };
    start[0] = 0;
    start[static_cast<size_t>(T)] = n;
    for (int t = 1; t < T; ++t) {
      size_t k = n * static_cast<size_t>(t) / static_cast<size_t>(T);
      if (cut_threads_ == T) {
        const int node = cut_node_[static_cast<size_t>(t)];
        k = static_cast<size_t>(std::lower_bound(list_.begin(), list_.end(), node,
                                                 [](const Entry& e, int v) { return e.node < v; }) -
                                list_.begin());
      }
      start[static_cast<size_t>(t)] =
          std::max(start[static_cast<size_t>(t) - 1], std::min(node_start(k), n));
    }
  }
  // Cuts the list where the cost of this evaluation, one unit per listed pair and
  // kNearCost per pair of pass 2, splits evenly; kept for the next evaluation.
  void balance(int T, const std::array<size_t, kMaxThreads + 1>& start,
               const std::array<size_t, kMaxThreads>& n_near) {
    // a pair of pass 2 (contact law, friction, stiffness) against one of pass 1 (a closest
    // point): about 30 ns against 3-4 ns in a profile of the classic crumpling deck
    constexpr double kNearCost = 8.0;
    double total = 0.0;
    std::array<double, kMaxThreads> cost{};
    for (size_t t = 0; t < static_cast<size_t>(T); ++t) {
      cost[t] =
          static_cast<double>(start[t + 1] - start[t]) + kNearCost * static_cast<double>(n_near[t]);
      total += cost[t];
    }
    double base = 0.0;
    size_t t = 0;
    for (int j = 1; j < T; ++j) {
      const double target = total * j / T;
      while (t + 1 < static_cast<size_t>(T) && base + cost[t] < target) base += cost[t++];
      const auto first = todo_[t].begin(), last = first + static_cast<long>(n_near[t]);
      // the cost of thread t's entries before k
      auto cost_to = [&](size_t k) {
        const auto near =
            std::lower_bound(first, last, k, [](const Near& g, size_t v) { return g.k < v; });
        return base + static_cast<double>(k - start[t]) +
               kNearCost * static_cast<double>(near - first);
      };
      size_t lo = start[t], hi = start[t + 1];
      while (lo < hi) {
        const size_t mid = lo + (hi - lo) / 2;
        if (cost_to(mid) < target)
          lo = mid + 1;
        else
          hi = mid;
      }
      cut_node_[static_cast<size_t>(j)] = lo < list_.size() ? list_[lo].node : INT_MAX;
    }
    cut_threads_ = T;
  }
  bool topology_changed(const Context&) const {
    size_t ne = 0;
    for (auto* c : chains_) ne += static_cast<size_t>(c->n_edges());
    return ne != edges_.size();
  }
  bool excluded(int node, const Edge& e) const {
    if (chain_of_[node] != e.chain) return false;
    const Chain& ch = *chains_[e.chain];
    const int n = ch.n_nodes(), i = pos_in_chain_[node];
    auto gap = [&](int j) {
      int g = std::abs(i - j);
      return ch.closed ? std::min(g, n - g) : g;
    };
    return std::min(gap(e.index), gap((e.index + 1) % n)) <= exclude_;
  }

  // Linked cells over the nodes; each edge is filed under its midpoint's cell.
  void build(Context& sim) {
    auto& x = sim.nodes().x;
    const double cutoff = d_ + schedule_.skin();
    double lmax = 0.0;
    Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
    for (auto& e : edges_) {
      lmax = std::max(lmax, (x[e.b] - x[e.a]).norm());
      for (int i : {e.a, e.b}) {
        lo = lo.cwiseMin(x[i]);
        hi = hi.cwiseMax(x[i]);
      }
    }
    mid_.resize(edges_.size());
    for (size_t k = 0; k < edges_.size(); ++k) mid_[k] = 0.5 * (x[edges_[k].a] + x[edges_[k].b]);
    grid_.build(lo, hi, cutoff + 0.5 * lmax, 2, mid_);

    old_.swap(list_);
    old_xi_.swap(xi_);
    list_.clear();
    const double cut2 = cutoff * cutoff;
    // the nodes are cut into one range per thread, each thread lists its nodes' pairs in
    // the serial order, and the lists are joined in thread order: the same list as serial
    parallel_list(sim.threads(), chain_of_.size(), list_, part_lists_,
                  [&](size_t begin, size_t end, std::vector<Entry>& out) {
                    for (size_t i = begin; i < end; ++i) {
                      if (chain_of_[i] < 0) continue;
                      const int node = static_cast<int>(i);
                      const size_t first = out.size();
                      grid_.for_each_near(x[i], [&](int eid) {
                        const Edge& e = edges_[static_cast<size_t>(eid)];
                        if (excluded(node, e)) return;
                        const Vec3 seg = x[e.b] - x[e.a];
                        const double len2 = seg.squaredNorm();
                        const double t =
                            len2 > 0 ? std::clamp((x[i] - x[e.a]).dot(seg) / len2, 0.0, 1.0) : 0.0;
                        if ((x[i] - x[e.a] - t * seg).squaredNorm() < cut2) {
                          Entry en;
                          en.node = node;
                          en.edge = eid;
                          en.tail = e.a;
                          out.push_back(en);
                        }
                      });
                      std::sort(out.begin() + static_cast<long>(first), out.end(),
                                [](const Entry& a, const Entry& b) { return a.edge < b.edge; });
                    }
                  });
    // carry the history of pairs that stay listed, matched by (node, edge tail node)
    xi_.assign(list_.size(), Vec3::Zero());
    carry_pair_history_indexed(
        old_.size(), list_.size(),
        [&](size_t k) { return id_pair_key(old_[k].node, old_[k].tail); },
        [&](size_t k) { return id_pair_key(list_[k].node, list_[k].tail); },
        [&](size_t k) { return (old_[k].flags & (kActive | kStick)) || old_[k].side != 0; },
        [&](size_t from, size_t to) {
          list_[to].flags = static_cast<std::uint8_t>(old_[from].flags & (kActive | kStick));
          list_[to].side = old_[from].side;
          xi_[to] = old_xi_[from];
        });
    schedule_.built(sim);
    need_build_ = false;
  }

  // A new contact whose node was touching the neighbouring edge of the same chain
  // at the last evaluation (kPrev, set for every entry by pass 1) takes over that
  // contact's stick state (docs/models.md §2.3): the state as it is when entry k is reached,
  // i.e. already updated by this evaluation for the entries before k.
  // Entry k's friction state is in `st` (not yet written back).
  void hand_over(size_t k, FrictionState& st) const {
    const Entry& c = list_[k];
    const Edge& ed = edges_[static_cast<size_t>(c.edge)];
    for (size_t j = k; j-- > 0 && list_[j].node == c.node;)
      try_take(st, ed, j, list_[j].flags & kPrev);
    for (size_t j = k + 1; j < list_.size() && list_[j].node == c.node; ++j)
      try_take(st, ed, j, list_[j].flags & kPrev);
  }
  void try_take(FrictionState& st, const Edge& ed, size_t other, bool other_was_active) const {
    const Edge& eo = edges_[static_cast<size_t>(list_[other].edge)];
    if (!other_was_active || eo.chain != ed.chain || std::abs(eo.index - ed.index) != 1) return;
    st.xi = xi_[other];
    st.stick = list_[other].flags & kStick;
    st.active = true;
  }

  bool tails_from_ids_ = false;
  double d_;
  double d2_apart_ = d_ * d_ * (1.0 + 1e-14);  // |r|^2 above this: |r| >= d for sure
  ContactLaw law_;
  RebuildSchedule schedule_;
  int exclude_;
  std::vector<std::string> names_;
  std::vector<const Chain*> chains_;
  std::vector<Edge> edges_;
  std::vector<int> chain_of_, pos_in_chain_;
  std::vector<Entry> list_, old_;
  std::vector<Vec3> xi_, old_xi_;
  std::vector<Entry> kept_list_;
  std::vector<Vec3> kept_xi_;
  int kept_contacts_ = 0;
  double kept_omega_ = 0.0;  // stick spring (or last slip direction) of list_[k]
  std::vector<std::vector<Entry>> part_lists_;
  // pass 1's pairs for pass 2, per thread: list index, closest point, edge, separation
  struct Near {
    size_t k;
    double t, sx, sy, rx, ry;
  };
  std::vector<std::vector<Near>> todo_ =
      std::vector<std::vector<Near>>(kMaxThreads);  // per thread, while the list is built
  // where balance() cut the list for cut_threads_ threads: thread t starts at the first
  // entry of node cut_node_[t] or above (0 threads: no cut yet, equal ranges)
  int cut_threads_ = 0;
  std::array<int, kMaxThreads + 1> cut_node_{};
  CellGrid grid_;
  std::vector<Vec3> mid_;
  bool need_build_ = true;
  int contacts_ = 0;
  NodeStiffness stiffness_;
};

}  // namespace slender

SLENDER_REGISTER_STYLE(slender::PairStyle, "contact/node-edge", slender::NodeEdgeContactPair)
