// Self-contact of a shell surface (docs/models.md §6.10, (5.36)), frictionless unless
// mu_static > 0 (then stick-slip friction per triangle pair, §2.3).
//
// Broad phase: triangle AABBs (current control mesh, inflated by (h + skin)/2) in
// cubic voxels of edge max(largest AABB, h), so a box spans at most 2 voxels per
// axis (docs/models.md §6.10 planned twice that; smaller voxels hold fewer pairs); a pair
// list rebuilt every `rebuild_every` steps or as soon as a node has moved skin/2 since the
// last build, as the scene's neighbour service decides for every list at once
// (src/neighbors.hpp).
// Topology check: the smallest reference distance d_ref between the vertices of the
// two triangles; pairs with d_ref = 0 (neighbours) never collide, pairs with
// d_ref <= h (near neighbours) only while their current normals oppose (n1.n2 < 0,
// a ridge; Fig. 5.6). Dense phase: closest points of the two control triangles
// (vertex-triangle and edge-edge), force f = k (h - r)^2 / r^2 along d/r for r < h,
// r clamped at 1e-3 h, split with the barycentric weights. The force derives from
// U(r) = k (h^2/r - r + 2 h ln(r/h)), continued linearly below the clamp.
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>
#include <unordered_map>

#include "contact_hessian.hpp"
#include "contact_law.hpp"
#include "context.hpp"
#include "pair_history.hpp"
#include "registry.hpp"
#include "shell/triangle_distance.hpp"
#include "shell/trimesh.hpp"

