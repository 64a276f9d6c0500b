// Unit tests of inject/wire and of wall openings.
// Covers styles/fix/inject_wire.cpp and the openings of styles/fix/wall_sphere.cpp.
#include <cmath>

#include "helpers.hpp"
#include "quaternion_rod.hpp"

using namespace slender;
using namespace slender::test;

namespace {

std::unique_ptr<Simulation> feed_scene(const std::string& channels, double gamma, double v) {
  auto sim = std::make_unique<Simulation>(2, 1);
  sim->verbose = false;
  std::vector<Vec3> pts;
  for (int i = 0; i < 25; ++i) pts.emplace_back(-12.0 + i, 0, 0);  // r = 10: 3 nodes per channel
  sim->add_chain("wire", pts, 1.0, false);
  sim->add_bond("spring", P({{"k", 1000.0}}));
  sim->add_bond("bend2d", P({{"k", 60.0}}));
  sim->add_fix("drag", "damping/viscous", P({{"gamma", gamma}}));
  sim->add_fix(
      "feed", "inject/wire",
      P({{"chain", std::string("wire")}, {"radius", 10.0}, {"speed", v}, {"channels", channels}}));
  sim->set_integrator("gear", P({{"dt", 0.002}}));
  return sim;
}

}  // namespace

TEST(WireInjectionFix, FeedsTheRightLengthAndGrowsTheChain) {
  // one channel: the straight wire slides through the cavity (two channels would
  // compress a perfectly straight wire until the guard stops it)
  const double v = 0.1;
  auto sim = feed_scene("left", 0.0, v);
  const size_t n0 = sim->nodes().size();
  sim->run(RunOptions{50000, 0, {}});  // t = 100: the channel feeds 10
  const double fed = sim->fix("feed").value("injected");
  EXPECT_NEAR(fed, v * 100.0, 1.0 + 1e-9);  // within one rest length
  EXPECT_EQ(sim->nodes().size() - n0, static_cast<size_t>(std::lround(fed)));
  EXPECT_EQ(sim->topology().chains[0].n_edges(), static_cast<int>(sim->nodes().size()) - 1);
  // every node is in the chain's group and every new node has the chain's mass
  EXPECT_EQ(sim->group("wire").size(), sim->nodes().size());
  for (double m : sim->nodes().mass) EXPECT_EQ(m, 1.0);
  // the rest lengths of the fed edges are the wire's
  for (double l : sim->topology().chains[0].rest_length) EXPECT_EQ(l, 1.0);
}

TEST(WireInjectionFix, InjectionForceBalancesTheDragOfTheWire) {
  // one channel, no obstacle: the whole wire (channel nodes included) slides at v
  // against the drag, so the feeder pushes with gamma v per node
  const double gamma = 0.5, v = 0.05;
  auto sim = feed_scene("left", gamma, v);
  sim->run(RunOptions{40000, 0, {}});  // t = 80, steady sliding
  const double expected = gamma * v * static_cast<double>(sim->nodes().size());
  EXPECT_NEAR(sim->fix("feed").value("force"), expected, 0.04 * expected);
  // packing density d L / (pi r^2) of the wire inside the cavity
  EXPECT_NEAR(sim->fix("feed").value("phi"), 20.0 / (M_PI * 100.0), 1.5 / (M_PI * 100.0));
}

namespace {

// A straight wire fed from the left whose far end is held: pushing it loads it until the
// averaged injection force passes jam_force = 50.
std::unique_ptr<Simulation> clamped_feed(double dt, double jam_time) {
  auto sim = std::make_unique<Simulation>(2, 1);
  sim->verbose = false;
  std::vector<Vec3> pts;
  for (int i = 0; i < 25; ++i) pts.emplace_back(-12.0 + i, 0, 0);
  sim->add_chain("wire", pts, 1.0, false);
  sim->add_bond("spring", P({{"k", 1000.0}}));
  sim->add_fix("drag", "damping/viscous", P({{"gamma", 0.5}}));
  sim->set_group("far", {24});
  sim->add_fix("hold", "clamp", P({{"group", std::string("far")}}));
  sim->add_fix("feed", "inject/wire",
               P({{"chain", std::string("wire")},
                  {"radius", 10.0},
                  {"speed", 0.01},
                  {"channels", std::string("left")},
                  {"jam_force", 50.0},
                  {"jam_time", jam_time}}));
  sim->set_integrator("gear", P({{"dt", dt}}));
  return sim;
}

}  // namespace

