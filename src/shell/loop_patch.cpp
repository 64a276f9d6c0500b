#include "shell/loop_patch.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <map>
#include <stdexcept>

#include "params.hpp"

namespace slender::shell {

namespace {

// A polynomial's value with its first and second derivatives in (v, w): the box
// splines are written once and differentiated exactly by these operations.
struct Jet {
  double f = 0, v = 0, w = 0, vv = 0, vw = 0, ww = 0;
};
Jet operator+(const Jet& a, const Jet& b) {
  return {a.f + b.f, a.v + b.v, a.w + b.w, a.vv + b.vv, a.vw + b.vw, a.ww + b.ww};
}
Jet operator*(double s, const Jet& a) {
  return {s * a.f, s * a.v, s * a.w, s * a.vv, s * a.vw, s * a.ww};
}
Jet operator*(const Jet& a, const Jet& b) {
  return {a.f * b.f,
          a.v * b.f + a.f * b.v,
          a.w * b.f + a.f * b.w,
          a.vv * b.f + 2 * a.v * b.v + a.f * b.vv,
          a.vw * b.f + a.v * b.w + a.w * b.v + a.f * b.vw,
          a.ww * b.f + 2 * a.w * b.w + a.f * b.ww};
}

}  // namespace

std::array<ShapeRow, 12> box_splines(double vv, double ww) {
  const Jet v{vv, 1, 0, 0, 0, 0}, w{ww, 0, 1, 0, 0, 0}, u{1 - vv - ww, -1, -1, 0, 0, 0};
  const Jet u2 = u * u, u3 = u2 * u, u4 = u3 * u;
  const Jet v2 = v * v, v3 = v2 * v, v4 = v3 * v;
  const Jet w2 = w * w, w3 = w2 * w, w4 = w3 * w;
  // docs/models.md §6.6 (App. C), times 12
  Jet N[12];
  N[0] = u4 + 2 * (u3 * v);
  N[1] = u4 + 2 * (u3 * w);
  N[2] = u4 + 2 * (u3 * w) + 6 * (u3 * v) + 6 * (u2 * v * w) + 12 * (u2 * v2) + 6 * (u * v2 * w) +
         6 * (u * v3) + 2 * (v3 * w) + v4;
  N[3] = 6 * u4 + 24 * (u3 * w) + 24 * (u2 * w2) + 8 * (u * w3) + w4 + 24 * (u3 * v) +
         60 * (u2 * v * w) + 36 * (u * v * w2) + 6 * (v * w3) + 24 * (u2 * v2) + 36 * (u * v2 * w) +
         12 * (v2 * w2) + 8 * (u * v3) + 6 * (v3 * w) + v4;
  N[4] = u4 + 6 * (u3 * w) + 12 * (u2 * w2) + 6 * (u * w3) + w4 + 2 * (u3 * v) + 6 * (u2 * v * w) +
         6 * (u * v * w2) + 2 * (v * w3);
  N[5] = 2 * (u * v3) + v4;
  N[6] = u4 + 6 * (u3 * w) + 12 * (u2 * w2) + 6 * (u * w3) + w4 + 8 * (u3 * v) + 36 * (u2 * v * w) +
         36 * (u * v * w2) + 8 * (v * w3) + 24 * (u2 * v2) + 60 * (u * v2 * w) + 24 * (v2 * w2) +
         24 * (u * v3) + 24 * (v3 * w) + 6 * v4;
  N[7] = u4 + 8 * (u3 * w) + 24 * (u2 * w2) + 24 * (u * w3) + 6 * w4 + 6 * (u3 * v) +
         36 * (u2 * v * w) + 60 * (u * v * w2) + 24 * (v * w3) + 12 * (u2 * v2) +
         36 * (u * v2 * w) + 24 * (v2 * w2) + 6 * (u * v3) + 8 * (v3 * w) + v4;
  N[8] = 2 * (u * w3) + w4;
  N[9] = 2 * (v3 * w) + v4;
  N[10] = 2 * (u * w3) + w4 + 6 * (u * v * w2) + 6 * (v * w3) + 6 * (u * v2 * w) + 12 * (v2 * w2) +
          2 * (u * v3) + 6 * (v3 * w) + v4;
  N[11] = w4 + 2 * (v * w3);
  std::array<ShapeRow, 12> out;
  for (int i = 0; i < 12; ++i) {
    const Jet n = (1.0 / 12.0) * N[i];
    out[i] = ShapeRow{-1, n.f, n.v, n.w, n.vv, n.vw, n.ww};
  }
  return out;
}

std::array<int, 12> gather_regular(const Rings& rings, int p4, int p7, int p8) {
  const auto r4 = ring_from(rings, p4, p7);  // 7 8 5 2 1 3
  const auto r7 = ring_from(rings, p7, p4);  // 4 3 6 10 11 8
  const auto r8 = ring_from(rings, p8, p4);  // 4 7 11 12 9 5
  if (r4.size() != 6 || r7.size() != 6 || r8.size() != 6 || r4[1] != p8)
    throw std::logic_error("gather_regular: the patch is not regular");
  return {r4[4], r4[3], r4[5], p4, r4[2], r7[2], p7, p8, r8[4], r7[3], r7[4], r8[3]};
}

double loop_omega(int V) {
  const double c = 3.0 / 8.0 + 0.25 * std::cos(2 * M_PI / V);
  return (5.0 / 8.0 - c * c) / V;
}

Tri oriented_element(const GhostedMesh& g, int t) {
  Tri c = g.mesh.tri[t];
  for (int k = 0; k < 3; ++k) {
    if (g.valence[c[0]] != 6) break;
    c = {c[1], c[2], c[0]};
  }
  return c;
}

namespace {

// A piece of mesh whose node positions are linear combinations of the patch's
// control nodes (rows of W); an empty row marks a node whose stencil is incomplete.
struct LocalMesh {
  std::vector<Eigen::VectorXd> W;
  std::vector<Tri> tri;
};

struct Subdivided {
  LocalMesh mesh;
  std::vector<int> vertex_of;                  // old node -> new node
  std::map<std::pair<int, int>, int> edge_of;  // sorted old edge -> new node
  int edge(int a, int b) const { return edge_of.at({std::min(a, b), std::max(a, b)}); }
};

// One Loop step (5.20)-(5.22) on a local mesh; stencils that reach outside it stay empty.
Subdivided subdivide(const LocalMesh& L) {
  const int n = static_cast<int>(L.W.size());
  const int P = static_cast<int>(L.W[0].size() ? L.W[0].size() : 0);
  Rings rings = build_rings(n, L.tri);
  Subdivided S;
  auto& M = S.mesh;
  auto valid = [&](int i) { return L.W[i].size() > 0; };
  S.vertex_of.resize(n);
  for (int i = 0; i < n; ++i) {
    S.vertex_of[i] = static_cast<int>(M.W.size());
    Eigen::VectorXd w;
    bool ok = rings.closed[i] && valid(i);
    for (int j : rings.ring[i]) ok = ok && valid(j);
    if (ok) {
      const int V = static_cast<int>(rings.ring[i].size());
      const double om = loop_omega(V);
      w = (1 - V * om) * L.W[i];
      for (int j : rings.ring[i]) w += om * L.W[j];
    }
    M.W.push_back(w);
  }
  // opposite vertex of each directed edge
  std::map<std::pair<int, int>, int> opp;
  for (const Tri& t : L.tri)
    for (int k = 0; k < 3; ++k) opp[{t[k], t[(k + 1) % 3]}] = t[(k + 2) % 3];
  for (const Tri& t : L.tri)
    for (int k = 0; k < 3; ++k) {
      const int a = t[k], b = t[(k + 1) % 3];
      auto key = std::make_pair(std::min(a, b), std::max(a, b));
      if (S.edge_of.count(key)) continue;
      S.edge_of[key] = static_cast<int>(M.W.size());
      Eigen::VectorXd w;
      auto c = opp.find({a, b}), d = opp.find({b, a});
      if (c != opp.end() && d != opp.end() && valid(a) && valid(b) && valid(c->second) &&
          valid(d->second))
        w = 0.375 * (L.W[a] + L.W[b]) + 0.125 * (L.W[c->second] + L.W[d->second]);
      M.W.push_back(w);
    }
  for (const Tri& t : L.tri) {
    const int a = S.vertex_of[t[0]], b = S.vertex_of[t[1]], c = S.vertex_of[t[2]];
    const int ab = S.edge(t[0], t[1]), bc = S.edge(t[1], t[2]), ca = S.edge(t[2], t[0]);
    M.tri.push_back({a, ab, ca});
    M.tri.push_back({ab, b, bc});
    M.tri.push_back({ca, bc, c});
    M.tri.push_back({ab, bc, ca});
  }
  (void)P;
  return S;
}

// The triangles of L incident to any of `corners`, renumbered compactly.
LocalMesh restrict_to(const LocalMesh& L, Tri& corners) {
  std::map<int, int> id;
  LocalMesh out;
  auto map = [&](int i) {
    auto [it, fresh] = id.try_emplace(i, static_cast<int>(out.W.size()));
    if (fresh) out.W.push_back(L.W[i]);
    return it->second;
  };
  for (int c : corners) map(c);
  for (const Tri& t : L.tri) {
    bool touches = false;
    for (int k : t)
      for (int c : corners) touches |= (k == c);
    if (touches) out.tri.push_back({map(t[0]), map(t[1]), map(t[2])});
  }
  for (int& c : corners) c = id.at(c);
  return out;
}

}  // namespace

Stencil evaluate(const GhostedMesh& g, const Tri& corners, double v, double w) {
  const Rings& R = g.rings;
  if (g.valence[corners[0]] == 6 && g.valence[corners[1]] == 6 && g.valence[corners[2]] == 6) {
    const auto nodes = gather_regular(R, corners[0], corners[1], corners[2]);
    const auto N = box_splines(v, w);
    Stencil s(12);
    for (int i = 0; i < 12; ++i) {
      s[i] = N[i];
      s[i].node = nodes[i];
    }
    return s;
  }
  // local mesh: every triangle incident to the element's corners
  std::map<int, int> local;
  std::vector<int> global;
  LocalMesh L;
  auto map = [&](int i) {
    auto [it, fresh] = local.try_emplace(i, static_cast<int>(global.size()));
    if (fresh) global.push_back(i);
    return it->second;
  };
  for (int c : corners) map(c);
  std::vector<int> tris;
  for (int c : corners)
    for (int t : R.tris[c]) tris.push_back(t);
  std::sort(tris.begin(), tris.end());
  tris.erase(std::unique(tris.begin(), tris.end()), tris.end());
  for (int t : tris) {
    const Tri& tr = g.mesh.tri[t];
    L.tri.push_back({map(tr[0]), map(tr[1]), map(tr[2])});
  }
  const int P = static_cast<int>(global.size());
  for (int i = 0; i < P; ++i) L.W.push_back(Eigen::VectorXd::Unit(P, i));
  Tri c{local.at(corners[0]), local.at(corners[1]), local.at(corners[2])};

  const double eps = 1e-12;
  double jac1 = 1.0, jac2 = 1.0;  // first- and second-derivative scale
  for (int level = 0; level < 40; ++level) {
    Subdivided S = subdivide(L);
    const int A = S.vertex_of[c[0]], B = S.vertex_of[c[1]], C = S.vertex_of[c[2]];
    const int ab = S.edge(c[0], c[1]), bc = S.edge(c[1], c[2]), ca = S.edge(c[2], c[0]);
    const double u = 1 - v - w;
    Tri child;
    if (u > 0.5 + eps) {  // child 4: irregular again, recurse
      v *= 2;
      w *= 2;
      jac1 *= 2;
      jac2 *= 4;
      child = {A, ab, ca};
      L = restrict_to(S.mesh, child);
      c = child;
      continue;
    }
    if (v > 0.5 - eps) {  // child 1
      child = {ab, B, bc};
      v = 2 * v - 1;
      w = 2 * w;
      jac1 *= 2;
    } else if (w > 0.5 - eps) {  // child 3
      child = {ca, bc, C};
      v = 2 * v;
      w = 2 * w - 1;
      jac1 *= 2;
    } else {  // child 2 (middle, reversed parameters)
      child = {bc, ca, ab};
      v = 1 - 2 * v;
      w = 1 - 2 * w;
      jac1 *= -2;
    }
    jac2 *= 4;
    LocalMesh Lc = restrict_to(S.mesh, child);
    Rings rc = build_rings(static_cast<int>(Lc.W.size()), Lc.tri);
    const auto nodes = gather_regular(rc, child[0], child[1], child[2]);
    const auto N = box_splines(v, w);
    Eigen::MatrixXd acc = Eigen::MatrixXd::Zero(6, P);
    for (int i = 0; i < 12; ++i) {
      const Eigen::VectorXd& W = Lc.W[nodes[i]];
      if (W.size() != P) throw std::logic_error("evaluate: incomplete subdivision stencil");
      const double vals[6] = {N[i].N,          jac1 * N[i].Nv,  jac1 * N[i].Nw,
                              jac2 * N[i].Nvv, jac2 * N[i].Nvw, jac2 * N[i].Nww};
      for (int r = 0; r < 6; ++r) acc.row(r) += vals[r] * W.transpose();
    }
    Stencil s;
    for (int j = 0; j < P; ++j) {
      if (acc.col(j).cwiseAbs().maxCoeff() == 0.0) continue;
      s.push_back(
          ShapeRow{global[j], acc(0, j), acc(1, j), acc(2, j), acc(3, j), acc(4, j), acc(5, j)});
    }
    return s;
  }
  throw std::logic_error("evaluate: point too close to the irregular node");
}

Stencil limit_mask(const GhostedMesh& g, int node) {
  const auto& ring = g.rings.ring[node];
  const int V = static_cast<int>(ring.size());
  const double chi = 1.0 / (V + 3.0 / (8.0 * loop_omega(V)));
  Stencil s;
  s.push_back(ShapeRow{node, 1 - V * chi});
  for (int j : ring) s.push_back(ShapeRow{j, chi});
  return s;
}

}  // namespace slender::shell