namespace slender {

class ShellContactPair : public PairStyle {
 public:
  static ParamSpec spec(const std::string& name) {
    ParamSpec s("pair", name,
                "self-contact of a shell surface: voxel broad phase, reference-distance topology "
                "check, faceted dense phase, repulsion k (h-r)^2/r^2 (docs/models.md §6.10, "
                "(5.36))");
    s.string("mesh", "surface created by sim:mesh").required();
    s.real("thickness", "contact distance h (the shell thickness)").required().positive();
    s.real("k", "contact stiffness k_ct (default Y h mean_edge)").positive();
    s.real("young", "Young's modulus for the default k").def(1e4).positive();
    s.real("skin", "extra reach of the pair list (default h)").positive();
    s.real("near_distance",
           "pairs whose smallest reference vertex distance is at most this are near "
           "neighbours and touch only across a ridge (docs/models.md §6.10: h; a few h keeps the "
           "tightly curved core of a thick e-cone from touching itself)")
        .positive();
    s.string("near_contact",
             "ridge: near neighbours touch only while their normals oppose (docs/models.md §6.10); "
             "never: they never touch (no force that switches on with the sign of n1.n2)")
        .def(std::string("ridge"))
        .choices({"ridge", "never"});
    s.string("dense",
             "closest: one force per triangle pair along its closest points (docs/models.md "
             "§6.10); all: one per vertex-triangle and edge-edge feature pair within h, a "
             "smoother sum that lets relaxations converge when faceted contacts slide")
        .def(std::string("closest"))
        .choices({"closest", "all"});
    s.real("far_distance",
           "contacts between triangles farther apart than this in the reference are also "
           "counted as far_contacts (e.g. the wings of an e-cone, not its apex)")
        .def(0.0)
        .nonnegative();
    s.integer("rebuild_every", "steps between pair-list rebuilds (also rebuilt on movement)")
        .def(20.0)
        .min(1);
    s.real("mu_static",
           "static friction between contacting areas (docs/models.md §6.10: the stabilised "
           "symmetric e-cone, S-2), stick-slip as in §2.3; sim:modify can change it (0: release)")
        .def(0.0)
        .nonnegative();
    s.real("mu_dynamic", "dynamic friction coefficient (default 0.9 mu_static)").nonnegative();
    s.real("stick_stiffness",
           "tangential stick spring of a triangle pair carrying the normal force k (at r = h/2); "
           "it scales with the pair's normal force, so every pair of a contact patch slips at "
           "the same tangential displacement mu k / stick_stiffness (default 4 k / h: h mu / 4)")
        .positive();
    s.real("slip_velocity", "slipping contacts slower than this stick again")
        .def(1e-4)
        .nonnegative();
    ContactLaw::declare_new_contacts(s);
    s.output("contacts", "number of triangle pairs in contact at the last evaluation");
    s.output("far_contacts",
             "contacts of triangles farther apart than far_distance in the reference");
    s.output("force", "sum of the magnitudes of the normal contact forces");
    s.output("gamma",
             "angle between the two contact planes (radians), -1 without two contact zones");
    s.output("pairs", "number of triangle pairs in the pair list");
    s.output("rebuilds", "number of pair-list rebuilds since the start");
    return s;
  }
  ShellContactPair(Context& sim, const ParamValues& p)
      : mesh_name_(p.str("mesh")), h_(p.real("thickness")), every_(p.integer("rebuild_every")) {
    const Surface* s = sim.topology().find_surface(p.str("mesh"));
    if (!s) throw InputError("pair 'contact/shell': no mesh named '" + p.str("mesh") + "'");
    mesh_ = s->mesh;
    base_ = s->first_node;
    mean_edge_ = shell::reference_edges(*mesh_).mean;
    k_ = p.has("k") ? p.real("k") : p.real("young") * h_ * mean_edge_;
    skin_ = p.has("skin") ? p.real("skin") : h_;
    near_ = p.has("near_distance") ? p.real("near_distance") : h_;
    near_never_ = p.str("near_contact") == "never";
    far_ = p.real("far_distance");
    dense_all_ = p.str("dense") == "all";
    set_friction(p);
    face_flag_.assign(mesh_->n_real_tris, 0.0);
    // dense = all: each vertex and each edge is owned by one of its triangles, so that
    // a vertex-triangle or edge-edge term is summed once, not once per triangle pair
    const auto& tri = mesh_->mesh.tri;
    std::vector<int> vertex_owner(mesh_->mesh.n_nodes(), -1);
    std::map<std::pair<int, int>, int> edge_owner;
    for (int t = 0; t < mesh_->n_real_tris; ++t)
      for (int k = 0; k < 3; ++k) {
        if (vertex_owner[tri[t][k]] < 0) vertex_owner[tri[t][k]] = t;
        const int a = tri[t][k], b = tri[t][(k + 1) % 3];
        edge_owner.try_emplace({std::min(a, b), std::max(a, b)}, t);
      }
    masks_.resize(mesh_->n_real_tris);
    for (int t = 0; t < mesh_->n_real_tris; ++t)
      for (int k = 0; k < 3; ++k) {
        const int a = tri[t][k], b = tri[t][(k + 1) % 3];
        masks_[t].vertex[k] = vertex_owner[a] == t;
        masks_[t].edge[k] = edge_owner.at({std::min(a, b), std::max(a, b)}) == t;
      }
  }

  void set_friction(const ParamValues& p) {
    friction_.mu_static = p.real("mu_static");
    friction_.mu_dynamic = p.has("mu_dynamic") ? p.real("mu_dynamic") : 0.9 * friction_.mu_static;
    friction_.stick_stiffness = p.has("stick_stiffness") ? p.real("stick_stiffness") : 4 * k_ / h_;
    friction_.slip_velocity = p.real("slip_velocity");
    friction_.new_stick_always = p.str("new_contacts") == "stick";
    if (friction_.mu_dynamic > friction_.mu_static)
      throw InputError("pair 'contact/shell': mu_dynamic must not exceed mu_static");
  }
  // Friction can be switched on and off between runs (S-2 releases it at phi_e = 10).
  void modify(const RawParams& raw) override {
    RawParams full = raw;
    for (auto& kv : raw)
      if (kv.first != "mu_static" && kv.first != "mu_dynamic" && kv.first != "stick_stiffness" &&
          kv.first != "slip_velocity" && kv.first != "new_contacts")
        throw InputError("pair 'contact/shell': modify accepts only the friction keys, not '" +
                         kv.first + "'");
    full["mesh"] = mesh_name_;
    full["thickness"] = h_;
    full["near_distance"] = near_;
    full["near_contact"] = std::string(near_never_ ? "never" : "ridge");
    full["far_distance"] = far_;
    full["dense"] = std::string(dense_all_ ? "all" : "closest");
    if (!full.count("mu_static")) full["mu_static"] = friction_.mu_static;
    if (!full.count("stick_stiffness")) full["stick_stiffness"] = friction_.stick_stiffness;
    // keys not given keep their values (not the declared defaults)
    if (!full.count("slip_velocity")) full["slip_velocity"] = friction_.slip_velocity;
    if (!full.count("new_contacts"))
      full["new_contacts"] = std::string(friction_.new_stick_always ? "stick" : "by_speed");
    set_friction(spec(style_name()).validate(full));
    if (!friction_.frictional())
      for (auto& c : pairs_) c.friction = FrictionState{};
  }

