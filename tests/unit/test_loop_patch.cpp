// Loop subdivision surfaces (docs/models.md §6.6): the box-spline identities, the
// irregular-element evaluation by local subdivision, limit masks, planarity and the
// continuity of position and normal across element edges; meshes and ghosts (§6.7).
#ifdef SLENDER_HAVE_SHELL
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <map>
#include <random>
#include <tuple>

#include "params.hpp"
#include "shell/loop_patch.hpp"
#include "shell/trimesh.hpp"

using namespace slender;
using namespace slender::shell;

namespace {
const double lat[12][2] = {{0, -1}, {-1, 0}, {1, -1}, {0, 0}, {-1, 1}, {2, -1},
                           {1, 0},  {0, 1},  {-1, 2}, {2, 0}, {1, 1},  {0, 2}};

Vec3 eval_x(const GhostedMesh& g, const Stencil& s, Vec3* a1 = nullptr, Vec3* a2 = nullptr) {
  Vec3 x = Vec3::Zero(), t1 = x, t2 = x;
  for (auto& r : s) {
    x += r.N * g.mesh.x[r.node];
    t1 += r.Nv * g.mesh.x[r.node];
    t2 += r.Nw * g.mesh.x[r.node];
  }
  if (a1) *a1 = t1;
  if (a2) *a2 = t2;
  return x;
}
}  // namespace

TEST(BoxSplines, IdentitiesOfModels) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0, 1);
  for (int k = 0; k < 50; ++k) {
    double v = u(rng), w = u(rng);
    if (v + w > 1) {
      v = 1 - v;
      w = 1 - w;
    }
    auto N = box_splines(v, w);
    double s = 0, sv = 0, sw = 0, s2 = 0, lv = 0, lw = 0;
    for (int i = 0; i < 12; ++i) {
      EXPECT_GE(N[i].N, -1e-15);
      s += N[i].N;
      sv += N[i].Nv;
      sw += N[i].Nw;
      s2 += N[i].Nvv + N[i].Nvw + N[i].Nww;
      lv += N[i].N * lat[i][0];
      lw += N[i].N * lat[i][1];
    }
    EXPECT_NEAR(s, 1.0, 1e-14);
    EXPECT_NEAR(sv, 0.0, 1e-13);
    EXPECT_NEAR(sw, 0.0, 1e-13);
    EXPECT_NEAR(s2, 0.0, 1e-12);
    EXPECT_NEAR(lv, v, 1e-14);  // linear precision
    EXPECT_NEAR(lw, w, 1e-14);
    // derivatives against finite differences of the values
    const double h = 1e-6;
    auto Np = box_splines(v + h, w), Nm = box_splines(v - h, w);
    auto Nq = box_splines(v, w + h), Nr = box_splines(v, w - h);
    for (int i = 0; i < 12; ++i) {
      EXPECT_NEAR(N[i].Nv, (Np[i].N - Nm[i].N) / (2 * h), 1e-8);
      EXPECT_NEAR(N[i].Nw, (Nq[i].N - Nr[i].N) / (2 * h), 1e-8);
      EXPECT_NEAR(N[i].Nvv, (Np[i].Nv - Nm[i].Nv) / (2 * h), 1e-7);
      EXPECT_NEAR(N[i].Nvw, (Nq[i].Nv - Nr[i].Nv) / (2 * h), 1e-7);
      EXPECT_NEAR(N[i].Nww, (Nq[i].Nw - Nr[i].Nw) / (2 * h), 1e-7);
    }
  }
  // Loop's limit mask at the corners, and the centroid values of §6.6 (iii), (vi)
  auto N0 = box_splines(0, 0);
  EXPECT_NEAR(N0[3].N, 0.5, 1e-15);
  for (int i : {0, 1, 2, 4, 6, 7}) EXPECT_NEAR(N0[i].N, 1.0 / 12, 1e-15);
  auto N1 = box_splines(1, 0);
  EXPECT_NEAR(N1[6].N, 0.5, 1e-15);
  for (int i : {2, 3, 5, 7, 9, 10}) EXPECT_NEAR(N1[i].N, 1.0 / 12, 1e-15);
  auto Nc = box_splines(1.0 / 3, 1.0 / 3);
  for (int i : {3, 6, 7}) EXPECT_NEAR(Nc[i].N, 23.0 / 81, 1e-14);
  for (int i : {2, 4, 10}) EXPECT_NEAR(Nc[i].N, 7.0 / 162, 1e-14);
  for (int i : {0, 1, 5, 8, 9, 11}) EXPECT_NEAR(Nc[i].N, 1.0 / 324, 1e-14);
  // v <-> w symmetry (v)
  auto A = box_splines(0.2, 0.3), B = box_splines(0.3, 0.2);
  const int perm[12] = {1, 0, 4, 3, 2, 8, 7, 6, 5, 11, 10, 9};
  for (int i = 0; i < 12; ++i) EXPECT_NEAR(A[i].N, B[perm[i]].N, 1e-15);
}