TEST(WireInjectionFix, JammingStopsTheRunCleanly) {
  auto sim = clamped_feed(0.002, 0.2);
  sim->run(RunOptions{10000000, 0, {}});
  EXPECT_LT(sim->step, 10000000);
  EXPECT_EQ(sim->fix("feed").value("jammed"), 1.0);
  EXPECT_GT(sim->fix("feed").value("force_avg"), 50.0);
  EXPECT_NE(sim->stop_reason().find("jammed"), std::string::npos) << sim->stop_reason();
}

TEST(WireInjectionFix, JamWindowIsATimeSoTheStopDoesNotDependOnTheStep) {
  // The injection force ramps up, and its average over the last jam_time lags the force
  // by about jam_time / 2. With a window of steps the lag would halve with dt (about 10
  // time units here); with a window in time the stop comes at the same time at both steps.
  auto jam_time_at = [](double dt) {
    auto sim = clamped_feed(dt, 40.0);
    sim->run(RunOptions{100000000, 0, {}});
    EXPECT_EQ(sim->fix("feed").value("jammed"), 1.0);
    return sim->time;
  };
  const double t1 = jam_time_at(0.004), t2 = jam_time_at(0.002);
  EXPECT_NEAR(t1, t2, 1.0) << t1 << " " << t2;
}

TEST(WireInjectionFix, JamTestsNeedTheirAveragingTime) {
  Simulation sim(2, 1);
  std::vector<Vec3> pts;
  for (int i = 0; i < 25; ++i) pts.emplace_back(-12.0 + i, 0, 0);
  sim.add_chain("wire", pts, 1.0, false);
  try {
    sim.add_fix("feed", "inject/wire",
                P({{"chain", std::string("wire")},
                   {"radius", 10.0},
                   {"speed", 0.01},
                   {"jam_force", 50.0}}));
    FAIL() << "jam_force without jam_time was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("jam_time"), std::string::npos) << e.what();
  }
}

TEST(WireInjectionFix, JamTestsWaitForTheirPackingDensity) {
  // one channel: the wire slides through the cavity at a constant packing density
  // (20 / (100 pi) = 0.064), and its drag (about 0.6) passes jam_force = 0.1 at once;
  // with jam_min_phi above that density the run is never stopped
  auto run = [](double min_phi) {
    auto sim = std::make_unique<Simulation>(2, 1);
    sim->verbose = false;
    std::vector<Vec3> pts;
    for (int i = 0; i < 25; ++i) pts.emplace_back(-12.0 + i, 0, 0);
    sim->add_chain("wire", pts, 1.0, false);
    sim->add_bond("spring", P({{"k", 1000.0}}));
    sim->add_fix("drag", "damping/viscous", P({{"gamma", 0.5}}));
    sim->add_fix("feed", "inject/wire",
                 P({{"chain", std::string("wire")},
                    {"radius", 10.0},
                    {"speed", 0.05},
                    {"channels", std::string("left")},
                    {"jam_force", 0.1},
                    {"jam_time", 0.2},
                    {"jam_min_phi", min_phi}}));
    sim->set_integrator("gear", P({{"dt", 0.002}}));
    sim->run(RunOptions{20000, 0, {}});
    return std::make_pair(sim->fix("feed").value("jammed"), sim->step);
  };
  const auto early = run(0.06);
  EXPECT_EQ(early.first, 1.0);
  EXPECT_LT(early.second, 1000);
  const auto never = run(0.07);
  EXPECT_EQ(never.first, 0.0);
  EXPECT_EQ(never.second, 20000);
}

