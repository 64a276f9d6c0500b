// Nonlinear Koiter (Kirchhoff–Love) shell on a Loop subdivision surface with
// in-plane growth (docs/models.md §6.1–§6.8).
//
// Energy (§6.3): Phi = sum_p w_p sqrt(abar) 1/2 [C_m alpha^T H alpha + C_b beta^T H beta],
// alpha = 1/2 (P^T a P - abar), beta = kbar - P^T kappa P, P = Gtilde^-1 (§6.2).
// Forces are the exact gradient (§6.4), written with the pulled-back resultants
// Ntilde = P N P^T and Mtilde = P M P^T, which is the Voigt transform T of §6.4
// applied in tensor form:
//   dPhi = sum_ab Ntilde_ab a_b . da_a  -  Mtilde : dkappa,
//   dkappa_ab = da_{a,b} . a3 + a_{a,b} . da3,  da3 = (1/J)(1 - a3 a3^T)(da1 x a2 + a1 x da2).
// Quadrature (§6.8): 3 points (1/6,1/6), (2/3,1/6), (1/6,2/3), weights 1/6, exact for
// quadratics and never on a vertex (irregular elements need no limit at a node);
// quadrature = 1 uses the centroid. Lumped mass by row sums (§6.4).
#include <Eigen/Dense>
#include <array>
#include <cassert>
#include <cmath>
#include <random>
#include <unsupported/Eigen/AutoDiff>

#include "context.hpp"
#include "hessian.hpp"
#include "registry.hpp"
#include "shell/loop_patch.hpp"

namespace slender {

namespace {
using Mat2 = Eigen::Matrix2d;
using Mat3 = Eigen::Matrix3d;

struct GaussPoint {
  int row0 = 0, nrows = 0;  // stencil rows
  int element = 0;
  double w = 0;   // quadrature weight times sqrt(abar)
  double wq = 0;  // quadrature weight alone
  Mat2 abar, kbar;
  Mat3 H;                // H_V of §6.3 from abar^{-1}
  Vec3 X, a1bar, a2bar;  // reference limit point and tangents
  Mat2 P = Mat2::Identity();
  double detG = 1.0;
};
}  // namespace

class KoiterShell : public ShellStyle {
  // the ghost rule as a value, not the deck's string: it is tested every step
  // (kClampedEdge: the second-order clamp of clamped_edges; kClamped: `boundary =
  // "clamped"`, which holds the first row too; kSymmetry, kDiaphragm: symmetry_edges and
  // diaphragm_edges, reflected like kClampedEdge with their own reflection)
  enum class Boundary {
    kCombined,
    kMirror,
    kFreeGhosts,
    kClamped,
    kSimplySupported,
    kClampedEdge,
    kSymmetry,
    kDiaphragm
  };

 public:
  static ParamSpec spec(const std::string& name) {
    ParamSpec s("shell", name,
                "nonlinear Koiter shell on a Loop subdivision surface with in-plane growth "
                "(docs/models.md §6)");
    s.string("mesh", "surface created by sim:mesh").required();
    s.real("thickness", "shell thickness h").required().positive();
    s.real("young", "Young's modulus Y").def(1e4).positive();
    s.real("poisson", "Poisson ratio nu").def(0.3).min(-0.99).max(0.499);
    s.real("density", "mass density rho (mass per volume)").def(1.0).positive();
    s.string("boundary",
             "ghost-node rule at free edges (§6.7): combined (free ghosts pulled towards the "
             "mirror, (5.35)), mirror (u3 = u0 + u2 - u1), free_ghosts (Green), clamped, "
             "simply_supported")
        .def(std::string("combined"))
        .choices({"combined", "mirror", "free_ghosts", "clamped", "simply_supported"});
    s.string("ghost_partner",
             "simply supported edges: the interior node p whose displacement a ghost negates "
             "(u_g = -u_p): reflection = the node nearest to the ghost's mirror image across "
             "the edge (2nd order); point = the triangle's third node as printed in docs/models.md "
             "§6.7 (1st order). Clamped edges always fix boundary, ghosts and first row (§6.7)")
        .def(std::string("reflection"))
        .choices({"reflection", "point"});
    s.add("clamped_edges", ParamType::StringList,
          "node groups whose boundary edges (both ends in the group) are clamped at "
          "second order (§6.7): their boundary nodes are held and each ghost mirrors "
          "its partner's displacement, the normal part even and the in-plane part odd "
          "(u_g = (2 n n^T - 1) u_p); the other edges follow `boundary`")
        .def(std::vector<std::string>{});
    s.add("supported_edges", ParamType::StringList,
          "node groups whose boundary edges are simply supported (u_g = -u_p, boundary "
          "nodes held); the other edges follow `boundary`")
        .def(std::vector<std::string>{});
    s.add("symmetry_edges", ParamType::StringList,
          "node groups whose boundary edges lie on a symmetry plane normal to x, y or z "
          "(the edge's outward direction): the displacement normal to the plane is held on "
          "the edge and odd across it, the others even (u_g = (1 - 2 nu nu^T) u_p), so the "
          "surface meets the plane at a right angle (§6.7)")
        .def(std::vector<std::string>{});
    s.add("diaphragm_edges", ParamType::StringList,
          "node groups whose boundary edges rest on a rigid diaphragm normal to x, y or z "
          "(the edge's outward direction): the displacement in the diaphragm's plane is "
          "held on the edge and odd across it, the one normal to it free and even (u_g = "
          "(2 nu nu^T - 1) u_p): no bending moment, no force along the edge's outward "
          "direction at nu = 0 (§6.7)")
        .def(std::vector<std::string>{});
    s.real("k_ghost", "spring of the combined method (default Y h)").positive();
    s.real("ghost_lambda", "dead zone of the ghost spring, fraction of the mean edge")
        .def(0.1)
        .nonnegative();
    s.boolean("ghost_reaction",
              "the ghost spring also acts back on the three nodes that define the mirror "
              "position, so it derives from an energy (minimisers converge); false = on the "
              "ghost only, as in the thesis")
        .def(true);
    s.string("growth", "id of a growth style (sim:growth); none: no growth");
    s.boolean("growth_area_factor",
              "integrate over the grown area (det G); false = the thesis (§6.2)")
        .def(false);
    s.integer("quadrature", "Gauss points per element: 3 or 1").def(3.0).min(1).max(3);
    s.vector("load", "uniform load q per reference area (2.32): f_I = q * integral of N_I")
        .def(std::vector<double>{0, 0, 0})
        .length(3, 3);
    s.vector("line_load",
             "dead load per reference length on the boundary edges of line_load_edges: "
             "f_I = q * integral of N_I along each edge's limit curve (consistent nodal loads)")
        .length(3, 3);
    s.add("line_load_edges", ParamType::StringList,
          "node groups whose boundary edges (both ends in the group) carry line_load")
        .def(std::vector<std::string>{});
    s.vector("line_moment",
             "moment per reference length on the boundary edges of line_moment_edges, as a "
             "vector (its direction the axis, fixed in space): the work of |m| times the "
             "rotation of the material fibre that crosses each edge, about that axis, followed "
             "through full turns (§6.4), so an end moment can roll a strip up")
        .length(3, 3);
    s.add("line_moment_edges", ParamType::StringList,
          "node groups whose boundary edges (both ends in the group) carry line_moment")
        .def(std::vector<std::string>{});
    s.real("pressure",
           "follower pressure p on the side the normal a1 x a2 points away from (outwards on "
           "the generated sphere): f_I = p * integral of N_I n over the current surface "
           "(§6.4); its potential -p V, V the volume enclosed (closed surfaces)")
        .def(0.0);
    s.output("stretch", "stretching energy of the last force evaluation");
    s.output("bend", "bending energy of the last force evaluation (ghost springs not included)");
    s.output("energy", "stretching plus bending energy");
    s.output("Eb_hat",
             "mean bending density: integral of U_b over the current area, divided by that area");
    s.output("area", "current area of the surface");
    s.output("volume",
             "volume enclosed by the current limit surface, 1/3 integral of x . n (closed "
             "surfaces; computed where pressure is set)");
    s.output("load_factor",
             "lambda of a continuation: load, line_load, line_moment and pressure scale with it");
    s.output("omega",
             "highest angular frequency estimated by power iteration, for the stable step");
    s.output("elements", "number of elements (real triangles)");
    s.output("nodes", "number of real (non-ghost) control nodes");
    return s;
  }

