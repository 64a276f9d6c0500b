// Shell self-contact (docs/models.md §6.10): closest points of triangles, forces as the
// gradient of the contact energy, two shells pressed together never interpenetrate,
// a flat shell is not repelled by its own neighbours, a folded shell is.
#ifdef SLENDER_HAVE_SHELL
#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "helpers.hpp"
#include "shell/surface.hpp"
#include "shell/triangle_distance.hpp"
#include "shell/trimesh.hpp"

using namespace slender;
using namespace slender::test;

namespace {
shell::TriMesh two_plates(double gap, int n) {
  shell::TriMesh a = shell::make_rectangle(1.0, 1.0, n, n), b = a;
  const int off = a.n_nodes();
  for (auto& x : b.x) {
    x.z() = gap;
    a.x.push_back(x);
  }
  for (auto t : b.tri) a.tri.push_back({t[0] + off, t[1] + off, t[2] + off});
  return a;
}
// A plate resting on a clamped one at `gap`, with the Koiter shell and the contact pair
// (`contact` adds to mesh and thickness); the top plate's nodes go to group "top".
std::unique_ptr<Simulation> plate_on_plate(int n, double gap, RawParams contact) {
  auto sim = std::make_unique<Simulation>(3, 1);
  sim->verbose = false;
  const double h = 0.02;
  shell::add_surface(*sim, "s", two_plates(1.0, n), 0.0);
  std::vector<int> top, bottom;
  for (int i : sim->group("s")) (sim->nodes().x[i].z() > 0.5 ? top : bottom).push_back(i);
  for (int i : top) sim->nodes().x[i].z() = gap;
  sim->add_shell(
      "koiter",
      P({{"mesh", std::string("s")}, {"thickness", h}, {"boundary", std::string("mirror")}}));
  contact["mesh"] = std::string("s");
  contact["thickness"] = h;
  sim->add_pair("contact/shell", contact);
  sim->set_group("top", top);
  sim->set_group("bottom", bottom);
  sim->add_fix("hold", "clamp", P({{"group", std::string("bottom")}}));
  return sim;
}
}  // namespace

TEST(ShellContact, TriangleDistance) {
  std::array<Vec3, 3> A{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  // a point above the face, beyond an edge, beyond a vertex
  auto w = shell::closest_on_triangle(Vec3(0.2, 0.3, 1), A[0], A[1], A[2]);
  EXPECT_NEAR(w[1], 0.2, 1e-15);
  EXPECT_NEAR(w[2], 0.3, 1e-15);
  w = shell::closest_on_triangle(Vec3(0.5, -1, 0.3), A[0], A[1], A[2]);
  EXPECT_NEAR(w[1], 0.5, 1e-15);
  EXPECT_NEAR(w[2], 0.0, 1e-15);
  w = shell::closest_on_triangle(Vec3(2, 2, 0), A[0], A[1], A[2]);
  EXPECT_NEAR(w[1], 0.5, 1e-15);
  EXPECT_NEAR(w[2], 0.5, 1e-15);
  // crossed edges above each other: edge-edge distance
  std::array<Vec3, 3> B{Vec3(0.5, -0.5, 0.2), Vec3(0.5, 0.5, 0.2), Vec3(2, 0, 0.2)};
  auto tp = shell::triangle_distance(A, B);
  EXPECT_NEAR(tp.dist, 0.2, 1e-12);
  // against brute-force sampling of both triangles
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int k = 0; k < 20; ++k) {
    std::array<Vec3, 3> P, Q;
    for (auto& p : P) p = Vec3(u(rng), u(rng), u(rng));
    for (auto& q : Q) q = Vec3(u(rng), u(rng), u(rng)) + Vec3(0, 0, 2.5);
    auto r = shell::triangle_distance(P, Q);
    double brute = 1e300;
    const int S = 40;
    for (int i = 0; i <= S; ++i)
      for (int j = 0; i + j <= S; ++j) {
        const Vec3 p = P[0] + (double(i) / S) * (P[1] - P[0]) + (double(j) / S) * (P[2] - P[0]);
        auto wq = shell::closest_on_triangle(p, Q[0], Q[1], Q[2]);
        brute = std::min(brute, (p - (wq[0] * Q[0] + wq[1] * Q[1] + wq[2] * Q[2])).norm());
      }
    EXPECT_LE(r.dist, brute + 1e-12);
    EXPECT_GT(r.dist, brute - 0.05);
  }
}