  void setup(Context& sim) override {
    m_min_ = 1e300;
    for (int i = 0; i < mesh_->n_real_nodes; ++i)
      m_min_ = std::min(m_min_, sim.nodes().mass[base_ + i]);
  }

  // stiffness at an overlap of 20% of h, the scale of resolved contacts
  double max_frequency(const Context&) const override {
    const double r = 0.8 * h_;
    double kr = k_ * (2 * (h_ - r) / (r * r) + 2 * (h_ - r) * (h_ - r) / (r * r * r));
    // the stick spring of a pair carrying the normal force at that overlap
    if (friction_.frictional()) kr += friction_.stick_stiffness * (h_ - r) * (h_ - r) / (r * r);
    // dense = all: a node above a vertex of the other sheet meets up to six triangles
    if (dense_all_) kr *= 6;
    return std::sqrt(kr / m_min_);
  }

  double compute(Context& sim) override {
    auto& x = sim.nodes().x;
    auto& f = sim.nodes().f;
    if (handle_ < 0) handle_ = sim.neighbors().request(this, skin_, every_);
    if (need_build_) sim.neighbors().invalidate();
    if (sim.neighbors().due(handle_, x, sim.step())) {
      rebuild(x);
      sim.neighbors().built(handle_, sim.step());
    }
    const auto& T = mesh_->mesh.tri;
    double energy = 0;
    contacts_ = 0;
    far_contacts_ = 0;
    force_sum_ = 0;
    std::fill(face_flag_.begin(), face_flag_.end(), 0.0);
    points_.clear();
    forces_.clear();
    const double rc = 1e-3 * h_;
    // bounding boxes of this step, once per triangle
    const int nt = mesh_->n_real_tris;
    box_lo_.resize(nt);
    box_hi_.resize(nt);
    for (int t = 0; t < nt; ++t) {
      const Vec3 &a = x[base_ + T[t][0]], &b = x[base_ + T[t][1]], &c = x[base_ + T[t][2]];
      box_lo_[t] = a.cwiseMin(b).cwiseMin(c).array() - 0.5 * h_;
      box_hi_[t] = a.cwiseMax(b).cwiseMax(c).array() + 0.5 * h_;
    }
    // Pass 1, on threads: screen every listed pair (boxes, the ridge rule, the separating
    // planes) and find its feature pairs within h; pure geometry, one record per feature
    // pair in list order (or one "not touching" record). Pass 2, serial, in list order:
    // forces, energies and friction, so that any thread count gives the serial sums.
    hits_.clear();
    parallel_list(sim.heavy_threads(), pairs_.size(), hits_, hit_parts_,
                  [&](std::size_t begin, std::size_t end, std::vector<Hit>& out) {
                    for (std::size_t i = begin; i < end; ++i) screen(x, i, out);
                  });
    auto& v = sim.nodes().v;
    for (std::size_t k = 0; k < hits_.size();) {
      Candidate& c = pairs_[hits_[k].pair];
      if (!hits_[k].touching) {
        c.friction.active = false;
        ++k;
        continue;
      }
      std::array<Vec3, 3> A, B;
      for (int j = 0; j < 3; ++j) {
        A[j] = x[base_ + T[c.t1][j]];
        B[j] = x[base_ + T[c.t2][j]];
      }
      // normal forces of this pair; friction acts once per pair on their sum, at the
      // force-weighted contact point (so dense = all and closest share one stick spring)
      Vec3 normal_sum = Vec3::Zero(), w1_sum = Vec3::Zero(), w2_sum = Vec3::Zero();
      double mag_sum = 0;
      const std::size_t pair = hits_[k].pair;
      for (; k < hits_.size() && hits_[k].pair == pair; ++k) {
        const shell::TrianglePair& tp = hits_[k].tp;
        Vec3 dir = tp.d;
        if (tp.dist > 0) {
          dir /= tp.dist;
        } else {  // touching: push along the normal of T1
          dir = hits_[k].n1.normalized();
        }
        const double r = std::max(tp.dist, rc);
        const double mag = k_ * (h_ - r) * (h_ - r) / (r * r);
        double U = k_ * (h_ * h_ / r - r + 2 * h_ * std::log(r / h_));
        if (tp.dist < rc) U += mag * (rc - tp.dist);
        energy += U;
        const Vec3 fv = mag * dir;
        for (int j = 0; j < 3; ++j) {
          f[base_ + T[c.t1][j]] += tp.w1[j] * fv;
          f[base_ + T[c.t2][j]] -= tp.w2[j] * fv;
        }
        force_sum_ += mag;
        normal_sum += fv;
        mag_sum += mag;
        for (int j = 0; j < 3; ++j) {
          w1_sum[j] += mag * tp.w1[j];
          w2_sum[j] += mag * tp.w2[j];
        }
        Vec3 p1 = Vec3::Zero(), p2 = Vec3::Zero();
        for (int j = 0; j < 3; ++j) {
          p1 += tp.w1[j] * A[j];
          p2 += tp.w2[j] * B[j];
        }
        points_.push_back(0.5 * (p1 + p2));
        forces_.push_back(fv);
      }
      const double normal = normal_sum.norm();
      if (friction_.frictional() && normal > 0) {
        const Vec3 w1 = w1_sum / mag_sum, w2 = w2_sum / mag_sum;
        Vec3 vrel = Vec3::Zero();
        for (int j = 0; j < 3; ++j)
          vrel += w1[j] * v[base_ + T[c.t1][j]] - w2[j] * v[base_ + T[c.t2][j]];
        // a pair's stick spring scales with its normal force (contact size), so that the
        // lightly loaded pairs at a patch's rim do not slip first and unzip the patch
        ContactLaw law = friction_;
        law.stick_stiffness *= normal / k_;
        const Vec3 ft = law.friction(normal, normal_sum / normal, vrel, sim.dt(), c.friction);
        for (int j = 0; j < 3; ++j) {
          f[base_ + T[c.t1][j]] += w1[j] * ft;
          f[base_ + T[c.t2][j]] -= w2[j] * ft;
        }
      }
      ++contacts_;
      if (c.dref > far_) ++far_contacts_;
      face_flag_[c.t1] = face_flag_[c.t2] = 1.0;
    }
    return energy;
  }