  KoiterShell(Context& sim, const ParamValues& p)
      : mesh_name_(p.str("mesh")),
        h_(p.real("thickness")),
        Y_(p.real("young")),
        nu_(p.real("poisson")),
        rho_(p.real("density")),
        boundary_(boundary_rule(p.str("boundary"))),
        k_ghost_(p.has("k_ghost") ? p.real("k_ghost") : p.real("young") * p.real("thickness")),
        lambda_(p.real("ghost_lambda")),
        reflection_(p.str("ghost_partner") == "reflection"),
        ghost_reaction_(p.boolean("ghost_reaction")),
        growth_id_(p.has("growth") ? p.str("growth") : ""),
        area_factor_(p.boolean("growth_area_factor")),
        nquad_(static_cast<int>(p.integer("quadrature"))),
        load_(p.vec3("load")),
        pressure_(p.real("pressure")) {
    if (nquad_ == 2) throw InputError("shell 'koiter': quadrature must be 1 or 3");
    if (!sim.topology().find_surface(mesh_name_))
      throw InputError("shell 'koiter': no mesh named '" + mesh_name_ +
                       "' (create it with sim:mesh)");
    if (!growth_id_.empty()) sim.growth(growth_id_);  // fails early on an unknown id
    Cm_ = Y_ * h_ / (1 - nu_ * nu_);
    Cb_ = Y_ * h_ * h_ * h_ / (12 * (1 - nu_ * nu_));
    precompute(sim);
    assign_edge_rules(sim, p.strings("supported_edges"), p.strings("clamped_edges"),
                      p.strings("symmetry_edges"), p.strings("diaphragm_edges"));
    if (p.has("line_load") != !p.strings("line_load_edges").empty())
      throw InputError(
          "shell 'koiter': line_load and line_load_edges go together (the load per length, "
          "and the node groups whose boundary edges carry it)");
    if (p.has("line_load")) {
      line_load_ = p.vec3("line_load");
      line_weights_ = edge_integrals(sim, p.strings("line_load_edges"));
    }
    if (p.has("line_moment") != !p.strings("line_moment_edges").empty())
      throw InputError(
          "shell 'koiter': line_moment and line_moment_edges go together (the moment per "
          "length as a vector, and the node groups whose boundary edges carry it)");
    if (p.has("line_moment")) {
      const Vec3 m = p.vec3("line_moment");
      if (!(m.norm() > 0))
        throw InputError("shell 'koiter': line_moment must not be the zero vector");
      moment_ = m.norm();
      moment_points_ = edge_fibres(sim, p.strings("line_moment_edges"), m / m.norm());
    }
  }

  void setup(Context& sim) override {
    if (!growth_id_.empty()) growth_ = &sim.growth(growth_id_);
    if (!constraints_done_) {
      apply_constraints(sim);
      constraints_done_ = true;
    }
    update_growth(sim);
    if (omega_ <= 0) omega_ = estimate_omega(sim);
  }

  void compute(Context& sim) override {
    if (!growth_id_.empty() && !growth_) growth_ = &sim.growth(growth_id_);
    update_growth(sim);
    auto& x = sim.nodes().x;
    place_ghosts(x);
    double es = 0, eb = 0;
    accumulate(x, sim.nodes().f, &es, &eb, true, &sim);
    double ext = 0;
    if (load_.squaredNorm() > 0) {
      // consistent nodal loads, Phi_ext = -q . sum_I (integral N_I) u_I
      const auto& g = mesh();
      const Vec3 q = load_factor_ * load_;
      for (int i = 0; i < g.mesh.n_nodes(); ++i) {
        const double A = lumped_[i] / (rho_ * h_);
        sim.nodes().f[base_ + i] += A * q;
        ext -= A * q.dot(x[base_ + i] - g.mesh.x[i]);
      }
      sim.add_energy("external", ext);
    }
    if (!line_weights_.empty()) {
      // on the control nodes of the edges' limit curves, ghosts included: their share
      // goes to the real nodes with the ghost rule below, as the element forces do
      const auto& g = mesh();
      const Vec3 q = load_factor_ * line_load_;
      double e = 0;
      for (auto [i, w] : line_weights_) {
        sim.nodes().f[base_ + i] += w * q;
        e -= w * q.dot(x[base_ + i] - g.mesh.x[i]);
      }
      sim.add_energy("external", e);
    }
    if (!moment_points_.empty()) add_moment(x, sim.nodes().f, sim);
    if (pressure_ != 0) add_pressure(x, sim.nodes().f, sim);
    map_ghost_forces(x, sim.nodes().f);
    stretch_ = es;
    bend_ = eb;
    sim.add_energy("stretch", es);
    sim.add_energy("bend", eb + ghost_energy_);
  }

