// Threads (src/threads.hpp): the threaded kernels give the serial forces up to rounding,
// a run is bit-identical to itself for a thread count, and the per-thread buffers are
// reduced and cleared (a missed reduction or a stale buffer would change the forces).
// Covers the threaded paths of contact/segment, contact/node-edge, spring, rod/straight,
// rod/cosserat, bend2d, bend2d/hysteresis, wall/sphere and wall/circle, damping/viscous
// and verlet.
#include <cmath>
#include <cstdio>
#include <random>

#include "helpers.hpp"
#include "threads.hpp"

using namespace slender;
using namespace slender::test;

namespace {
// A helix of n nodes (spacing ~1) whose turns press on each other (pitch 0.95 against a
// contact distance 2a = 1), its ends inside a frictional sphere that they touch, with
// random velocities so that the friction and the dashpots act: thousands of segment
// contacts, enough work items for every kernel to run on two threads.
std::unique_ptr<Simulation> packed_helix(int threads, double mu = 0.3, int n = 3000) {
  auto sim = std::make_unique<Simulation>(3, 7);
  sim->verbose = false;
  sim->set_threads(threads);
  sim->set_threads_min_nodes(0);  // the kernels on threads at any size
  const double r = 10.0, pitch = 0.95;
  const double turn = 2 * M_PI * r;
  std::vector<Vec3> pts;
  for (int i = 0; i < n; ++i) {
    const double phi = 2 * M_PI * i / turn;
    pts.emplace_back(r * std::cos(phi), r * std::sin(phi), pitch * phi / (2 * M_PI));
  }
  sim->add_chain("w", pts, 1.0, false);
  const double zmid = 0.5 * pts.back().z();
  sim->add_bond("spring", P({{"k", 1000.0}}));
  sim->add_bond("rod/straight", P({{"YI", 60.0}}));
  sim->add_pair(
      "contact/segment",
      P({{"radius", 0.5}, {"stiffness", 1e3}, {"damping", 5.0}, {"mu_static", mu}, {"skin", 0.3}}));
  sim->add_fix("wall", "wall/sphere",
               P({{"center", std::vector<double>{0, 0, zmid}},
                  {"radius", std::sqrt(r * r + zmid * zmid) + 0.3},
                  {"diameter", 1.0},
                  {"stiffness", 500.0},
                  {"exponent", 1.0},
                  {"mu_static", mu}}));
  std::mt19937 g(3);
  std::normal_distribution<double> u(0.0, 0.05);
  for (auto& v : sim->nodes().v) v = Vec3(u(g), u(g), u(g));
  sim->set_integrator("verlet", P({{"dt", 0.005}}));
  return sim;
}
// The 2D counterpart: an Archimedean spiral of n nodes whose turns press on each other
// (0.95 apart against a contact diameter 1), plastic in its inner turns, its outer turn
// on a frictional circular wall.
std::unique_ptr<Simulation> packed_spiral(int threads, int n = 3000) {
  auto sim = std::make_unique<Simulation>(2, 7);
  sim->verbose = false;
  sim->set_threads(threads);
  sim->set_threads_min_nodes(0);  // the kernels on threads at any size
  const double b = 0.95 / (2 * M_PI);
  double th = 3.0 / b, rmax = 0.0;
  std::vector<Vec3> pts;
  for (int i = 0; i < n; ++i) {
    const double r = b * th;
    pts.emplace_back(r * std::cos(th), r * std::sin(th), 0.0);
    rmax = r;
    th += 1.0 / std::sqrt(r * r + b * b);
  }
  sim->add_chain("w", pts, 1.0, false);
  sim->add_bond("spring", P({{"k", 1000.0}}));
  sim->add_bond("bend2d/hysteresis", P({{"k", 60.0}, {"yield_curvature", 0.1}}));
  sim->add_pair("contact/node-edge", P({{"diameter", 1.0},
                                        {"stiffness", 1e3},
                                        {"damping", 5.0},
                                        {"mu_static", 0.3},
                                        {"skin", 0.3}}));
  sim->add_fix("wall", "wall/circle",
               P({{"radius", rmax + 0.3},
                  {"diameter", 1.0},
                  {"stiffness", 500.0},
                  {"exponent", 1.0},
                  {"mu_static", 0.3}}));
  std::mt19937 g(3);
  std::normal_distribution<double> u(0.0, 0.05);
  for (auto& v : sim->nodes().v) v = Vec3(u(g), u(g), 0.0);
  sim->set_integrator("verlet", P({{"dt", 0.005}}));
  return sim;
}

// Forces, energies, contact counts and measured stiffness of two scenes agree.
void expect_same_evaluation(Simulation& one, Simulation& two, const char* pair) {
  one.compute_forces();
  two.compute_forces();
  const auto& f1 = one.nodes().f;
  const auto& f2 = two.nodes().f;
  double fmax = 0.0, worst = 0.0;
  for (std::size_t i = 0; i < f1.size(); ++i) {
    fmax = std::max(fmax, f1[i].cwiseAbs().maxCoeff());
    worst = std::max(worst, (f1[i] - f2[i]).cwiseAbs().maxCoeff());
  }
  ASSERT_GT(fmax, 1.0);
  EXPECT_LT(worst, 1e-12 * fmax);
  for (auto& [cat, e] : one.energies())
    EXPECT_NEAR(two.energies().at(cat), e, 1e-12 * std::max(1.0, std::abs(e))) << cat;
  EXPECT_GT(one.energies().at("contact"), 0.0);
  for (const char* id : {pair, "wall"}) {
    const double c1 = one.find_style(id)->value("contacts");
    EXPECT_GT(c1, 10) << id;
    EXPECT_EQ(c1, two.find_style(id)->value("contacts")) << id;
    const double w1 = one.find_style(id)->value("omega");
    EXPECT_GT(w1, 0.0) << id;
    EXPECT_NEAR(two.find_style(id)->value("omega"), w1, 1e-12 * w1) << id;
  }
}
}  // namespace