  // The Hessian of the contact energy at the current positions (docs/models.md §9.9): each
  // feature pair that compute() loads is a distance between two closest points on the
  // control triangles, weights w1 on T1 and -w2 on T2; a weight's support of m vertices
  // leaves m - 1 free parameters (a vertex, an edge, the face). U'(r) = -k (h-r)^2/r^2,
  // U''(r) = 2 k h (h-r)/r^3, and the linear continuation below 1e-3 h has U'' = 0.
  // Friction's stick springs have no energy of the positions alone: none then.
  bool add_hessian(Context& sim, Hessian& H) const override {
    if (friction_.frictional()) return false;
    const auto& x = sim.nodes().x;
    const auto& T = mesh_->mesh.tri;
    const double rc = 1e-3 * h_;
    for (const Candidate& c : pairs_) {
      std::array<Vec3, 3> A, B;
      std::array<int, 6> node{};
      for (int k = 0; k < 3; ++k) {
        node[k] = base_ + T[c.t1][k];
        node[3 + k] = base_ + T[c.t2][k];
        A[k] = x[node[k]];
        B[k] = x[node[3 + k]];
      }
      const Vec3 n1 = (A[1] - A[0]).cross(A[2] - A[0]), n2 = (B[1] - B[0]).cross(B[2] - B[0]);
      if (c.near && (near_never_ || n1.dot(n2) > 0)) continue;
      if (separated(A, B, n1, n2)) continue;
      auto add = [&](const shell::TrianglePair& tp) {
        if (!(tp.dist > 0.0)) return;  // touching: no distance to differentiate
        const double r = std::max(tp.dist, rc);
        const double dE = -k_ * (h_ - r) * (h_ - r) / (r * r);
        const double d2E = tp.dist < rc ? 0.0 : 2 * k_ * h_ * (h_ - r) / (r * r * r);
        Eigen::Matrix<double, 6, 1> w;
        w << tp.w1[0], tp.w1[1], tp.w1[2], -tp.w2[0], -tp.w2[1], -tp.w2[2];
        // free parameters: on each side, moving weight from its first supported vertex to
        // each other one
        Eigen::MatrixXd dc = Eigen::MatrixXd::Zero(6, 4);
        int m = 0;
        for (int side = 0; side < 2; ++side) {
          const auto& ws = side == 0 ? tp.w1 : tp.w2;
          const double sign = side == 0 ? 1.0 : -1.0;
          int first = -1;
          for (int k = 0; k < 3; ++k) {
            if (ws[k] == 0.0) continue;
            if (first < 0) {
              first = k;
              continue;
            }
            dc(3 * side + first, m) = -sign;
            dc(3 * side + k, m) = sign;
            ++m;
          }
        }
        add_distance_hessian<6>(H, node, x, w, Eigen::MatrixXd(dc.leftCols(m)), dE, d2E, 3);
      };
      if (dense_all_) {
        shell::for_each_feature_pair(
            A, B,
            [&](const shell::TrianglePair& tp) {
              if (tp.dist < h_) add(tp);
            },
            masks_[c.t1], masks_[c.t2]);
      } else {
        const shell::TrianglePair tp = shell::triangle_distance(A, B);
        if (tp.dist < h_) add(tp);
      }
    }
    return true;
  }