namespace {
// Two plates 1 apart in the reference with the contact alone (h = 0.02, k = 3); the test
// brings them within h.
std::unique_ptr<Simulation> contact_plates(const std::string& dense) {
  auto sim = std::make_unique<Simulation>(3, 1);
  sim->verbose = false;
  shell::add_surface(*sim, "s", two_plates(1.0, 2), 0.0);
  sim->add_pair("contact/shell",
                P({{"mesh", std::string("s")}, {"thickness", 0.02}, {"k", 3.0}, {"dense", dense}}));
  return sim;
}
}  // namespace

TEST(ShellContact, ForcesAreTheGradientOfTheContactEnergy) {
  for (std::string dense : {"closest", "all"}) {
    // far apart in the reference, brought within h now
    auto sim = contact_plates(dense);
    std::mt19937 rng(9);
    std::uniform_real_distribution<double> u(-0.003, 0.003);
    for (auto& x : sim->nodes().x) {
      if (x.z() > 0.5) x.z() -= 1.0 - 0.012;
      x += Vec3(u(rng), u(rng), u(rng));
    }
    sim->compute_forces();
    EXPECT_GT(sim->find_style("contact/shell")->value("contacts"), 0);
    EXPECT_GT(sim->potential_energy(), 0);
    EXPECT_LT(fd_force_error(*sim, 1e-8), 1e-5) << dense;
  }
}

// The Hessian (docs/models.md §9.9) against central differences of the forces: the top
// plate turned about z (no parallel edges) and tilted, its nodes jiggled, within h of the
// bottom one: vertex-face, vertex-edge and edge-edge contacts, both dense modes.
TEST(ShellContact, HessianMatchesFiniteDifferencesOfTheForces) {
  for (std::string dense : {"closest", "all"}) {
    auto sim = contact_plates(dense);
    std::mt19937 rng(4);
    std::uniform_real_distribution<double> u(-0.002, 0.002);
    const Eigen::Matrix3d turn = Eigen::AngleAxisd(0.3, Vec3::UnitZ()).toRotationMatrix();
    for (auto& x : sim->nodes().x) {
      if (x.z() > 0.5) {
        x = turn * (x - Vec3(0.5, 0.5, 1.0)) + Vec3(0.5, 0.5, 0.013);
        x.z() += 0.004 * (x.x() - 0.5);
      }
      x += Vec3(u(rng), u(rng), u(rng));
    }
    sim->compute_forces();
    EXPECT_GT(sim->find_style("contact/shell")->value("contacts"), 2) << dense;
    EXPECT_LT(fd_hessian_error(*sim, 1e-8), 1e-5) << dense;
  }
}

TEST(ShellContact, FlatShellIsNotRepelledByItsNeighbours) {
  auto sim = std::make_unique<Simulation>(3, 1);
  sim->verbose = false;
  // edges (~0.06) shorter than the thickness: near neighbours exist
  shell::add_surface(*sim, "s", shell::make_disc(1.0, 4), 1e-3);
  sim->add_pair("contact/shell", P({{"mesh", std::string("s")}, {"thickness", 0.1}}));
  sim->compute_forces();
  EXPECT_EQ(sim->find_style("contact/shell")->value("contacts"), 0);
  EXPECT_GT(sim->find_style("contact/shell")->value("pairs"), 0);
  EXPECT_EQ(sim->max_force(), 0.0);
}

namespace {
// Folds a strip lying on 0 <= x <= 2 flat onto itself round a half cylinder of radius
// gap / 2 at x = 1: the two halves, far apart along the surface, lie gap apart.
void fold_at_x1(Simulation& sim, double gap) {
  const double R = gap / 2;
  for (auto& x : sim.nodes().x) {
    const double s = x.x() - 1.0;
    if (s <= 0) {
      x.z() = 0;
    } else if (s < M_PI * R) {
      x = Vec3(1.0 + R * std::sin(s / R), x.y(), R * (1 - std::cos(s / R)));
    } else {
      x = Vec3(1.0 - (s - M_PI * R), x.y(), gap);
    }
  }
}
}  // namespace

TEST(ShellContact, FoldedShellIsRepelled) {
  // a strip folded flat on itself: the two halves, far apart along the surface, touch
  auto sim = std::make_unique<Simulation>(3, 1);
  sim->verbose = false;
  shell::add_surface(*sim, "s", shell::make_rectangle(2.0, 0.5, 16, 4), 0.0);
  sim->add_pair("contact/shell", P({{"mesh", std::string("s")}, {"thickness", 0.05}}));
  const double gap = 0.03;
  fold_at_x1(*sim, gap);
  sim->compute_forces();
  EXPECT_GT(sim->find_style("contact/shell")->value("contacts"), 10);
  double fz_top = 0, fz_bottom = 0;
  Vec3 total = Vec3::Zero();
  for (int i : sim->group("s")) {
    const Vec3& x = sim->nodes().x[i];
    total += sim->nodes().f[i];
    if (x.x() > 0.9) continue;  // away from the fold
    (x.z() > gap / 2 ? fz_top : fz_bottom) += sim->nodes().f[i].z();
  }
  EXPECT_GT(fz_top, 0);  // the halves are pushed apart
  EXPECT_LT(fz_bottom, 0);
  EXPECT_LT(total.norm(), 1e-9 * fz_top);  // action = reaction
}