TEST(Threads, RangesCoverTheWorkOnceInOrder) {
  for (std::size_t n : {0u, 1u, 7u, 512u, 1001u})
    for (int T : {1, 2, 3, 8}) {
      std::size_t next = 0;
      for (int t = 0; t < T; ++t) {
        std::size_t b, e;
        thread_range(n, T, t, b, e);
        EXPECT_EQ(b, next);
        EXPECT_LE(b, e);
        next = e;
      }
      EXPECT_EQ(next, n);
    }
  // small kernels stay serial; large ones take every thread asked for
  EXPECT_EQ(threads_for(100, 2), 1);
  EXPECT_EQ(threads_for(100000, 2), 2);
  EXPECT_EQ(threads_for(100000, 1000), kMaxThreads);
  // light passes over the nodes take a thread per kMinLightItemsPerThread nodes: a chain of
  // 1 500 nodes runs them serially while its force kernels use two threads
  EXPECT_EQ(threads_for(1500, 2), 2);
  EXPECT_EQ(threads_for(1500, 2, kMinLightItemsPerThread), 1);
  EXPECT_EQ(threads_for(2 * kMinLightItemsPerThread - 1, 2, kMinLightItemsPerThread), 1);
  EXPECT_EQ(threads_for(2 * kMinLightItemsPerThread, 2, kMinLightItemsPerThread), 2);
  int used = 0;
  std::vector<int> seen(1500, 0);
  used = parallel_ranges(
      2, seen.size(),
      [&](int, std::size_t b, std::size_t e) {
        for (std::size_t i = b; i < e; ++i) ++seen[i];
      },
      kMinLightItemsPerThread);
  EXPECT_EQ(used, 1);
  for (int v : seen) EXPECT_EQ(v, 1);
}

TEST(Threads, ThreadCountIsValidated) {
  Simulation sim(3, 1);
  EXPECT_THROW(sim.set_threads(0), InputError);
  EXPECT_THROW(sim.set_threads(kMaxThreads + 1), InputError);
  sim.set_threads(2);
  EXPECT_EQ(sim.requested_threads(), 2);
  // a scene below threads_min_nodes runs on one thread, and takes the threads asked for
  // once it has grown to that size
  EXPECT_EQ(sim.threads(), 1);
  sim.set_threads_min_nodes(50);
  std::vector<Vec3> pts;
  for (int i = 0; i < 49; ++i) pts.emplace_back(i, 0, 0);
  sim.add_chain("w", pts, 1.0, false);
  EXPECT_EQ(sim.threads(), 1);
  sim.add_chain("v", {Vec3(0, 5, 0), Vec3(1, 5, 0)}, 1.0, false);
  EXPECT_EQ(sim.threads(), 2);
}