  std::string neighbor_structure() const override { return "voxels + triangle pair list"; }
  double value(const std::string& key) const override {
    if (key == "contacts") return contacts_;
    if (key == "far_contacts") return far_contacts_;
    if (key == "force") return force_sum_;
    if (key == "gamma") return contact_plane_angle();
    if (key == "pairs") return static_cast<double>(pairs_.size());
    if (key == "rebuilds") return static_cast<double>(rebuilds_);
    return PairStyle::value(key);
  }
  // Friction history, so that a restarted run sticks where it stuck.
  void save_state(StateMap& st) const override {
    std::vector<double> fr;
    for (auto& c : pairs_)
      if (c.friction.active)
        fr.insert(fr.end(), {double(c.t1), double(c.t2), c.friction.xi.x(), c.friction.xi.y(),
                             c.friction.xi.z(), c.friction.stick ? 1.0 : 0.0});
    if (!fr.empty()) st["friction"] = fr;
    save_measured(st, {double(contacts_), double(far_contacts_), force_sum_});
  }
  void load_state(const StateMap& st) override {
    restored_.clear();
    if (auto it = st.find("friction"); it != st.end())
      for (std::size_t k = 0; k + 5 < it->second.size(); k += 6) {
        const auto& v = it->second;
        Candidate c{saved_index(v[k]), saved_index(v[k + 1]), false, 0.0, FrictionState{}};
        c.friction.xi = Vec3(v[k + 2], v[k + 3], v[k + 4]);
        c.friction.stick = v[k + 5] != 0;
        c.friction.active = true;
        restored_.push_back(c);
      }
    if (auto* m = load_measured(st, 3)) {
      contacts_ = saved_int((*m)[0]);
      far_contacts_ = saved_int((*m)[1]);
      force_sum_ = (*m)[2];
    }
    need_build_ = true;  // rebuild the list (with this history) at the next evaluation
    pairs_.clear();
  }