TEST(TriMesh, GeneratorsAndGhosts) {
  TriMesh d = make_disc(1.0, 3);
  EXPECT_EQ(d.n_tris(), 6 * 64);
  GhostedMesh g = add_ghosts(d);
  EXPECT_EQ(static_cast<int>(g.boundary.size()), 48);
  EXPECT_EQ(static_cast<int>(g.ghosts.size()), 48);
  int v5 = 0;
  for (int i = 0; i < g.n_real_nodes; ++i) {
    EXPECT_TRUE(g.rings.closed[i]);
    if (g.valence[i] == 5)
      ++v5;
    else
      EXPECT_EQ(g.valence[i], 6);
  }
  EXPECT_EQ(v5, 6);  // the hexagon corners (§6.12)
  EXPECT_NO_THROW(check_patches(g));
  for (int b : g.boundary) EXPECT_NEAR(d.x[b].norm(), 1.0, 1e-12);
  // the ring, rectangle and sphere are valid patches too
  EXPECT_NO_THROW(check_patches(add_ghosts(make_ring(0.25, 1.0, 4, 24))));
  EXPECT_NO_THROW(check_patches(add_ghosts(make_rectangle(1.0, 0.5, 6, 3))));
  GhostedMesh s = add_ghosts(make_sphere(1.0, 2));
  EXPECT_TRUE(s.ghosts.empty());
  EXPECT_NO_THROW(check_patches(s));
  // a mesh whose triangles carry two irregular nodes is refused with advice
  TriMesh coarse;
  coarse.x = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  coarse.tri = {{0, 1, 2}};
  try {
    check_patches(add_ghosts(coarse));
    FAIL() << "expected an error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("refine"), std::string::npos);
  }
}

// A disc whose core is refined red-green (e-cone apex): the transition nodes become
// irregular (valence 5 or 7) but each stays alone in its triangles, the core edge is a
// quarter of the outer one after two levels, no triangle degenerates, and Loop's limit
// surface of a tilted planar control net stays on that plane everywhere.
TEST(TriMesh, DiscWithRefinedCore) {
  TriMesh d = make_disc(1.0, 3, 0.5, 2);
  GhostedMesh g = add_ghosts(d);
  EXPECT_NO_THROW(check_patches(g));
  std::map<int, int> valences;
  for (int i = 0; i < g.n_real_nodes; ++i)
    if (d.x[i].norm() < 0.99) ++valences[g.valence[i]];
  for (auto [v, n] : valences) EXPECT_TRUE(v >= 5 && v <= 7) << "valence " << v << " x" << n;
  EXPECT_GT(valences[7], 0);
  double core = 0, outer = 0, min_angle = M_PI;
  int nc = 0, no = 0;
  for (const Tri& t : d.tri) {
    const Vec3 c = (d.x[t[0]] + d.x[t[1]] + d.x[t[2]]) / 3;
    const double e = (d.x[t[0]] - d.x[t[1]]).norm();
    if (c.norm() < 0.15) core += e, ++nc;
    if (c.norm() > 0.8) outer += e, ++no;
    for (int k = 0; k < 3; ++k) {
      const Vec3 a = d.x[t[(k + 1) % 3]] - d.x[t[k]], b = d.x[t[(k + 2) % 3]] - d.x[t[k]];
      min_angle = std::min(min_angle, std::acos(a.dot(b) / (a.norm() * b.norm())));
    }
  }
  EXPECT_NEAR((core / nc) / (outer / no), 0.25, 0.05);
  EXPECT_GT(min_angle, 15 * M_PI / 180);
  for (auto& x : d.x) x.z() = 0.3 * x.x() - 0.2 * x.y() + 0.1;
  GhostedMesh gp = add_ghosts(d);
  for (int t = 0; t < gp.n_real_tris; ++t) {
    const Vec3 x = eval_x(gp, evaluate(gp, oriented_element(gp, t), 0.2, 0.3));
    EXPECT_NEAR(x.z(), 0.3 * x.x() - 0.2 * x.y() + 0.1, 1e-12);
  }
  EXPECT_THROW(make_disc(1.0, 3, 1.5, 1), InputError);
  EXPECT_THROW(make_disc(1.0, 1, 0.5, 1), InputError);
}