TEST(SphereWallFix, OpeningsLetTheWirePass) {
  Simulation sim(2, 1);
  // nodes across the rim at angle 0 (in the opening) and at angle pi/2 (not)
  sim.add_chain("w", {Vec3(10.2, 0, 0), Vec3(0, 10.2, 0)}, 1.0, false);
  sim.add_fix("cavity", "wall/circle",
              P({{"radius", 10.0},
                 {"diameter", 1.0},
                 {"stiffness", 100.0},
                 {"openings", std::vector<double>{0.0, M_PI}}}));
  sim.compute_forces();
  EXPECT_EQ(sim.nodes().f[0].norm(), 0.0);
  EXPECT_GT(sim.nodes().f[1].norm(), 0.0);
}

TEST(WireInjectionFix, ModifiedSpeedHoldsAndResumesTheFeed) {
  // the force protocol of docs/models.md §2.4: stop the feed, relax, then go on
  auto sim = feed_scene("left", 0.5, 0.1);
  sim->run(RunOptions{10000, 0, {}});
  const double fed = sim->fix("feed").value("injected");
  const double phi = sim->fix("feed").value("phi");
  EXPECT_GT(fed, 0.0);
  sim->fix("feed").modify(P({{"speed", 0.0}}));
  const Vec3 end = sim->nodes().x[sim->topology().chains[0].nodes.front()];
  sim->run(RunOptions{20000, 0, {}});
  EXPECT_EQ(sim->fix("feed").value("injected"), fed);
  EXPECT_EQ(sim->fix("feed").value("phi"), phi);
  EXPECT_EQ((sim->nodes().x[sim->topology().chains[0].nodes.front()] - end).norm(), 0.0);
  // held, the wire relaxes: nothing pushes it any more, the drag stops it
  EXPECT_LT(sim->kinetic_energy(), 1e-6);
  sim->fix("feed").modify(P({{"speed", 0.1}}));
  sim->run(RunOptions{10000, 0, {}});
  EXPECT_NEAR(sim->fix("feed").value("injected"), 2 * fed, 1.0 + 1e-9);
  EXPECT_THROW(sim->fix("feed").modify(P({{"radius", 5.0}})), InputError);
  EXPECT_THROW(sim->fix("feed").modify(P({{"speed", -1.0}})), InputError);
}