  std::string check_loaded(const Context&) const override {
    for (std::size_t k = 0; k < restored_.size(); ++k) {
      const Candidate& c = restored_[k];
      if (c.t1 < 0 || c.t2 <= c.t1 || c.t2 >= mesh_->n_real_tris || !c.friction.xi.allFinite())
        return "friction pair " + std::to_string(k + 1) + " (triangles " + std::to_string(c.t1) +
               ", " + std::to_string(c.t2) + ") is not two triangles of mesh '" + mesh_name_ +
               "' (" + std::to_string(mesh_->n_real_tris) + "), or holds NaN";
    }
    return "";
  }
  const std::vector<double>* face_values(const std::string& key) const override {
    return key == "contact" ? &face_flag_ : nullptr;
  }

  // Angle between the two contact planes (docs/models.md §6.11): the contact points are
  // split into two zones (2-means), the forces of each zone averaged with one
  // orientation; gamma = acos |n1 . n2|. -1 when there are not two zones.
  double contact_plane_angle() const {
    const int n = static_cast<int>(points_.size());
    if (n < 2) return -1;
    // seeds: the two points farthest apart
    int s1 = 0, s2 = 0;
    double best = -1;
    for (int i = 0; i < n; ++i)
      for (int j = i + 1; j < n; ++j)
        if ((points_[i] - points_[j]).squaredNorm() > best) {
          best = (points_[i] - points_[j]).squaredNorm();
          s1 = i;
          s2 = j;
        }
    if (best < (4 * h_) * (4 * h_)) return -1;  // a single zone
    Vec3 c1 = points_[s1], c2 = points_[s2];
    std::vector<int> zone(n);
    for (int it = 0; it < 20; ++it) {
      Vec3 m1 = Vec3::Zero(), m2 = Vec3::Zero();
      int n1 = 0, n2 = 0;
      for (int i = 0; i < n; ++i) {
        zone[i] = (points_[i] - c1).squaredNorm() <= (points_[i] - c2).squaredNorm() ? 0 : 1;
        if (zone[i] == 0) {
          m1 += points_[i];
          ++n1;
        } else {
          m2 += points_[i];
          ++n2;
        }
      }
      if (n1 == 0 || n2 == 0) return -1;
      c1 = m1 / n1;
      c2 = m2 / n2;
    }
    Vec3 nz[2];
    for (int z = 0; z < 2; ++z) {
      Vec3 ref = Vec3::Zero();
      for (int i = 0; i < n; ++i)
        if (zone[i] == z && forces_[i].norm() > ref.norm()) ref = forces_[i];
      Vec3 sum = Vec3::Zero();
      for (int i = 0; i < n; ++i)
        if (zone[i] == z) sum += forces_[i].dot(ref) >= 0 ? forces_[i] : Vec3(-forces_[i]);
      nz[z] = sum.normalized();
    }
    return std::acos(std::min(1.0, std::abs(nz[0].dot(nz[1]))));
  }