TEST(ShellContact, NearNeighboursTouchAcrossARidgeOrNever) {
  // the folded strip again, with near neighbours out to 0.3 in the reference: the layers
  // next to the fold are near neighbours with opposed normals, so "ridge" lets them touch
  // and "never" does not, while the layers farther from the fold touch either way
  double contacts[2], fold_force[2];
  for (int k = 0; k < 2; ++k) {
    auto sim = std::make_unique<Simulation>(3, 1);
    sim->verbose = false;
    shell::add_surface(*sim, "s", shell::make_rectangle(2.0, 0.5, 16, 4), 0.0);
    sim->add_pair("contact/shell", P({{"mesh", std::string("s")},
                                      {"thickness", 0.05},
                                      {"near_distance", 0.3},
                                      {"near_contact", std::string(k ? "never" : "ridge")}}));
    fold_at_x1(*sim, 0.03);
    sim->compute_forces();
    contacts[k] = sim->find_style("contact/shell")->value("contacts");
    fold_force[k] = 0;
    for (int i : sim->group("s")) {
      const Vec3& x = sim->nodes().x[i];
      if (x.x() > 0.9 && x.z() < 0.01) fold_force[k] += sim->nodes().f[i].norm();
    }
  }
  EXPECT_GT(fold_force[0], 0.0);
  EXPECT_EQ(fold_force[1], 0.0);  // the bottom layer next to the fold: only near pairs
  EXPECT_GT(contacts[1], 10);     // the halves still touch away from the fold
  EXPECT_LT(contacts[1], contacts[0]);
}

TEST(ShellContact, PressedShellsNeverInterpenetrate) {
  for (auto [speed, dense] :
       {std::pair{0.5, "closest"}, {5.0, "closest"}, {20.0, "closest"}, {20.0, "all"}}) {
    auto sim = std::make_unique<Simulation>(3, 1);
    sim->verbose = false;
    const double h = 0.02;
    shell::add_surface(*sim, "s", two_plates(0.05, 6), 0.0);
    sim->add_shell(
        "koiter",
        P({{"mesh", std::string("s")}, {"thickness", h}, {"boundary", std::string("mirror")}}));
    sim->add_pair("contact/shell",
                  P({{"mesh", std::string("s")}, {"thickness", h}, {"dense", dense}}));
    std::vector<int> top, bottom;
    for (int i : sim->group("s")) (sim->nodes().x[i].z() > 0.025 ? top : bottom).push_back(i);
    for (int i : top) sim->nodes().v[i] = Vec3(0, 0, -speed);
    sim->set_group("bottom", bottom);
    sim->add_fix("hold", "clamp", P({{"group", std::string("bottom")}}));
    sim->set_integrator("newmark", P({{"gamma", 0.5}}));
    double zmin = 1e300;
    const long steps = std::lround(0.1 / speed / sim->suggest_dt(0.5)) + 2000;
    sim->run(RunOptions{steps, 1, [&](Simulation& s) {
                          for (int i : top) zmin = std::min(zmin, s.nodes().x[i].z());
                          return false;
                        }});
    std::printf("speed %.1f: closest approach %.4f (h = %.2f), %ld steps\n", speed, zmin, h, steps);
    EXPECT_GT(zmin, 0.0);
    EXPECT_LT(zmin, h);  // they did touch
    double vz = 0;
    for (int i : top) vz += sim->nodes().v[i].z();
    EXPECT_GT(vz, 0);  // and bounced
  }
}