TEST(Threads, TwoThreadsGiveTheSerialForcesAndEnergies) {
  auto one = packed_helix(1), two = packed_helix(2);
  // twice: the second evaluation finds the buffers of the first cleared
  for (int pass = 0; pass < 2; ++pass) expect_same_evaluation(*one, *two, "contact/segment");
}

TEST(Threads, TwoThreadsGiveTheSerialForcesIn2D) {
  auto one = packed_spiral(1), two = packed_spiral(2);
  for (int pass = 0; pass < 2; ++pass) expect_same_evaluation(*one, *two, "contact/node-edge");
  // the inner turns flowed plastically, on both
  const double lost = one->find_style("bend2d/hysteresis")->value("dissipated");
  EXPECT_GT(lost, 0.0);
  EXPECT_NEAR(two->find_style("bend2d/hysteresis")->value("dissipated"), lost, 1e-12 * lost);
}

// The Cosserat rod turns frames on both sides of each vertex: on threads the even and
// the odd vertices go in two passes. Open and closed chains (a ring's closing vertex
// wraps around), frames perturbed so that every term acts.
TEST(Threads, CosseratRodGivesTheSerialForcesAndFrameForces) {
  for (bool closed : {false, true}) {
    std::unique_ptr<Simulation> sims[2];
    for (int k = 0; k < 2; ++k) {
      auto& sim = sims[k];
      sim = std::make_unique<Simulation>(3, 1);
      sim->verbose = false;
      sim->set_threads(k + 1);
      sim->set_threads_min_nodes(0);  // the kernels on threads at any size
      const int n = 2001;
      std::vector<Vec3> pts;
      for (int i = 0; i < n; ++i) {
        const double phi = 2 * M_PI * i / n;
        pts.emplace_back(300 * std::cos(phi), 300 * std::sin(phi), 0.1 * std::sin(7 * phi));
      }
      sim->add_chain("r", pts, 1.0, closed);
      sim->add_bond("rod/cosserat", P({{"YI", 2.0},
                                       {"GJ", 1.5},
                                       {"coupling", 200.0},
                                       {"rot_inertia", 0.5},
                                       {"rest_curvature", std::vector<double>{0, 0.1, 0.02}},
                                       {"rot_damping", 0.1}}));
      sim->compute_forces();  // binds the frames
      auto& q = sim->coordinates("rod.q").q->values();
      std::mt19937 g(4);
      std::normal_distribution<double> u(0, 0.1);
      for (auto& qi : q) qi = (qi + Vec4(u(g), u(g), u(g), u(g))).normalized();
      for (auto& v : sim->coordinates("rod.q").v->values()) v = Vec4(u(g), u(g), u(g), u(g));
    }
    double fmax = 0.0, qmax = 0.0, worst = 0.0;
    for (int pass = 0; pass < 2; ++pass) {
      sims[0]->compute_forces();
      sims[1]->compute_forces();
      const auto& f0 = sims[0]->nodes().f;
      const auto& f1 = sims[1]->nodes().f;
      const auto& g0 = sims[0]->coordinates("rod.q").f->values();
      const auto& g1 = sims[1]->coordinates("rod.q").f->values();
      for (size_t i = 0; i < f0.size(); ++i) {
        fmax = std::max(fmax, f0[i].cwiseAbs().maxCoeff());
        qmax = std::max(qmax, g0[i].cwiseAbs().maxCoeff());
        worst = std::max(worst, (f0[i] - f1[i]).cwiseAbs().maxCoeff() / std::max(fmax, 1e-300));
        worst = std::max(worst, (g0[i] - g1[i]).cwiseAbs().maxCoeff() / std::max(qmax, 1e-300));
      }
    }
    EXPECT_GT(fmax, 1.0);
    EXPECT_GT(qmax, 1.0);
    EXPECT_LT(worst, 1e-12) << (closed ? "closed" : "open");
    for (auto& [cat, e] : sims[0]->energies())
      EXPECT_NEAR(sims[1]->energies().at(cat), e, 1e-12 * std::max(1.0, std::abs(e))) << cat;
    EXPECT_GT(sims[0]->energies().at("twist"), 0.0);
    EXPECT_EQ(sims[0]->bonds()[0]->value("misalignment"),
              sims[1]->bonds()[0]->value("misalignment"));
  }
}