TEST(WireInjectionFix, NozzleFeedsA3dWireAlongItsAxis) {
  // a 3D wire fed through a nozzle at (0, 0, R) pointing down (docs/models.md §5.3)
  auto sim = std::make_unique<Simulation>(3, 1);
  sim->verbose = false;
  const double R = 6.0, v = 0.2;
  std::vector<Vec3> pts;
  for (int i = 0; i < 6; ++i) pts.emplace_back(0, 0, R + 2.0 - i);  // 3 nodes in the nozzle
  sim->add_chain("wire", pts, 1.0, false);
  sim->add_bond("spring", P({{"k", 1000.0}}));
  sim->add_bond("rod/straight", P({{"YI", 60.0}}));
  sim->add_fix("feed", "inject/wire",
               P({{"chain", std::string("wire")},
                  {"radius", R},
                  {"speed", v},
                  {"channels", std::string("nozzle")},
                  {"diameter", 1.0},
                  {"center", std::vector<double>{0, 0, 0}}}));
  sim->set_integrator("gear", P({{"dt", 0.002}, {"values", 6.0}}));
  sim->run(RunOptions{10000, 0, {}});  // t = 20: feeds 4
  const double fed = sim->fix("feed").value("injected");
  EXPECT_NEAR(fed, v * 20.0, 1.0 + 1e-9);
  EXPECT_EQ(sim->nodes().size(), 6 + static_cast<size_t>(std::lround(fed)));
  // the channel holds the wire on the axis; the free straight wire stays on it too
  for (auto& x : sim->nodes().x) EXPECT_LT(x.head<2>().norm(), 1e-9);
  // 3D packing density: L pi a^2 / (4/3 pi R^3), L the length inside the sphere
  const Chain& c = sim->topology().chains[0];
  double inside = 0;
  for (int e = 0; e < c.n_edges(); ++e)
    if ((0.5 * (sim->nodes().x[c.edge_tail(e)] + sim->nodes().x[c.edge_head(e)])).norm() < R)
      inside += c.rest_length[e];
  EXPECT_NEAR(sim->fix("feed").value("phi"), inside * 0.25 / (4.0 / 3.0 * R * R * R), 1e-12);
  EXPECT_GE(inside, 6.0);
  // a wire whose end is not in the nozzle is refused
  Simulation bad(3, 1);
  std::vector<Vec3> in;
  for (int i = 0; i < 4; ++i) in.emplace_back(0, 0, -i);
  bad.add_chain("wire", in, 1.0, false);
  EXPECT_THROW(bad.add_fix("feed", "inject/wire",
                           P({{"chain", std::string("wire")},
                              {"radius", R},
                              {"speed", v},
                              {"channels", std::string("nozzle")}})),
               InputError);
}

TEST(WireInjectionFix, NozzleHoldsTheFramesOfACosseratRodOnlyWhenAsked) {
  for (const char* rotation : {"free", "held"}) {
    Simulation sim(3, 1);
    sim.verbose = false;
    const double R = 6.0;
    std::vector<Vec3> pts;
    for (int i = 0; i < 6; ++i) pts.emplace_back(0.01 * (i % 2), 0, R + 2.0 - i);
    sim.add_chain("wire", pts, 1.0, false);
    sim.add_bond("spring", P({{"k", 1000.0}}));
    sim.add_bond("rod/cosserat", P({{"YI", 60.0},
                                    {"GJ", 40.0},
                                    {"coupling", 1000.0},
                                    {"rot_inertia", 1.0},
                                    {"rest_curvature", std::vector<double>{0, 0.1, 0}}}));
    sim.add_fix("feed", "inject/wire",
                P({{"chain", std::string("wire")},
                   {"radius", R},
                   {"speed", 0.2},
                   {"channels", std::string("nozzle")},
                   {"rotation", std::string(rotation)},
                   {"center", std::vector<double>{0, 0, 0}}}));
    sim.set_integrator("gear", P({{"dt", 0.002}, {"values", 6.0}}));
    sim.run(RunOptions{5000, 0, {}});
    const Chain& c = sim.topology().chains[0];
    const auto& fixed = sim.coordinates("rod.q").fixed->values();
    const auto& q = sim.coordinates("rod.q").q->values();
    // the first (outermost) edge is in the nozzle; new edges are born from it
    const int outer = c.nodes.front();
    EXPECT_GT(sim.nodes().x[outer].z(), R);
    EXPECT_EQ(fixed[outer], std::string(rotation) == "held" ? 1 : 0) << rotation;
    EXPECT_LT((qrod::d3(q[outer]) - Vec3(0, 0, -1)).norm(), 2e-2)
        << rotation;  // docs/models.md §4.3: |t - d3| < 1e-2
    // edges inside the sphere are free in both setups
    EXPECT_EQ(fixed[c.nodes[c.n_nodes() - 2]], 0);
  }
}