// Static friction (S-2): a plate pressed onto another with a tangential push below
// mu_s times the normal load is held; above it slides away. Both dense phases: friction
// acts once per triangle pair on the sum of its normal forces.
TEST(ShellContact, StaticFrictionHoldsBelowMuTimesTheLoad) {
  auto slide = [](double ratio, const std::string& dense, double mu) {
    const double h = 0.02;  // the top plate just touches the bottom one
    auto sim = plate_on_plate(4, 0.95 * h,
                              P({{"mu_static", mu}, {"mu_dynamic", 0.9 * mu}, {"dense", dense}}));
    const std::vector<int> top = sim->group("top");
    const double fz = -0.5;
    sim->add_fix(
        "push", "force/constant",
        P({{"group", std::string("top")}, {"force", std::vector<double>{-ratio * fz, 0, fz}}}));
    sim->set_integrator("newmark", P({{"gamma", 1.0}, {"damping", 20.0}}));
    // after settling, how far the top plate moves in the same time again
    auto mean_x = [&] {
      double x = 0;
      for (int i : top) x += sim->nodes().x[i].x();
      return x / top.size();
    };
    sim->run(RunOptions{3000, 0, nullptr});
    const double x0 = mean_x();
    sim->run(RunOptions{3000, 0, nullptr});
    return mean_x() - x0;
  };
  const double mu = 0.5;
  for (std::string dense : {"closest", "all"}) {
    const double stick = slide(0.6 * mu, dense, mu), slip = slide(1.4 * mu, dense, mu);
    std::printf(
        "dense = %s, mu = %g: tangential creep after settling: %.3g at T/N = 0.6 mu, "
        "%.3g at 1.4 mu\n",
        dense.c_str(), mu, stick, slip);
    // (measured 0.027 against 11.9 (closest) and 0.0099 against 4.9 (all): contacts with
    // little normal force slip and re-stick, so a held plate still creeps slowly; a
    // sliding one runs away)
    EXPECT_GT(slip, 300 * std::abs(stick)) << dense;
    EXPECT_GT(slip, 1.0) << dense;
  }
}

// Pass 1 (screening and feature pairs) runs on the requested threads at any scene size;
// pass 2 applies forces, energies and friction in list order, so two threads give the
// serial trajectory bit for bit, friction history included.
TEST(ShellContact, ScreeningOnThreadsGivesTheSerialTrajectory) {
  for (std::string dense : {"closest", "all"}) {
    auto run = [&](int threads, double* energy, double* contacts) {
      const double h = 0.02;
      auto sim = plate_on_plate(16, 0.9 * h, P({{"mu_static", 0.5}, {"dense", dense}}));
      sim->set_threads(threads);
      sim->add_fix(
          "push", "force/constant",
          P({{"group", std::string("top")}, {"force", std::vector<double>{0.1, 0, -1.0}}}));
      sim->set_integrator("newmark", P({{"gamma", 1.0}, {"damping", 20.0}}));
      sim->run(RunOptions{40, 0, nullptr});
      *energy = sim->potential_energy();
      *contacts = sim->find_style("contact/shell")->value("contacts");
      EXPECT_GT(sim->find_style("contact/shell")->value("pairs"), 1000) << dense;
      return sim->nodes().x;
    };
    double e1 = 0, e2 = 0, c1 = 0, c2 = 0;
    const auto x1 = run(1, &e1, &c1);
    const auto x2 = run(2, &e2, &c2);
    std::printf("dense = %s: %g contacts\n", dense.c_str(), c1);
    EXPECT_GT(c1, 100) << dense;
    EXPECT_EQ(c1, c2) << dense;
    EXPECT_EQ(e1, e2) << dense;
    ASSERT_EQ(x1.size(), x2.size());
    for (std::size_t i = 0; i < x1.size(); ++i) ASSERT_EQ(x1[i], x2[i]) << dense << " node " << i;
  }
}

#ifdef SLENDER_HAVE_HDF5
// The friction history goes into checkpoints: a restarted frictional contact continues
// bit-identically.
// A fresh scene that has not run yet reads a checkpoint of the same deck: the mirror
// ghosts' dof_mask, which the shell creates when it first binds, must not make the
// scenes look different (it did: "checkpoint has node property 'dof_mask' that this
// scene does not use").
TEST(ShellContact, AFreshSceneReadsTheCheckpointOfARunOne) {
  auto make = [] {
    auto sim = std::make_unique<Simulation>(3, 1);
    sim->verbose = false;
    shell::add_surface(*sim, "d", shell::make_disc(1.0, 2), 1e-3);
    sim->add_shell(
        "koiter",
        P({{"mesh", std::string("d")}, {"thickness", 0.05}, {"boundary", std::string("mirror")}}));
    sim->add_fix("push", "force/constant",
                 P({{"group", std::string("d")}, {"force", std::vector<double>{0, 0, 0.1}}}));
    sim->set_integrator("verlet", P({{"dt", 1e-4}}));
    return sim;
  };
  auto a = make();
  a->run(RunOptions{20, 0, nullptr});
  a->write_checkpoint("shell_fresh_restart.h5");
  a->run(RunOptions{30, 0, nullptr});
  auto b = make();
  b->read_checkpoint("shell_fresh_restart.h5");
  b->run(RunOptions{30, 0, nullptr});
  for (std::size_t i = 0; i < a->nodes().size(); ++i) EXPECT_EQ(a->nodes().x[i], b->nodes().x[i]);
  std::remove("shell_fresh_restart.h5");
}