TEST(Threads, ARunIsBitIdenticalForTheSameThreadCount) {
  for (int dim : {3, 2}) {
    auto a = dim == 3 ? packed_helix(2) : packed_spiral(2);
    auto b = dim == 3 ? packed_helix(2) : packed_spiral(2);
    for (auto* sim : {a.get(), b.get()}) sim->run(RunOptions{100, 0, nullptr});
    for (std::size_t i = 0; i < a->nodes().size(); ++i)
      for (int c = 0; c < 3; ++c) {
        ASSERT_EQ(a->nodes().x[i][c], b->nodes().x[i][c]) << dim << "D node " << i;
        ASSERT_EQ(a->nodes().v[i][c], b->nodes().v[i][c]) << dim << "D node " << i;
      }
    const char* pair = dim == 3 ? "contact/segment" : "contact/node-edge";
    EXPECT_GT(a->find_style(pair)->value("contacts"), 10);
    if (dim == 2) {
      EXPECT_EQ(a->find_style("bend2d/hysteresis")->value("dissipated"),
                b->find_style("bend2d/hysteresis")->value("dissipated"));
    }
  }
}

TEST(Threads, ARunOnTwoThreadsFollowsTheSerialOne) {
  // The threads add forces in another order, so the runs part at rounding level; the
  // packed helix then amplifies that quickly (nearly parallel segments switch between
  // the closest-point formulas, stick/slip switches are discontinuous), so compare the
  // first steps, where the integrator's threaded loops must match the serial ones.
  auto s = packed_helix(1), t = packed_helix(2);
  for (auto* sim : {s.get(), t.get()}) sim->run(RunOptions{4, 0, nullptr});
  double worst = 0.0, moved = 0.0;
  for (std::size_t i = 0; i < s->nodes().size(); ++i) {
    worst = std::max(worst, (s->nodes().x[i] - t->nodes().x[i]).norm());
    worst = std::max(worst, 0.005 * (s->nodes().v[i] - t->nodes().v[i]).norm());
    moved = std::max(moved, s->nodes().v[i].norm());
  }
  EXPECT_LT(worst, 1e-13);
  EXPECT_GT(moved, 1e-2);
}

// Chain bonds on several threads write straight into the force array and defer only the
// contributions to nodes an earlier thread also touches (ChainForces): every node then
// receives its contributions in the serial order, so the forces are bit-identical to one
// thread — on open and closed chains (the seam of a closed chain is shared by the
// first and the last thread), with two and three threads; spring, bend2d, bend2d/hysteresis
// and rod/straight.
TEST(Threads, ChainBondsGiveTheSerialForcesBitForBit) {
  for (bool closed : {false, true})
    for (const char* bend : {"bend2d", "bend2d/hysteresis", "rod/straight"}) {
      const bool rod = std::string(bend) == "rod/straight";  // the 3D discrete elastic rod
      std::vector<std::unique_ptr<Simulation>> sims;
      for (int threads : {1, 2, 3}) {
        auto sim = std::make_unique<Simulation>(rod ? 3 : 2, 7);
        sim->verbose = false;
        sim->set_threads(threads);
        sim->set_threads_min_nodes(0);  // the kernels on threads at any size
        std::vector<Vec3> pts;
        const int n = 1500;  // >= 256 hinges per thread on three threads
        std::mt19937 g(5);
        std::uniform_real_distribution<double> u(-0.05, 0.05);
        for (int i = 0; i < n; ++i) {
          const double phi = 2 * M_PI * i / n;
          pts.emplace_back((240 + 3 * std::sin(7 * phi)) * std::cos(phi) + u(g),
                           (240 + 3 * std::sin(7 * phi)) * std::sin(phi) + u(g),
                           rod ? 2 * std::cos(5 * phi) + u(g) : 0.0);
        }
        sim->add_chain("w", pts, 1.0, closed);
        sim->add_bond("spring", P({{"k", 1000.0}}));
        if (rod)
          sim->add_bond(bend, P({{"YI", 60.0}}));
        else if (std::string(bend) == "bend2d")
          sim->add_bond(bend, P({{"k", 60.0}}));
        else  // plastic where the wiggles bend most
          sim->add_bond(bend, P({{"k", 60.0}, {"yield_curvature", 0.05}}));
        for (auto& v : sim->nodes().v) v = Vec3(u(g), u(g), rod ? u(g) : 0.0);
        sim->compute_forces();
        sims.push_back(std::move(sim));
      }
      const auto& f1 = sims[0]->nodes().f;
      ASSERT_GT(f1[0].norm() + f1[f1.size() / 2].norm(), 0.0);
      for (int t = 1; t < 3; ++t) {
        const auto& ft = sims[static_cast<std::size_t>(t)]->nodes().f;
        for (std::size_t i = 0; i < f1.size(); ++i)
          ASSERT_EQ(f1[i], ft[i]) << bend << (closed ? " closed" : " open") << ", " << t + 1
                                  << " threads, node " << i;
        // energies are summed per thread, then in thread order: equal up to rounding
        for (const auto& [cat, e] : sims[0]->energies())
          EXPECT_NEAR(sims[static_cast<std::size_t>(t)]->energies().at(cat), e,
                      1e-12 * std::max(1.0, std::abs(e)))
              << cat;
      }
    }
}