 private:
  // What pass 1 of compute() finds for a listed pair: one record per feature pair within
  // h (touching), or one record saying the pair is in reach but not touching.
  struct Hit {
    std::size_t pair;
    bool touching;
    Vec3 n1;  // T1's unnormalised normal, for a feature pair at distance 0
    shell::TrianglePair tp;
  };
  // Pass 1 for listed pair i: reads positions and the boxes of this step, writes only `out`.
  void screen(const std::vector<Vec3>& x, std::size_t i, std::vector<Hit>& out) const {
    const Candidate& c = pairs_[i];
    // boxes grown by h/2 that do not overlap: more than h apart
    if ((box_lo_[c.t1].array() > box_hi_[c.t2].array()).any() ||
        (box_lo_[c.t2].array() > box_hi_[c.t1].array()).any())
      return;
    const auto& T = mesh_->mesh.tri;
    std::array<Vec3, 3> A, B;
    for (int k = 0; k < 3; ++k) {
      A[k] = x[base_ + T[c.t1][k]];
      B[k] = x[base_ + T[c.t2][k]];
    }
    const Vec3 n1 = (A[1] - A[0]).cross(A[2] - A[0]), n2 = (B[1] - B[0]).cross(B[2] - B[0]);
    // near neighbours touch only across a ridge (or never)
    if (c.near && (near_never_ || n1.dot(n2) > 0)) return;
    if (separated(A, B, n1, n2)) return;
    const std::size_t before = out.size();
    if (dense_all_) {
      shell::for_each_feature_pair(
          A, B,
          [&](const shell::TrianglePair& tp) {
            if (tp.dist < h_) out.push_back(Hit{i, true, n1, tp});
          },
          masks_[c.t1], masks_[c.t2]);
    } else {
      const shell::TrianglePair tp = shell::triangle_distance(A, B);
      if (tp.dist < h_) out.push_back(Hit{i, true, n1, tp});
    }
    if (out.size() == before) out.push_back(Hit{i, false, Vec3::Zero(), shell::TrianglePair{}});
  }

  struct Candidate {
    int t1, t2;
    bool near;
    double dref;             // smallest reference distance of their vertices
    FrictionState friction;  // history of the stick spring (frictional contacts)
  };

  // Separating-axis test with margin h on the face normals and the in-plane edge
  // normals of both triangles: most pairs of the list (neighbours lying side by side)
  // are rejected here, before the 15 closest-point problems of the dense phase.
  bool separated(const std::array<Vec3, 3>& A, const std::array<Vec3, 3>& B, const Vec3& n1,
                 const Vec3& n2) const {
    auto apart = [&](const Vec3& axis) {
      const double len = axis.norm();
      if (len == 0) return false;
      double a0 = 1e300, a1 = -1e300, b0 = 1e300, b1 = -1e300;
      for (int k = 0; k < 3; ++k) {
        const double pa = A[k].dot(axis), pb = B[k].dot(axis);
        a0 = std::min(a0, pa);
        a1 = std::max(a1, pa);
        b0 = std::min(b0, pb);
        b1 = std::max(b1, pb);
      }
      return a0 > b1 + h_ * len || b0 > a1 + h_ * len;
    };
    if (apart(n1) || apart(n2)) return true;
    for (int k = 0; k < 3; ++k) {
      if (apart((A[(k + 1) % 3] - A[k]).cross(n1))) return true;
      if (apart((B[(k + 1) % 3] - B[k]).cross(n2))) return true;
    }
    return false;
  }