// The automatic step comes from the shell's largest frequency, estimated once on the
// configuration of the first run. A fresh scene reading a checkpoint must take the
// estimate from the checkpoint, not re-estimate it on the restart configuration, or the
// continued run takes another step (the e-cone ramps resumed 1e-6 away from their
// uninterrupted runs).
TEST(ShellContact, AFreshSceneKeepsTheAutomaticStepOfTheRunItContinues) {
  auto make = [] {
    auto sim = std::make_unique<Simulation>(3, 1);
    sim->verbose = false;
    shell::add_surface(*sim, "d", shell::make_disc(1.0, 2), 1e-3);
    sim->add_growth("g", "econe", P({{"phi_e", 0.0}}));
    sim->add_shell("koiter", P({{"mesh", std::string("d")},
                                {"thickness", 0.05},
                                {"growth", std::string("g")},
                                {"boundary", std::string("mirror")}}));
    sim->set_integrator("verlet", P({}));
    return sim;
  };
  // as the e-cone deck does: the growth changes between runs
  auto grow = [](Simulation& sim, double phi) {
    RawParams p;
    p["phi_e"] = phi;
    sim.find_style("g")->modify(p);
    sim.forces_valid = false;
  };
  auto a = make();
  grow(*a, 1.0);
  a->run(RunOptions{50, 0, nullptr});
  grow(*a, 3.0);
  a->run(RunOptions{400, 0, nullptr});
  a->write_checkpoint("shell_auto_dt_restart.h5");
  a->run(RunOptions{30, 0, nullptr});
  auto b = make();
  b->read_checkpoint("shell_auto_dt_restart.h5");
  grow(*b, 3.0);
  b->run(RunOptions{30, 0, nullptr});
  EXPECT_EQ(a->dt, b->dt);
  for (std::size_t i = 0; i < a->nodes().size(); ++i) EXPECT_EQ(a->nodes().x[i], b->nodes().x[i]);
  std::remove("shell_auto_dt_restart.h5");
}

TEST(ShellContact, FrictionHistoryRestartsBitIdentically) {
  for (std::string dense : {"closest", "all"}) {
    auto sim = plate_on_plate(3, 0.8 * 0.02, P({{"mu_static", 0.5}, {"dense", dense}}));
    sim->add_fix("push", "force/constant",
                 P({{"group", std::string("top")}, {"force", std::vector<double>{0.1, 0, -0.5}}}));
    sim->set_integrator("verlet", P({{"dt", 1e-4}}));
    sim->run(RunOptions{500, 0, nullptr});
    sim->write_checkpoint("shell_friction_restart.h5");
    sim->run(RunOptions{300, 0, nullptr});
    const std::vector<Vec3> first = sim->nodes().x;
    sim->read_checkpoint("shell_friction_restart.h5");
    sim->run(RunOptions{300, 0, nullptr});
    for (std::size_t i = 0; i < first.size(); ++i)
      EXPECT_EQ(first[i], sim->nodes().x[i]) << dense << " " << i;
    std::remove("shell_friction_restart.h5");
  }
}

TEST(ShellContact, ADamagedFrictionHistoryIsRefusedNotIndexed) {
  auto sim = plate_on_plate(3, 0.8 * 0.02, P({{"mu_static", 0.5}}));
  Style* pair = sim->find_style("contact/shell");
  ASSERT_NE(pair, nullptr);
  const double nan = std::nan("");
  for (const std::vector<double>& bad :
       {std::vector<double>{0, 1e6, 0, 0, 0, 1}, std::vector<double>{-7, 2, 0, 0, 0, 1},
        std::vector<double>{2, 1, 0, 0, 0, 1}, std::vector<double>{0.5, 2, 0, 0, 0, 1},
        std::vector<double>{1, 2, nan, 0, 0, 1}}) {
    StateMap st;
    st["friction"] = bad;
    pair->load_state(st);
    EXPECT_NE(pair->check_loaded(sim->context()).find("friction pair 1"), std::string::npos);
  }
  StateMap good;
  good["friction"] = {1, 2, 0.001, 0, 0, 1};
  pair->load_state(good);
  EXPECT_EQ(pair->check_loaded(sim->context()), "");
}
#endif

#endif