  // The exact Hessian (docs/models.md §9.7): the Jacobian of each Gauss point's nodal forces
  // of accumulate() by forward automatic differentiation over its stencil's coordinates,
  // then carried through the ghost rules as the forces are (a prescribed ghost is a linear
  // combination of real nodes: H -> T^T H T). The dead loads are linear: nothing; the
  // pressure follows the surface (below).
  bool add_hessian(Context& sim, Hessian& H) const override {
    // the ghost springs of the combined method derive from an energy only when they act back
    // on the mirror's nodes (ghost_reaction); on the ghost alone their Jacobian is not
    // symmetric
    for (Boundary r : rule_)
      if (r == Boundary::kCombined && !ghost_reaction_) return false;
    using Deriv = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 96, 1>;
    using AD = Eigen::AutoDiffScalar<Deriv>;
    using V = Eigen::Matrix<AD, 3, 1>;
    const auto& x = sim.nodes().x;
    const auto& g = mesh();
    // the real nodes (and weights) that place each node: a prescribed ghost expands
    // (x_g = sum W x_j + const, so its block is W_i^T B W_j)
    const Mat3 I = Mat3::Identity();
    std::vector<std::vector<std::pair<int, Mat3>>> via(static_cast<size_t>(g.mesh.n_nodes()));
    for (int i = 0; i < g.mesh.n_nodes(); ++i) via[i] = {{base_ + i, I}};
    for (std::size_t k = 0; k < g.ghosts.size(); ++k) {
      const auto& gh = g.ghosts[k];
      if (rule_[k] == Boundary::kMirror)
        via[gh.node] = {{base_ + gh.b0, I}, {base_ + gh.b2, I}, {base_ + gh.interior, -I}};
      else if (rule_[k] == Boundary::kSimplySupported)
        via[gh.node] = {{base_ + partner_[k], -I}};
      else if (reflected(rule_[k]))
        via[gh.node] = {{base_ + partner_[k], reflect_[k]}};
    }
    auto dot = [](const V& a, const V& b) { return AD(a.dot(b)); };
    auto cross = [](const V& a, const V& b) {
      V c;
      c << a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0];
      return c;
    };
    // P^T A P and P A P^T of a symmetric 2x2 AD matrix (a00, a01, a11)
    auto congruent = [](const Mat2& P, const AD A[3], bool transpose_first, AD out[3]) {
      AD full[2][2] = {{A[0], A[1]}, {A[1], A[2]}};
      auto Pt = [&](int i, int j) { return transpose_first ? P(j, i) : P(i, j); };
      for (int idx = 0; idx < 3; ++idx) {
        const int i = idx == 2 ? 1 : 0, j = idx == 0 ? 0 : 1;
        AD sum = AD(0.0);
        for (int k = 0; k < 2; ++k)
          for (int l = 0; l < 2; ++l) sum += Pt(i, k) * full[k][l] * Pt(j, l);
        out[idx] = sum;
      }
    };
    for (const GaussPoint& gp : gauss_) {
      const shell::ShapeRow* R = &rows_[gp.row0];
      const int nr = gp.nrows, nd = 3 * nr;
      if (nd > 96)
        throw InputError("shell 'koiter': a vertex of valence above 26 has no Hessian here");
      V a1 = V::Constant(AD(0.0)), a2 = a1, a11 = a1, a12 = a1, a22 = a1;
      for (int r = 0; r < nr; ++r) {
        V p;
        for (int k = 0; k < 3; ++k) p[k] = AD(x[R[r].node][k], nd, 3 * r + k);
        a1 += p * R[r].Nv;
        a2 += p * R[r].Nw;
        a11 += p * R[r].Nvv;
        a12 += p * R[r].Nvw;
        a22 += p * R[r].Nww;
      }
      const V n = cross(a1, a2);
      const AD J = sqrt(dot(n, n));
      const V a3 = n / J;
      const AD a[3] = {dot(a1, a1), dot(a1, a2), dot(a2, a2)};
      const AD k[3] = {dot(a11, a3), dot(a12, a3), dot(a22, a3)};
      AD ah[3], kh[3];
      congruent(gp.P, a, true, ah);
      congruent(gp.P, k, true, kh);
      const AD al[3] = {0.5 * (ah[0] - gp.abar(0, 0)), 0.5 * (ah[1] - gp.abar(0, 1)),
                        0.5 * (ah[2] - gp.abar(1, 1))};
      const AD be[3] = {gp.kbar(0, 0) - kh[0], gp.kbar(0, 1) - kh[1], gp.kbar(1, 1) - kh[2]};
      const AD alV[3] = {al[0], al[2], 2.0 * al[1]}, beV[3] = {be[0], be[2], 2.0 * be[1]};
      AD HalV[3], HbeV[3];
      for (int r = 0; r < 3; ++r) {
        HalV[r] = gp.H(r, 0) * alV[0] + gp.H(r, 1) * alV[1] + gp.H(r, 2) * alV[2];
        HbeV[r] = gp.H(r, 0) * beV[0] + gp.H(r, 1) * beV[1] + gp.H(r, 2) * beV[2];
      }
      const double w = area_factor_ ? gp.w * gp.detG : gp.w;
      const AD Nm[3] = {Cm_ * HalV[0], Cm_ * HalV[2], Cm_ * HalV[1]};
      const AD Mm[3] = {Cb_ * HbeV[0], Cb_ * HbeV[2], Cb_ * HbeV[1]};
      AD Nt[3], Mt[3];
      congruent(gp.P, Nm, false, Nt);
      congruent(gp.P, Mm, false, Mt);
      const V m1 = a1 * Nt[0] + a2 * Nt[1];
      const V m2 = a1 * Nt[1] + a2 * Nt[2];
      V c = a11 * Mt[0] + a12 * (2.0 * Mt[1]) + a22 * Mt[2];
      c -= a3 * dot(c, a3);
      const V b1 = cross(a2, c) / J, b2 = cross(c, a1) / J;
      const V g1 = (m1 - b1) * w, g2 = (m2 - b2) * w, g3 = a3 * (-w);
      for (int r = 0; r < nr; ++r) {
        const shell::ShapeRow& sr = R[r];
        const V fr = -(g1 * sr.Nv + g2 * sr.Nw +
                       g3 * (Mt[0] * sr.Nvv + 2.0 * Mt[1] * sr.Nvw + Mt[2] * sr.Nww));
        for (int col = 0; col < nr; ++col) {
          Eigen::Matrix3d b;
          for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
              const auto& d = fr[i].derivatives();
              b(i, j) = d.size() > 3 * col + j ? -d[3 * col + j] : 0.0;
            }
          for (auto [ri, wr] : via[R[r].node - base_])
            for (auto [ci, wc] : via[R[col].node - base_])
              H.add(ri, ci, Eigen::Matrix3d(wr.transpose() * b * wc));
        }
      }
    }
    if (!moment_points_.empty()) {
      // -|m| w d_I d_J times the Hessian of the angle in the (u, v) plane
      const double m = load_factor_ * moment_;
      for (const MomentPoint& mp : moment_points_) {
        Vec3 t = Vec3::Zero();
        for (auto [i, d] : mp.rows) t += d * x[base_ + i];
        const double u = t.dot(mp.e1), v = t.dot(mp.e2), r4 = std::pow(u * u + v * v, 2);
        const Mat3 B =
            (2 * u * v / r4) * (mp.e1 * mp.e1.transpose() - mp.e2 * mp.e2.transpose()) +
            ((v * v - u * u) / r4) * (mp.e1 * mp.e2.transpose() + mp.e2 * mp.e1.transpose());
        for (auto [i, di] : mp.rows)
          for (auto [j, dj] : mp.rows) {
            const Mat3 b = (-m * mp.w * di * dj) * B;
            for (auto [ri, wr] : via[i])
              for (auto [ci, wc] : via[j]) H.add(ri, ci, Mat3(wr.transpose() * b * wc));
          }
      }
    }
    const double p = load_factor_ * pressure_;
    if (p != 0) {
      auto skew = [](const Vec3& a) {
        Mat3 m;
        m << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
        return m;
      };
      const bool closed = g.ghosts.empty();
      for (const GaussPoint& gp : gauss_) {
        const shell::ShapeRow* R = &rows_[gp.row0];
        Vec3 X = Vec3::Zero(), a1 = X, a2 = X;
        for (int r = 0; r < gp.nrows; ++r) {
          X += R[r].N * x[R[r].node];
          a1 += R[r].Nv * x[R[r].node];
          a2 += R[r].Nw * x[R[r].node];
        }
        const Mat3 A1 = skew(a1), A2 = skew(a2), SX = skew(X);
        for (int r = 0; r < gp.nrows; ++r)
          for (int col = 0; col < gp.nrows; ++col) {
            const shell::ShapeRow &a = R[r], &c = R[col];
            Mat3 b;
            if (closed) {
              // -p/3 times the second derivative of x . (a1 x a2), a trilinear form
              b = -(p / 3.0) * gp.wq *
                  (A2 * (a.Nv * c.N - a.N * c.Nv) + A1 * (a.N * c.Nw - a.Nw * c.N) +
                   SX * (a.Nw * c.Nv - a.Nv * c.Nw));
            } else {
              // the follower load: dF_I/dx_J = p wq N_I (Nw_J [a1]x - Nv_J [a2]x); its
              // symmetric part (the skew part, boundary terms, has no place in a
              // symmetric solver)
              const Mat3 Brc = p * gp.wq * a.N * (c.Nw * A1 - c.Nv * A2);
              const Mat3 Bcr = p * gp.wq * c.N * (a.Nw * A1 - a.Nv * A2);
              b = -0.5 * (Brc + Bcr.transpose());
            }
            for (auto [ri, wr] : via[a.node - base_])
              for (auto [ci, wc] : via[c.node - base_])
                H.add(ri, ci, Mat3(wr.transpose() * b * wc));
          }
      }
    }
    // the ghost springs (5.35): 1/2 k (|d| - dead)^2 of d = x_g - (x_b0 + x_b2 - x_i), a
    // spring of rest length `dead` on the ghost and its mirror position (docs/models.md §9.7)
    const double dead = lambda_ * mean_edge_;
    for (std::size_t k = 0; k < g.ghosts.size(); ++k) {
      if (rule_[k] != Boundary::kCombined) continue;
      const auto& gh = g.ghosts[k];
      const Vec3 d =
          x[base_ + gh.node] - (x[base_ + gh.b0] + x[base_ + gh.b2] - x[base_ + gh.interior]);
      const double len = d.norm();
      if (len <= dead) continue;
      const Vec3 n = d / len;
      const Mat3 nn = n * n.transpose();
      const Mat3 h = k_ghost_ * (nn + (1.0 - dead / len) * (I - nn));
      const std::array<std::pair<int, double>, 4> w{{{base_ + gh.node, 1.0},
                                                     {base_ + gh.b0, -1.0},
                                                     {base_ + gh.b2, -1.0},
                                                     {base_ + gh.interior, 1.0}}};
      for (auto [i, wi] : w)
        for (auto [j, wj] : w) H.add(i, j, Mat3(wi * wj * h));
    }
    return true;
  }
  bool set_continuation_parameter(double lambda) override {
    if (load_.squaredNorm() == 0 && line_weights_.empty() && moment_points_.empty() &&
        pressure_ == 0)
      return false;
    load_factor_ = lambda;
    return true;
  }

  double max_frequency(const Context&) const override { return omega_; }
  // The frequency estimate depends on the configuration and growth of the first run; a
  // continued run keeps it so that its automatic step is the one it would have taken.
  void save_state(StateMap& st) const override {
    st["omega"] = {omega_};
    st["load_factor"] = {load_factor_};
    if (!moment_points_.empty()) {
      auto& phi = st["moment_angles"];
      for (const MomentPoint& mp : moment_points_) phi.push_back(mp.phi);
    }
  }
  void load_state(const StateMap& st) override {
    if (auto it = st.find("omega"); it != st.end() && !it->second.empty() && it->second[0] > 0)
      omega_ = it->second[0];
    if (auto it = st.find("load_factor"); it != st.end() && !it->second.empty())
      load_factor_ = it->second[0];
    if (auto it = st.find("moment_angles");
        it != st.end() && it->second.size() == moment_points_.size())
      for (std::size_t k = 0; k < moment_points_.size(); ++k) moment_points_[k].phi = it->second[k];
  }

  double value(const std::string& key) const override {
    if (key == "stretch") return stretch_;
    if (key == "bend") return bend_;
    if (key == "energy") return stretch_ + bend_;
    if (key == "Eb_hat") return area_ > 0 ? ub_integral_ / area_ : 0.0;
    if (key == "area") return area_;
    if (key == "volume") return volume_;
    if (key == "load_factor") return load_factor_;
    if (key == "omega") return omega_;
    if (key == "elements") return n_elem_;
    if (key == "nodes") return mesh().n_real_nodes;
    return ShellStyle::value(key);
  }

  // per-face densities U_b, U_s (§6.3) of the last force evaluation, for dumps
  const std::vector<double>* face_values(const std::string& key) const override {
    if (key == "Ub") return &face_ub_;
    if (key == "Us") return &face_us_;
    return nullptr;
  }

 private:
  const shell::GhostedMesh& mesh() const { return *mesh_; }

  void precompute(Context& sim) {
    const Surface* surface = sim.topology().find_surface(mesh_name_);
    mesh_ = surface->mesh;
    base_ = surface->first_node;
    const auto& g = mesh();
    n_elem_ = g.n_real_tris;
    std::vector<std::array<double, 3>> q;  // (v, w, weight)
    if (nquad_ == 3)
      q = {{1.0 / 6, 1.0 / 6, 1.0 / 6}, {2.0 / 3, 1.0 / 6, 1.0 / 6}, {1.0 / 6, 2.0 / 3, 1.0 / 6}};
    else
      q = {{1.0 / 3, 1.0 / 3, 0.5}};
    std::vector<double> lumped(g.mesh.n_nodes(), 0.0);
    const shell::EdgeStats edges = shell::reference_edges(g);
    lmin_ = edges.min;
    mean_edge_ = edges.mean;
    for (int t = 0; t < n_elem_; ++t) {
      const shell::Tri c = shell::oriented_element(g, t);
      for (auto& [v, w, wt] : q) {
        shell::Stencil st = shell::evaluate(g, c, v, w);
        GaussPoint gp;
        gp.element = t;
        gp.row0 = static_cast<int>(rows_.size());
        gp.nrows = static_cast<int>(st.size());
        Vec3 X = Vec3::Zero(), a1 = X, a2 = X, a11 = X, a12 = X, a22 = X;
        for (auto& r : st) {
          const Vec3& p = g.mesh.x[r.node];
          X += r.N * p;
          a1 += r.Nv * p;
          a2 += r.Nw * p;
          a11 += r.Nvv * p;
          a12 += r.Nvw * p;
          a22 += r.Nww * p;
          rows_.push_back(r);
          rows_.back().node += base_;
        }
        const Vec3 n = a1.cross(a2);
        const double J = n.norm();
        if (!(J > 0)) throw InputError("shell 'koiter': degenerate element " + std::to_string(t));
        const Vec3 a3 = n / J;
        gp.X = X;
        gp.a1bar = a1;
        gp.a2bar = a2;
        gp.abar << a1.dot(a1), a1.dot(a2), a1.dot(a2), a2.dot(a2);
        gp.kbar << a11.dot(a3), a12.dot(a3), a12.dot(a3), a22.dot(a3);
        const Mat2 ai = gp.abar.inverse();
        const double i11 = ai(0, 0), i22 = ai(1, 1), i12 = ai(0, 1);
        gp.H << i11 * i11, nu_ * i11 * i22 + (1 - nu_) * i12 * i12, i11 * i12,  //
            nu_ * i11 * i22 + (1 - nu_) * i12 * i12, i22 * i22, i22 * i12,      //
            i11 * i12, i22 * i12, 0.5 * ((1 - nu_) * i11 * i22 + (1 + nu_) * i12 * i12);
        gp.w = wt * J;
        gp.wq = wt;
        for (auto& r : st) lumped[r.node] += rho_ * h_ * r.N * gp.w;
        gauss_.push_back(gp);
      }
    }
    // supported ghosts copy (the negative of) an interior partner
    partner_.clear();
    for (auto& gh : g.ghosts) {
      int best = gh.interior;
      if (reflection_) {
        const Vec3 X0 = g.mesh.x[gh.b0], e = (g.mesh.x[gh.b2] - X0).normalized();
        Vec3 r = g.mesh.x[gh.node] - X0;
        r -= r.dot(e) * e;
        const Vec3 image = g.mesh.x[gh.node] - 2 * r;
        double d = 1e300;
        for (int b : {gh.b0, gh.b2})
          for (int k : g.rings.ring[b])
            if (k < g.n_real_nodes && (g.mesh.x[k] - image).norm() < d) {
              d = (g.mesh.x[k] - image).norm();
              best = k;
            }
      }
      partner_.push_back(best);
    }
    face_ub_.assign(n_elem_, 0.0);
    face_us_.assign(n_elem_, 0.0);
    lumped_ = lumped;
  }

  // the ghost of this rule is placed by the real nodes (or held), not a free node
  static bool kinematic(Boundary r) {
    return r != Boundary::kCombined && r != Boundary::kFreeGhosts;
  }
  // the rule holds (components of) the edge's boundary nodes
  static bool holds_edge(Boundary r) {
    return r == Boundary::kSimplySupported || r == Boundary::kClamped || reflected(r);
  }
  // the ghost is its partner's displacement reflected by reflect_ (the per-edge rules)
  static bool reflected(Boundary r) {
    return r == Boundary::kClampedEdge || r == Boundary::kSymmetry || r == Boundary::kDiaphragm;
  }

  struct MomentPoint {
    double w = 0;                              // quadrature weight times the edge's length
    Vec3 e1, e2;                               // the plane of the angle (normal to the axis)
    std::vector<std::pair<int, double>> rows;  // (mesh node, d_I): t = sum d_I x_I
    double phi = 0;                            // the angle, continued through full turns
  };

  // The boundary edges (each has one ghost) whose two end nodes lie in one of the groups.
  std::vector<std::size_t> edges_in(Context& sim, const std::string& key,
                                    const std::vector<std::string>& groups) const {
    const auto& g = mesh();
    std::vector<std::size_t> out;
    for (const std::string& name : groups) {
      if (!sim.has_group(name))
        throw InputError("shell 'koiter': " + key + " names the group '" + name +
                         "', which does not exist (define it with sim:group before the shell)");
      std::vector<char> in(static_cast<size_t>(g.mesh.n_nodes()), 0);
      for (int i : sim.group(name))
        if (i >= base_ && i < base_ + g.n_real_nodes) in[static_cast<size_t>(i - base_)] = 1;
      const std::size_t before = out.size();
      for (std::size_t k = 0; k < g.ghosts.size(); ++k)
        if (in[static_cast<size_t>(g.ghosts[k].b0)] && in[static_cast<size_t>(g.ghosts[k].b2)])
          out.push_back(k);
      if (out.size() == before)
        throw InputError("shell 'koiter': " + key + " group '" + name +
                         "' holds no boundary edge of mesh '" + mesh_name_ +
                         "' (an edge counts when both its end nodes are in the group)");
    }
    return out;
  }

  // Calls point(ghost k, stencil, weight) at 4 Gauss–Legendre points along the limit curve of
  // each boundary edge of the groups (N is quartic along an edge); the weight is the rule's
  // weight times the edge's length as meshed.
  template <class Point>
  void for_edge_points(Context& sim, const char* key, const std::vector<std::string>& groups,
                       Point point) const {
    const auto& g = mesh();
    const double a = 0.5 - std::sqrt(3.0 / 7 + 2.0 / 7 * std::sqrt(6.0 / 5)) / 2;
    const double b = 0.5 - std::sqrt(3.0 / 7 - 2.0 / 7 * std::sqrt(6.0 / 5)) / 2;
    const double wa = (18 - std::sqrt(30.0)) / 72, wb = (18 + std::sqrt(30.0)) / 72;
    const std::array<std::pair<double, double>, 4> gl = {
        {{a, wa}, {b, wb}, {1 - b, wb}, {1 - a, wa}}};
    for (std::size_t k : edges_in(sim, key, groups)) {
      const auto& gh = g.ghosts[k];
      int t = -1;
      for (int e = 0; e < g.n_real_tris && t < 0; ++e) {
        const auto& tri = g.mesh.tri[e];
        const auto has = [&](int n) { return tri[0] == n || tri[1] == n || tri[2] == n; };
        if (has(gh.b0) && has(gh.b2) && has(gh.interior)) t = e;
      }
      if (t < 0) throw InputError("shell 'koiter': a boundary edge without its triangle");
      const shell::Tri c = shell::oriented_element(g, t);
      const double length = (g.mesh.x[gh.b2] - g.mesh.x[gh.b0]).norm();
      // (v, w) of a point with barycentric weights l[0..2] on corners c[0..2]
      for (auto [s, wq] : gl) {
        double l[3] = {0, 0, 0};
        for (int j = 0; j < 3; ++j) {
          if (c[j] == gh.b0) l[j] = 1 - s;
          if (c[j] == gh.b2) l[j] = s;
        }
        point(k, shell::evaluate(g, c, l[1], l[2]), wq * length);
      }
    }
  }

  // |E| times the integral of N_I ds along the limit curve of each listed boundary edge E,
  // per control node
  std::vector<std::pair<int, double>> edge_integrals(Context& sim,
                                                     const std::vector<std::string>& groups) {
    const auto& g = mesh();
    std::vector<double> sum(static_cast<size_t>(g.mesh.n_nodes()), 0.0);
    for_edge_points(sim, "line_load_edges", groups,
                    [&](std::size_t, const shell::Stencil& st, double w) {
                      // per length of the edge as meshed: next to a corner of the mesh the ghost
                      // rings are open, the limit curve falls short of the corner and its stencil's
                      // weights sum to less than one (a tenth of the corner edge's load was lost
                      // with the limit curve's length element: a first-order error in the tip
                      // load); the load q |E| ds is shared in proportion to the weights, so that
                      // the whole of it arrives
                      double unity = 0;
                      for (const auto& r : st) unity += r.N;
                      for (const auto& r : st) sum[static_cast<size_t>(r.node)] += w * r.N / unity;
                    });
    std::vector<std::pair<int, double>> out;
    for (std::size_t i = 0; i < sum.size(); ++i)
      if (sum[i] != 0) out.push_back({static_cast<int>(i), sum[i]});
    return out;
  }

  // The fibres that cross the listed boundary edges (4 Gauss–Legendre points per edge):
  // the material direction t = c^a a_a that is the outward conormal nu0 in the reference,
  // as a stencil d_I = c^a N_I,a (c^a from A_ab c^b = A_a . nu0), and the plane normal to
  // the axis in which its angle is measured (e1 = nu0 projected, e2 = axis x e1).
  std::vector<MomentPoint> edge_fibres(Context& sim, const std::vector<std::string>& groups,
                                       const Vec3& axis) {
    const auto& g = mesh();
    std::vector<MomentPoint> out;
    for_edge_points(
        sim, "line_moment_edges", groups, [&](std::size_t k, const shell::Stencil& st, double w) {
          const auto& gh = g.ghosts[k];
          const Vec3 X0 = g.mesh.x[gh.b0], X2 = g.mesh.x[gh.b2];
          Vec3 A1 = Vec3::Zero(), A2 = A1;
          for (const auto& r : st) {
            A1 += r.Nv * g.mesh.x[r.node];
            A2 += r.Nw * g.mesh.x[r.node];
          }
          Vec3 nu = (X2 - X0).cross(A1.cross(A2)).normalized();
          if (nu.dot(g.mesh.x[gh.interior] - X0) > 0) nu = -nu;  // outwards
          Mat2 A;
          A << A1.dot(A1), A1.dot(A2), A1.dot(A2), A2.dot(A2);
          const Eigen::Vector2d cc = A.inverse() * Eigen::Vector2d(A1.dot(nu), A2.dot(nu));
          MomentPoint mp;
          mp.w = w;
          const Vec3 e1 = nu - nu.dot(axis) * axis;
          if (e1.norm() < 1e-3)
            throw InputError(
                "shell 'koiter': line_moment points along the outward direction of an edge of "
                "line_moment_edges: a twisting moment, which the fibre rotation does not carry; "
                "give a moment about the edge (a bending moment)");
          mp.e1 = e1.normalized();
          mp.e2 = axis.cross(mp.e1);
          for (const auto& r : st)
            if (double d = cc[0] * r.Nv + cc[1] * r.Nw; d != 0) mp.rows.push_back({r.node, d});
          out.push_back(std::move(mp));
        });
    return out;
  }

  // The line moment (docs/models.md §6.4): potential -|m| sum w phi, phi the angle of each
  // fibre t in the plane (e1, e2), continued through full turns from its last value.
  void add_moment(const std::vector<Vec3>& x, std::vector<Vec3>& f, Context& sim) {
    const double m = load_factor_ * moment_;
    double e = 0;
    for (MomentPoint& mp : moment_points_) {
      Vec3 t = Vec3::Zero();
      for (auto [i, d] : mp.rows) t += d * x[base_ + i];
      const double u = t.dot(mp.e1), v = t.dot(mp.e2), r2 = u * u + v * v;
      mp.phi += std::remainder(std::atan2(v, u) - mp.phi, 2 * M_PI);
      e -= m * mp.w * mp.phi;
      const Vec3 dphi = (-v / r2) * mp.e1 + (u / r2) * mp.e2;
      for (auto [i, d] : mp.rows) f[base_ + i] += (m * mp.w * d) * dphi;
    }
    sim.add_energy("external", e);
  }

  // Each ghost's rule: `boundary`, unless its edge (both boundary nodes) lies in one of
  // the node groups of supported_edges, symmetry_edges, diaphragm_edges or clamped_edges
  // (the later in this list wins where several name an edge).
  void assign_edge_rules(Context& sim, const std::vector<std::string>& supported,
                         const std::vector<std::string>& clamped,
                         const std::vector<std::string>& symmetry,
                         const std::vector<std::string>& diaphragm) {
    const auto& g = mesh();
    rule_.assign(g.ghosts.size(), boundary_);
    reflect_.assign(g.ghosts.size(), Mat3::Identity());
    edge_bits_.assign(g.ghosts.size(), kMaskAll);
    auto mark = [&](const std::string& key, const std::vector<std::string>& groups, Boundary r) {
      for (std::size_t k : edges_in(sim, key, groups)) rule_[k] = r;
    };
    mark("supported_edges", supported, Boundary::kSimplySupported);
    mark("symmetry_edges", symmetry, Boundary::kSymmetry);
    mark("diaphragm_edges", diaphragm, Boundary::kDiaphragm);
    mark("clamped_edges", clamped, Boundary::kClampedEdge);
    for (std::size_t k = 0; k < g.ghosts.size(); ++k) {
      if (!reflected(rule_[k])) continue;
      // the reference normal of the edge's triangle: the clamp's ghost displacement is its
      // partner's reflected in the tangent plane (normal part kept, in-plane part negated)
      const auto& gh = g.ghosts[k];
      const Vec3 e = g.mesh.x[gh.b2] - g.mesh.x[gh.b0];
      const Vec3 n = e.cross(g.mesh.x[gh.interior] - g.mesh.x[gh.b0]).normalized();
      if (rule_[k] == Boundary::kClampedEdge) {
        reflect_[k] = 2.0 * n * n.transpose() - Mat3::Identity();
        continue;
      }
      // the edge's outward direction in the tangent plane: the normal of the symmetry
      // plane or diaphragm, which must be a coordinate axis (the held components are)
      Vec3 nu = e.cross(n).normalized();
      if (nu.dot(g.mesh.x[gh.interior] - g.mesh.x[gh.b0]) > 0) nu = -nu;
      int axis = 0;
      nu.cwiseAbs().maxCoeff(&axis);
      if (std::abs(nu[axis]) < 1 - 1e-6) {
        char buf[400];
        std::snprintf(buf, sizeof buf,
                      "shell 'koiter': %s holds the edge from (%g, %g, %g) to (%g, %g, %g), "
                      "whose outward direction (%.4g, %.4g, %.4g) is not along x, y or z; "
                      "symmetry planes and diaphragms here are normal to a coordinate axis",
                      rule_[k] == Boundary::kSymmetry ? "symmetry_edges" : "diaphragm_edges",
                      g.mesh.x[gh.b0].x(), g.mesh.x[gh.b0].y(), g.mesh.x[gh.b0].z(),
                      g.mesh.x[gh.b2].x(), g.mesh.x[gh.b2].y(), g.mesh.x[gh.b2].z(), nu.x(), nu.y(),
                      nu.z());
        throw InputError(buf);
      }
      nu = Vec3::Unit(axis);
      const Mat3 odd_normal = Mat3::Identity() - 2.0 * nu * nu.transpose();
      const int bit = axis == 0 ? kMaskX : axis == 1 ? kMaskY : kMaskZ;
      if (rule_[k] == Boundary::kSymmetry) {
        reflect_[k] = odd_normal;
        edge_bits_[k] = bit;
      } else {
        reflect_[k] = -odd_normal;
        edge_bits_[k] = kMaskAll & ~bit;
      }
    }
  }

  // masses, and the node masks of the boundary rules
  void apply_constraints(Context& sim) {
    const auto& g = mesh();
    auto& m = sim.nodes().mass;
    std::vector<double> lumped = lumped_;
    double mean_real = 0;
    for (int i = 0; i < g.n_real_nodes; ++i) mean_real += lumped[i];
    mean_real /= g.n_real_nodes;
    for (std::size_t k = 0; k < g.ghosts.size(); ++k)
      if (kinematic(rule_[k])) {  // a prescribed ghost's inertia goes to its edge
        const auto& gh = g.ghosts[k];
        lumped[gh.b0] += 0.5 * lumped[gh.node];
        lumped[gh.b2] += 0.5 * lumped[gh.node];
        lumped[gh.node] = mean_real;
      }
    for (int i = 0; i < g.mesh.n_nodes(); ++i) m[base_ + i] = lumped[i];
    bool any = false;
    for (Boundary r : rule_) any = any || kinematic(r);
    if (!any) return;
    auto& mask = sim.held_components();
    for (std::size_t k = 0; k < g.ghosts.size(); ++k) {
      const auto& gh = g.ghosts[k];
      if (kinematic(rule_[k])) mask[base_ + gh.node] = kMaskAll;
      if (holds_edge(rule_[k])) {
        mask[base_ + gh.b0] |= edge_bits_[k];
        mask[base_ + gh.b2] |= edge_bits_[k];
      }
      if (rule_[k] == Boundary::kClamped) mask[base_ + gh.interior] = kMaskAll;  // first row
    }
    for (int i = 0; i < g.mesh.n_nodes(); ++i)
      for (int c = 0; c < 3; ++c)
        if (mask[base_ + i] & (1 << c)) sim.nodes().v[base_ + i][c] = 0;
  }

  void update_growth(Context& sim) {
    if (!growth_) return;
    if (growth_->version() == growth_version_ &&
        !(growth_->time_dependent() && sim.time() != growth_time_))
      return;
    growth_version_ = growth_->version();
    growth_time_ = sim.time();
    for (auto& gp : gauss_) {
      const Mat3 G = growth_->tensor(gp.X, sim.time());
      // mixed components Gtilde^c_a = abar^c . (G abar_a), abar^c = abar^{cd} abar_d
      const Mat2 ai = gp.abar.inverse();
      const Vec3 up1 = ai(0, 0) * gp.a1bar + ai(0, 1) * gp.a2bar;
      const Vec3 up2 = ai(1, 0) * gp.a1bar + ai(1, 1) * gp.a2bar;
      const Vec3 Ga1 = G * gp.a1bar, Ga2 = G * gp.a2bar;
      Mat2 Gt;
      Gt << up1.dot(Ga1), up1.dot(Ga2), up2.dot(Ga1), up2.dot(Ga2);
      gp.detG = Gt.determinant();
      // the in-plane growth must stretch the surface by positive factors: det > 0 and
      // trace > 0 (both eigenvalues of the 2 x 2 tensor with a positive real part); det > 0
      // alone passes G = -1, a factor below zero in both directions
      if (!(gp.detG > 0) || !(Gt.trace() > 0)) {
        char buf[768];
        std::snprintf(buf, sizeof buf,
                      "growth '%s' at (%g, %g, %g), t = %g: the in-plane growth tensor ((%g, "
                      "%g), (%g, %g)) %s; growth factors must be positive (a factor <= 0, from "
                      "'factor', 'rate' or 'fn', shrinks the surface to nothing or through it)",
                      growth_id_.c_str(), gp.X.x(), gp.X.y(), gp.X.z(), sim.time(), Gt(0, 0),
                      Gt(0, 1), Gt(1, 0), Gt(1, 1),
                      !std::isfinite(gp.detG) ? "is not finite"
                      : gp.detG == 0          ? "is singular"
                      : gp.detG < 0           ? "reverses the surface's orientation"
                                              : "has negative factors");
        throw InputError(buf);
      }
      gp.P = Gt.inverse();
    }
  }

  // Element energies and forces; f gets -grad. Observables when `observe`.
  // With a context, the Gauss points run on its threads (ranges aligned to whole
  // elements, so that each element's face values have one writer), forces into f =
  // the nodes' forces; without, serially into f.
  void accumulate(const std::vector<Vec3>& x, std::vector<Vec3>& f, double* es, double* eb,
                  bool observe, Context* threads = nullptr) {
    // one cache line per thread: the sums sit in registers during the loop and are stored
    // once, and no two threads' sums share a line
    struct alignas(64) Part {
      double Es = 0, Eb = 0, area = 0, ub_int = 0;
    };
    std::array<Part, kMaxThreads> parts{};
    if (observe) {
      std::fill(face_ub_.begin(), face_ub_.end(), 0.0);
      std::fill(face_us_.begin(), face_us_.end(), 0.0);
      face_area_.assign(n_elem_, 0.0);
    }
    const std::size_t n_gauss = gauss_.size();
    auto element_start = [&](std::size_t i) {
      while (i > 0 && i < n_gauss && gauss_[i].element == gauss_[i - 1].element) ++i;
      return i;
    };
    auto kernel = [&](int tid, std::size_t begin, std::size_t end, Vec3* fo) {
      double Es = 0, Eb = 0, area = 0, ub_int = 0;
      const std::size_t last = element_start(end);
      for (std::size_t g = element_start(begin); g < last; ++g) {
        const GaussPoint& gp = gauss_[g];
        const shell::ShapeRow* R = &rows_[gp.row0];
        Vec3 a1 = Vec3::Zero(), a2 = a1, a11 = a1, a12 = a1, a22 = a1;
        for (int r = 0; r < gp.nrows; ++r) {
          const Vec3& p = x[R[r].node];
          a1 += R[r].Nv * p;
          a2 += R[r].Nw * p;
          a11 += R[r].Nvv * p;
          a12 += R[r].Nvw * p;
          a22 += R[r].Nww * p;
        }
        const Vec3 n = a1.cross(a2);
        const double J = n.norm();
        const Vec3 a3 = n / J;
        Mat2 a, k;
        a << a1.dot(a1), a1.dot(a2), a1.dot(a2), a2.dot(a2);
        k << a11.dot(a3), a12.dot(a3), a12.dot(a3), a22.dot(a3);
        const Mat2 ah = gp.P.transpose() * a * gp.P;
        const Mat2 kh = gp.P.transpose() * k * gp.P;
        const Mat2 al = 0.5 * (ah - gp.abar);
        const Mat2 be = gp.kbar - kh;
        const Vec3 alV(al(0, 0), al(1, 1), 2 * al(0, 1));
        const Vec3 beV(be(0, 0), be(1, 1), 2 * be(0, 1));
        const Vec3 HalV = gp.H * alV, HbeV = gp.H * beV;
        const double Us = alV.dot(HalV), Ub = beV.dot(HbeV);
        const double w = area_factor_ ? gp.w * gp.detG : gp.w;
        Es += 0.5 * Cm_ * Us * w;
        Eb += 0.5 * Cb_ * Ub * w;
        if (observe) {
          // densities of §6.3/§6.11 over the current area element
          const double cur = gp.wq * J;
          area += cur;
          ub_int += Ub * cur;
          face_ub_[gp.element] += Ub * cur;
          face_us_[gp.element] += Us * cur;
          face_area_[gp.element] += cur;
        }
        Mat2 N, M;
        N << Cm_ * HalV(0), Cm_ * HalV(2), Cm_ * HalV(2), Cm_ * HalV(1);
        M << Cb_ * HbeV(0), Cb_ * HbeV(2), Cb_ * HbeV(2), Cb_ * HbeV(1);
        const Mat2 Nt = gp.P * N * gp.P.transpose();
        const Mat2 Mt = gp.P * M * gp.P.transpose();
        const Vec3 m1 = Nt(0, 0) * a1 + Nt(0, 1) * a2;
        const Vec3 m2 = Nt(1, 0) * a1 + Nt(1, 1) * a2;
        Vec3 c = Mt(0, 0) * a11 + 2 * Mt(0, 1) * a12 + Mt(1, 1) * a22;
        c -= c.dot(a3) * a3;
        const Vec3 b1 = a2.cross(c) / J, b2 = c.cross(a1) / J;
        const Vec3 g1 = w * (m1 - b1), g2 = w * (m2 - b2);
        const Vec3 g3 = -w * a3;
        for (int r = 0; r < gp.nrows; ++r) {
          const shell::ShapeRow& s = R[r];
          fo[s.node] -= s.Nv * g1 + s.Nw * g2 +
                        (Mt(0, 0) * s.Nvv + 2 * Mt(0, 1) * s.Nvw + Mt(1, 1) * s.Nww) * g3;
        }
      }
      parts[static_cast<std::size_t>(tid)] = Part{Es, Eb, area, ub_int};
      return 0.0;
    };
    if (threads) {
      assert(&f == &threads->nodes().f);
      threads->parallel_heavy_forces(n_gauss, kernel);
    } else {
      kernel(0, 0, n_gauss, f.data());
    }
    double Es = 0, Eb = 0, area = 0, ub_int = 0;
    for (const Part& part : parts) {
      Es += part.Es;
      Eb += part.Eb;
      area += part.area;
      ub_int += part.ub_int;
    }
    *es = Es;
    *eb = Eb;
    if (observe) {
      area_ = area;
      ub_integral_ = ub_int;
      for (int t = 0; t < n_elem_; ++t)
        if (face_area_[t] > 0) {
          face_ub_[t] /= face_area_[t];
          face_us_[t] /= face_area_[t];
        }
    }
  }

  // The pressure (docs/models.md §6.4). On a closed surface: p times the exact gradient of
  // the enclosed volume as integrated, V = 1/3 sum_gp wq x . (a1 x a2), so that the load
  // derives from -p V to round-off and Newton sees a symmetric, exact Hessian (the plain
  // follower form below differs from it by the quadrature's error). On an open surface: the
  // follower load f_I += p sum_gp wq N_I (a1 x a2), the current normal times the current
  // area element (it has no potential there).
  void add_pressure(const std::vector<Vec3>& x, std::vector<Vec3>& f, Context& sim) {
    const double p = load_factor_ * pressure_;
    const bool closed = mesh().ghosts.empty();
    double vol = 0;
    for (const GaussPoint& gp : gauss_) {
      const shell::ShapeRow* R = &rows_[gp.row0];
      Vec3 X = Vec3::Zero(), a1 = X, a2 = X;
      for (int r = 0; r < gp.nrows; ++r) {
        const Vec3& q = x[R[r].node];
        X += R[r].N * q;
        a1 += R[r].Nv * q;
        a2 += R[r].Nw * q;
      }
      const Vec3 n = gp.wq * a1.cross(a2);
      vol += X.dot(n) / 3.0;
      if (closed) {
        const Vec3 c1 = gp.wq * a2.cross(X), c2 = gp.wq * X.cross(a1);
        for (int r = 0; r < gp.nrows; ++r)
          f[R[r].node] += (p / 3.0) * (R[r].N * n + R[r].Nv * c1 + R[r].Nw * c2);
      } else {
        for (int r = 0; r < gp.nrows; ++r) f[R[r].node] += (p * R[r].N) * n;
      }
    }
    volume_ = vol;
    sim.add_energy("external", -p * vol);
  }

  void place_ghosts(std::vector<Vec3>& x) const {
    const auto& g = mesh();
    for (std::size_t k = 0; k < g.ghosts.size(); ++k) {
      const auto& gh = g.ghosts[k];
      const int gn = gh.node, pn = partner_[k];
      switch (rule_[k]) {
        case Boundary::kMirror:
          x[base_ + gn] = x[base_ + gh.b0] + x[base_ + gh.b2] - x[base_ + gh.interior];
          break;
        case Boundary::kSimplySupported:
          x[base_ + gn] = g.mesh.x[gn] - (x[base_ + pn] - g.mesh.x[pn]);
          break;
        case Boundary::kClampedEdge:
        case Boundary::kSymmetry:
        case Boundary::kDiaphragm:
          x[base_ + gn] = g.mesh.x[gn] + reflect_[k] * (x[base_ + pn] - g.mesh.x[pn]);
          break;
        default:
          break;
      }
    }
  }

  // Forces on prescribed ghosts go to the nodes that place them (chain rule);
  // the combined method pulls free ghosts towards their mirror position (5.35).
  void map_ghost_forces(const std::vector<Vec3>& x, std::vector<Vec3>& f) {
    const auto& g = mesh();
    ghost_energy_ = 0;
    const double dead = lambda_ * mean_edge_;
    for (std::size_t k = 0; k < g.ghosts.size(); ++k) {
      const auto& gh = g.ghosts[k];
      if (rule_[k] == Boundary::kMirror) {
        const Vec3 fg = f[base_ + gh.node];
        f[base_ + gh.b0] += fg;
        f[base_ + gh.b2] += fg;
        f[base_ + gh.interior] -= fg;
        f[base_ + gh.node].setZero();
      } else if (rule_[k] == Boundary::kSimplySupported) {
        f[base_ + partner_[k]] -= f[base_ + gh.node];
        f[base_ + gh.node].setZero();
      } else if (reflected(rule_[k])) {
        f[base_ + partner_[k]] += reflect_[k].transpose() * f[base_ + gh.node];
        f[base_ + gh.node].setZero();
      } else if (rule_[k] == Boundary::kCombined) {
        const Vec3 mirror = x[base_ + gh.b0] + x[base_ + gh.b2] - x[base_ + gh.interior];
        const Vec3 d = x[base_ + gh.node] - mirror;
        const double len = d.norm();
        if (len <= dead) continue;
        const Vec3 fs = k_ghost_ * (len - dead) / len * d;
        f[base_ + gh.node] -= fs;
        if (ghost_reaction_) {  // gradient of 1/2 k (|d| - dead)^2 w.r.t. the mirror's nodes
          f[base_ + gh.b0] += fs;
          f[base_ + gh.b2] += fs;
          f[base_ + gh.interior] -= fs;
        }
        ghost_energy_ += 0.5 * k_ghost_ * (len - dead) * (len - dead);
      }
    }
  }

  // Largest omega of M^-1 K by power iteration on finite differences of the forces
  // at the current state (free degrees of freedom only), checked against the
  // membrane wave estimate 2 c / l_min (c^2 = Y / (rho (1 - nu^2))).
  double estimate_omega(Context& sim) {
    const auto& g = mesh();
    const int n = g.mesh.n_nodes();
    std::vector<Vec3> x = sim.nodes().x, v(n);
    const Property<int>* mask = sim.held_components_if_any();
    auto free = [&](int i) { return !(mask && (*mask)[base_ + i] == kMaskAll); };
    std::mt19937_64 rng(12345);
    std::uniform_real_distribution<double> uni(-1, 1);
    for (int i = 0; i < n; ++i) v[i] = free(i) ? Vec3(uni(rng), uni(rng), uni(rng)) : Vec3::Zero();
    const double eps = 1e-6 * mean_edge_;
    auto Kv = [&](std::vector<Vec3>& out) {
      std::vector<Vec3> fp(x.size(), Vec3::Zero()), fm(x.size(), Vec3::Zero());
      for (int s = 0; s < 2; ++s) {
        std::vector<Vec3> xs = x;
        const double sign = s == 0 ? 1.0 : -1.0;
        for (int i = 0; i < n; ++i) xs[base_ + i] += sign * eps * v[i];
        place_ghosts(xs);
        auto& ff = s == 0 ? fp : fm;
        double a, b;
        accumulate(xs, ff, &a, &b, false);
        map_ghost_forces(xs, ff);
      }
      for (int i = 0; i < n; ++i)
        out[i] = free(i) ? Vec3(-(fp[base_ + i] - fm[base_ + i]) / (2 * eps)) : Vec3::Zero();
    };
    std::vector<Vec3> kv(n);
    double lambda = 0;
    for (int it = 0; it < 60; ++it) {
      Kv(kv);
      double vkv = 0, vmv = 0, norm = 0;
      for (int i = 0; i < n; ++i) {
        const double m = sim.nodes().mass[base_ + i];
        vkv += v[i].dot(kv[i]);
        vmv += m * v[i].squaredNorm();
      }
      lambda = vkv / vmv;
      for (int i = 0; i < n; ++i) {
        v[i] = kv[i] / sim.nodes().mass[base_ + i];
        norm = std::max(norm, v[i].norm());
      }
      if (!(norm > 0)) break;
      for (auto& vi : v) vi /= norm;
    }
    double omega = std::sqrt(std::max(0.0, lambda));
    const double wave = 2 * std::sqrt(Y_ / (rho_ * (1 - nu_ * nu_))) / lmin_;
    // power iteration converges from below; keep a margin
    omega = std::max(1.1 * omega, 0.5 * wave);
    if (sim.verbose())
      std::printf(
          "shell %s: omega_max %.4g (power iteration, +10%%), membrane wave 2c/l_min "
          "%.4g, l_min %.4g\n",
          id().c_str(), omega, wave, lmin_);
    return omega;
  }

  std::string mesh_name_;
  double h_, Y_, nu_, rho_;
  static Boundary boundary_rule(const std::string& s) {
    if (s == "mirror") return Boundary::kMirror;
    if (s == "free_ghosts") return Boundary::kFreeGhosts;
    if (s == "clamped") return Boundary::kClamped;
    if (s == "simply_supported") return Boundary::kSimplySupported;
    return Boundary::kCombined;
  }
  Boundary boundary_;
  double k_ghost_, lambda_;
  bool reflection_;
  bool ghost_reaction_;
  std::string growth_id_;
  bool area_factor_;
  int nquad_;
  Vec3 load_;
  double pressure_ = 0;
  double load_factor_ = 1.0;  // lambda of a continuation (docs/models.md §9.4)
  double volume_ = 0;
  double Cm_ = 0, Cb_ = 0;
  std::shared_ptr<const shell::GhostedMesh> mesh_;
  int base_ = 0, n_elem_ = 0;
  std::vector<shell::ShapeRow> rows_;
  std::vector<GaussPoint> gauss_;
  std::vector<double> lumped_;
  std::vector<int> partner_;
  std::vector<Boundary> rule_;  // per ghost
  std::vector<int> edge_bits_;  // per ghost: the components its edge's rule holds
  std::vector<Mat3> reflect_;   // per ghost of a clamped edge: 2 n n^T - 1
  Vec3 line_load_ = Vec3::Zero();
  std::vector<MomentPoint> moment_points_;
  double moment_ = 0;                                 // |line_moment|
  std::vector<std::pair<int, double>> line_weights_;  // (mesh node, integral of N along edges)
  double mean_edge_ = 0, lmin_ = 0;
  GrowthStyle* growth_ = nullptr;
  long growth_version_ = -1;
  double growth_time_ = -1;
  bool constraints_done_ = false;
  double omega_ = 0;
  double stretch_ = 0, bend_ = 0, area_ = 0, ub_integral_ = 0, ghost_energy_ = 0;
  std::vector<double> face_ub_, face_us_, face_area_;
};

}  // namespace slender

SLENDER_REGISTER_STYLE(slender::ShellStyle, "koiter", slender::KoiterShell)