TEST(TriMesh, ObjAndOffRoundTrip) {
  TriMesh m = make_ring(0.3, 1.0, 3, 12);
  for (const char* f : {"loop_test.obj", "loop_test.off"}) {
    write_mesh(f, m);
    TriMesh r = read_mesh(f);
    ASSERT_EQ(r.n_nodes(), m.n_nodes());
    ASSERT_EQ(r.n_tris(), m.n_tris());
    for (int i = 0; i < m.n_nodes(); ++i) EXPECT_NEAR((r.x[i] - m.x[i]).norm(), 0, 1e-15);
    for (int t = 0; t < m.n_tris(); ++t) EXPECT_EQ(r.tri[t], m.tri[t]);
    std::remove(f);
  }
  EXPECT_THROW(read_mesh("does_not_exist.obj"), InputError);
}

// Every element, regular or not: partition of unity, planar control nets give
// planar limit surfaces, and at an irregular node the limit equals Loop's mask.
TEST(LoopPatch, IrregularElementsByLocalSubdivision) {
  TriMesh d = make_disc(1.0, 3);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-0.02, 0.02);
  for (auto& x : d.x) x += Vec3(u(rng), u(rng), 0);
  for (auto& x : d.x) x.z() = 0.3 * x.x() - 0.2 * x.y() + 0.1;  // a tilted plane
  GhostedMesh g = add_ghosts(d);
  int irregular = 0;
  for (int t = 0; t < g.n_real_tris; ++t) {
    Tri c = oriented_element(g, t);
    if (g.valence[c[0]] != 6) ++irregular;
    for (auto [v, w] :
         {std::pair{1.0 / 6, 1.0 / 6}, {2.0 / 3, 1.0 / 6}, {0.1, 0.05}, {0.45, 0.5}}) {
      Stencil s = evaluate(g, c, v, w);
      double sum = 0, sv = 0;
      for (auto& r : s) {
        sum += r.N;
        sv += r.Nv + r.Nw + r.Nvv + r.Nvw + r.Nww;
      }
      EXPECT_NEAR(sum, 1.0, 1e-12);
      EXPECT_NEAR(sv, 0.0, 1e-9);
      Vec3 x = eval_x(g, s);
      EXPECT_NEAR(x.z(), 0.3 * x.x() - 0.2 * x.y() + 0.1, 1e-12);
    }
  }
  EXPECT_EQ(irregular, 6 * 2);  // two boundary elements touch each hexagon corner

  // limit mask at an irregular node, approached from inside its element
  TriMesh s = make_sphere(1.0, 1);
  GhostedMesh gs = add_ghosts(s);
  for (int t = 0; t < gs.n_real_tris; ++t) {
    Tri c = oriented_element(gs, t);
    if (gs.valence[c[0]] == 6) continue;
    Vec3 near = eval_x(gs, evaluate(gs, c, 1e-7, 1e-7));
    Vec3 lim = eval_x(gs, limit_mask(gs, c[0]));
    EXPECT_LT((near - lim).norm(), 1e-5);
  }
}

// Position and normal agree on both sides of every interior edge (C1 surface).
TEST(LoopPatch, TangentPlaneContinuousAcrossEdges) {
  TriMesh m = make_sphere(1.0, 2);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.05, 0.05);
  for (auto& x : m.x) x += Vec3(u(rng), u(rng), u(rng));
  GhostedMesh g = add_ghosts(m);
  // parameters of the corners of an oriented element
  const double P[3][2] = {{0, 0}, {1, 0}, {0, 1}};
  std::map<std::tuple<int, int, int>, std::vector<std::pair<Vec3, Vec3>>> seen;
  double worst_x = 0, worst_n = 0;
  for (int t = 0; t < g.n_real_tris; ++t) {
    Tri c = oriented_element(g, t);
    for (int k = 0; k < 3; ++k) {
      const int a = c[k], b = c[(k + 1) % 3];
      for (double s : {0.3, 0.5}) {
        // the same physical point from both sides: s measured from the smaller id
        const double f = a < b ? s : 1 - s;
        const double v = (1 - f) * P[k][0] + f * P[(k + 1) % 3][0];
        const double w = (1 - f) * P[k][1] + f * P[(k + 1) % 3][1];
        Vec3 a1, a2;
        Vec3 x = eval_x(g, evaluate(g, c, v, w), &a1, &a2);
        Vec3 n = a1.cross(a2).normalized();
        auto& list = seen[{std::min(a, b), std::max(a, b), static_cast<int>(10 * s)}];
        for (auto& [x2, n2] : list) {
          worst_x = std::max(worst_x, (x - x2).norm());
          worst_n = std::max(worst_n, (n - n2).norm());
        }
        list.push_back({x, n});
      }
    }
  }
  std::printf("largest jump across edges: position %.3g, normal %.3g\n", worst_x, worst_n);
  EXPECT_LT(worst_x, 1e-12);
  EXPECT_LT(worst_n, 1e-10);
}

#endif