TEST(WireInjectionFix, ReleasedNodesGetASeededTransverseKick) {
  auto run = [](double perturb, unsigned seed) {
    auto sim = std::make_unique<Simulation>(3, seed);
    sim->verbose = false;
    std::vector<Vec3> pts;
    for (int i = 0; i < 6; ++i) pts.emplace_back(0, 0, 8.0 - i);
    sim->add_chain("wire", pts, 1.0, false);
    sim->add_bond("spring", P({{"k", 1000.0}}));
    sim->add_fix("feed", "inject/wire",
                 P({{"chain", std::string("wire")},
                    {"radius", 6.0},
                    {"speed", 0.2},
                    {"channels", std::string("nozzle")},
                    {"perturb", perturb},
                    {"center", std::vector<double>{0, 0, 0}}}));
    sim->set_integrator("verlet", P({{"dt", 0.002}}));
    sim->run(RunOptions{5000, 0, {}});
    return sim->nodes().x;
  };
  double off = 0;
  for (auto& x : run(0.0, 1)) off = std::max(off, x.head<2>().norm());
  EXPECT_EQ(off, 0.0);
  const auto a = run(0.05, 1), b = run(0.05, 1), c = run(0.05, 2);
  off = 0;
  for (auto& x : a) off = std::max(off, x.head<2>().norm());
  EXPECT_GT(off, 1e-3);
  EXPECT_LT(off, 0.05 * std::sqrt(2.0) + 1e-12);  // springs alone do not push it further out
  EXPECT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i], b[i]);
  bool differ = false;
  for (size_t i = 0; i < std::min(a.size(), c.size()); ++i) differ = differ || a[i] != c[i];
  EXPECT_TRUE(differ);
}

// The resolved schedule of the 2D crumpling scene (golden): shells, bonds, pairs in the
// force stage by priority; the feed, which measures the injection force from the complete
// forces, after every other post-force fix, although the deck adds it before the wall;
// the core's constraints; removing a fix removes its calls (the mask stays: the feed holds
// its channel nodes through it).
TEST(Schedule, ResolvedOrderOfTheCrumplingSceneIsGolden) {
  auto sim = std::make_unique<Simulation>(2, 1);
  sim->verbose = false;
  std::vector<Vec3> pts;
  for (int i = 0; i < 25; ++i) pts.emplace_back(-12.0 + i, 0, 0);
  sim->add_chain("wire", pts, 1.0, false);
  sim->add_pair("contact/node-edge", P({{"stiffness", 1e3}}));  // added first, runs after bonds
  sim->add_bond("spring", P({{"k", 1000.0}}));
  sim->add_bond("bend2d", P({{"k", 60.0}}));
  sim->add_fix("feed", "inject/wire",
               P({{"chain", std::string("wire")}, {"radius", 10.0}, {"speed", 0.01}}));
  sim->add_fix("cavity", "wall/circle", P({{"radius", 10.0}, {"stiffness", 500.0}}));
  sim->add_fix("drag", "damping/viscous", P({{"gamma", 0.1}}));
  sim->set_group("tip", {12});
  sim->add_fix("pin", "clamp", P({{"group", std::string("tip")}}));
  EXPECT_EQ(sim->schedule().describe(),
            "force: bond spring [0]; bond bend2d [0]; pair contact/node-edge [100]\n"
            "post-force: fix cavity (wall/circle) [0]; fix drag (damping/viscous) [0]; "
            "fix feed (inject/wire) [1000]\n"
            "constrain: clamped components (dof_mask); 2D plane\n"
            "end of step: fix feed (inject/wire) [1000]\n");
  // the feed's measured force sees the wall's and the drag's forces: with the nominal
  // order it would be computed before them
  ASSERT_EQ(sim->schedule().post_force_fixes().back(), &sim->fix("feed"));
  sim->remove_fix("drag");
  sim->remove_fix("pin");
  EXPECT_EQ(sim->schedule().describe(),
            "force: bond spring [0]; bond bend2d [0]; pair contact/node-edge [100]\n"
            "post-force: fix cavity (wall/circle) [0]; fix feed (inject/wire) [1000]\n"
            "constrain: clamped components (dof_mask); 2D plane\n"
            "end of step: fix feed (inject/wire) [1000]\n");
}