  void rebuild(const std::vector<Vec3>& x) {
    ++rebuilds_;
    need_build_ = false;
    const auto& T = mesh_->mesh.tri;
    const auto& X = mesh_->mesh.x;  // reference positions
    const int nt = mesh_->n_real_tris;
    const double pad = 0.5 * (h_ + skin_);
    std::vector<Vec3> lo(nt), hi(nt);
    double extent = h_;
    for (int t = 0; t < nt; ++t) {
      lo[t] = hi[t] = x[base_ + T[t][0]];
      for (int k = 1; k < 3; ++k) {
        lo[t] = lo[t].cwiseMin(x[base_ + T[t][k]]);
        hi[t] = hi[t].cwiseMax(x[base_ + T[t][k]]);
      }
      lo[t].array() -= pad;
      hi[t].array() += pad;
      extent = std::max(extent, (hi[t] - lo[t]).maxCoeff());
    }
    const double inv = 1.0 / extent;
    // clamped before the cast (a node flung far, a NaN the guard has yet to see)
    auto cell = [&](double v) {
      const double c = std::floor(v * inv);
      return c == c ? static_cast<long>(std::clamp(c, -1e15, 1e15)) : 0L;
    };
    auto key = [](long i, long j, long k) {
      return (static_cast<std::uint64_t>(i & 0x1fffff) << 42) |
             (static_cast<std::uint64_t>(j & 0x1fffff) << 21) |
             static_cast<std::uint64_t>(k & 0x1fffff);
    };
    std::unordered_map<std::uint64_t, std::vector<int>> voxels;
    for (int t = 0; t < nt; ++t)
      for (long i = cell(lo[t].x()); i <= cell(hi[t].x()); ++i)
        for (long j = cell(lo[t].y()); j <= cell(hi[t].y()); ++j)
          for (long k = cell(lo[t].z()); k <= cell(hi[t].z()); ++k)
            voxels[key(i, j, k)].push_back(t);
    // each overlapping pair is taken in one voxel only: the one holding the lower
    // corner of the intersection of the two boxes (no duplicates)
    std::vector<std::uint64_t> found;
    for (auto& [vk, list] : voxels)
      for (std::size_t a = 0; a < list.size(); ++a)
        for (std::size_t b = a + 1; b < list.size(); ++b) {
          const int t1 = std::min(list[a], list[b]), t2 = std::max(list[a], list[b]);
          if ((lo[t1].array() > hi[t2].array()).any() || (lo[t2].array() > hi[t1].array()).any())
            continue;
          const Vec3 corner = lo[t1].cwiseMax(lo[t2]);
          if (key(cell(corner.x()), cell(corner.y()), cell(corner.z())) != vk) continue;
          found.push_back((static_cast<std::uint64_t>(t1) << 32) | static_cast<std::uint32_t>(t2));
        }
    // a fixed order, so that forces sum the same way whenever the list was built (restarts
    // are bit-identical)
    std::sort(found.begin(), found.end());
    // the old list (or the pairs a checkpoint restored) hands its friction history to the
    // pairs that stay listed (src/pair_history.hpp)
    std::vector<Candidate> old;
    old.swap(restored_.empty() ? pairs_ : restored_);
    pairs_.clear();
    for (std::uint64_t id : found) {
      const int t1 = static_cast<int>(id >> 32), t2 = static_cast<int>(id & 0xffffffffu);
      double dref = 1e300;
      for (int a : T[t1])
        for (int b : T[t2]) dref = std::min(dref, (X[a] - X[b]).norm());
      if (dref == 0) continue;  // neighbours never collide
      pairs_.push_back(Candidate{t1, t2, dref <= near_, dref, FrictionState{}});
    }
    carry_pair_history(
        old, pairs_, [](const Candidate& c) { return id_pair_key(c.t1, c.t2); },
        [](const Candidate& c) { return c.friction.active; },
        [](const Candidate& from, Candidate& to) { to.friction = from.friction; });
  }

  std::string mesh_name_;
  double h_;
  long every_;
  ContactLaw friction_;
  std::shared_ptr<const shell::GhostedMesh> mesh_;
  int base_ = 0;
  double mean_edge_ = 0, k_ = 0, skin_ = 0, near_ = 0, far_ = 0, m_min_ = 1;
  bool near_never_ = false;
  bool dense_all_ = false;
  std::vector<shell::FeatureMask> masks_;
  std::vector<Candidate> restored_;  // the friction history a checkpoint holds
  std::vector<Candidate> pairs_;
  std::vector<Vec3> box_lo_, box_hi_;
  int handle_ = -1;  // this list's request to the neighbour service
  bool need_build_ = true;
  long rebuilds_ = 0;
  int contacts_ = 0, far_contacts_ = 0;
  double force_sum_ = 0;
  std::vector<double> face_flag_;
  std::vector<Vec3> points_, forces_;
  std::vector<Hit> hits_;
  std::vector<std::vector<Hit>> hit_parts_;
};

}  // namespace slender

SLENDER_REGISTER_STYLE(slender::PairStyle, "contact/shell", slender::ShellContactPair)