// A chain grown at both ends (injection) numbers its new nodes alternately at its two
// ends, so the threads' ranges along the chain hold interleaved node indices: the forces
// stay bit-identical to one thread.
TEST(Threads, ChainGrownAtBothEndsGivesTheSerialForcesBitForBit) {
  const int n0 = 100, grown = 1400;  // 1 500 nodes, >= 256 hinges per thread on three
  const std::size_t N = n0 + grown;
  for (bool hysteresis : {false, true}) {
    std::vector<std::unique_ptr<Simulation>> sims;
    for (int threads : {1, 2, 3}) {
      auto sim = std::make_unique<Simulation>(2, 7);
      sim->verbose = false;
      sim->set_threads(threads);
      sim->set_threads_min_nodes(0);
      auto at = [](int p) {  // a wiggly circle by chain position
        const double phi = 2 * M_PI * p / 1700.0;
        const double r = 270 + 3 * std::sin(9 * phi);
        return Vec3(r * std::cos(phi), r * std::sin(phi), 0.0);
      };
      std::vector<Vec3> pts;
      for (int i = 0; i < n0; ++i) pts.push_back(at(i));
      sim->add_chain("w", pts, 1.0, false);
      for (int k = 0; k < grown; ++k) {
        const bool front = k % 2 == 0;
        sim->grow_chain("w", front, at(front ? -(k / 2 + 1) : n0 + k / 2), 1.0, 1.0);
      }
      sim->add_bond("spring", P({{"k", 1000.0}}));
      if (hysteresis)
        sim->add_bond("bend2d/hysteresis", P({{"k", 60.0}, {"yield_curvature", 0.02}}));
      else
        sim->add_bond("bend2d", P({{"k", 60.0}}));
      std::mt19937 g(11);
      std::uniform_real_distribution<double> u(-0.05, 0.05);
      for (auto& v : sim->nodes().v) v = Vec3(u(g), u(g), 0.0);
      for (auto& x : sim->nodes().x) x += Vec3(u(g), u(g), 0.0);
      sim->compute_forces();
      sims.push_back(std::move(sim));
    }
    const auto& f1 = sims[0]->nodes().f;
    ASSERT_EQ(f1.size(), N);
    ASSERT_GT(f1[N / 2].norm() + f1[N - 1].norm(), 0.0);
    for (int t = 1; t < 3; ++t) {
      const auto& ft = sims[static_cast<std::size_t>(t)]->nodes().f;
      for (std::size_t i = 0; i < N; ++i)
        ASSERT_EQ(f1[i], ft[i]) << (hysteresis ? "bend2d/hysteresis" : "bend2d") << ", " << t + 1
                                << " threads, node " << i;
    }
  }
}

// The node-edge pairs are cut among the threads by the cost of the last evaluation (the
// contacts cluster): a checkpoint keeps the cut, so a run continued from it on the same
// threads adds the forces in the same order as the uninterrupted run, bit for bit.
TEST(Threads, ARestartOnTwoThreadsContinuesBitForBit) {
  const std::string file = "test_threads_restart.h5";
  auto a = packed_spiral(2);
  a->run(RunOptions{40, 0, nullptr});
  a->write_checkpoint(file);
  a->run(RunOptions{40, 0, nullptr});
  auto b = packed_spiral(2);
  b->read_checkpoint(file);
  b->run(RunOptions{40, 0, nullptr});
  std::remove(file.c_str());
  ASSERT_EQ(a->step, b->step);
  for (std::size_t i = 0; i < a->nodes().size(); ++i)
    for (int c = 0; c < 2; ++c) {
      ASSERT_EQ(a->nodes().x[i][c], b->nodes().x[i][c]) << "node " << i;
      ASSERT_EQ(a->nodes().v[i][c], b->nodes().v[i][c]) << "node " << i;
    }
  EXPECT_GT(a->find_style("contact/node-edge")->value("contacts"), 10);
}
