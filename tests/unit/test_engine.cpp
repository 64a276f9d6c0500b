// Engine tests: registry and parameter declarations, node properties, regions,
// computes, independence of scenes, the instability guard, dumps and checkpoints.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>

#include "helpers.hpp"
#include "registry.hpp"
#include "scene_build.hpp"
#include "stiffness.hpp"
#ifdef SLENDER_HAVE_HDF5
#include "h5util.hpp"
#endif

using namespace slender;
using namespace slender::test;

TEST(Registry, EveryFamilyHasItsFirstStylesAndHelp) {
  for (auto name :
       {"spring", "bend2d", "clamp", "force/constant", "damping/viscous", "wall/sphere",
        "wall/circle", "energy", "count", "verlet", "gear", "fire", "circle", "sphere", "box"})
    EXPECT_EQ(Catalog::lookup(name).size(), 1u) << name;
  for (auto& e : Catalog::entries()) {
    ParamSpec s = e.spec();
    EXPECT_FALSE(s.summary.empty()) << e.name;
    EXPECT_EQ(s.family, e.family) << e.name;
    for (auto& d : s.decls) EXPECT_FALSE(d.help.empty()) << e.name << "." << d.name;
    EXPECT_NE(s.help_text().find(e.name), std::string::npos);
  }
  EXPECT_TRUE(Catalog::lookup("no-such-style").empty());
}

TEST(Params, ValidationMessagesNameTheProblem) {
  ParamSpec s("bond", "demo", "a demo");
  s.real("k", "stiffness").required().positive();
  s.integer("n", "count").def(3.0).min(1).max(5);
  s.string("mode", "mode").def(std::string("a")).choices({"a", "b"});
  s.vector("v", "vector").def(std::vector<double>{0, 0}).length(2, 3);
  auto expect_msg = [&](RawParams raw, const std::string& part) {
    try {
      s.validate(raw);
      ADD_FAILURE() << "no error for " << part;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    }
  };
  expect_msg(P({}), "missing required key 'k'");
  expect_msg(P({{"k", 1.0}, {"q", 1.0}}), "unknown key 'q'");
  expect_msg(P({{"k", 0.0}}), "'k' = 0 is out of range (0, inf)");
  // a non-finite value is named as such, not as out of a range that seems to hold it
  expect_msg(P({{"k", std::numeric_limits<double>::infinity()}}),
             "'k' = inf is not a finite number (range (0, inf))");
  expect_msg(P({{"k", 1.0}, {"v", std::vector<double>{1, std::nan("")}}}),
             "is not a finite number");
  expect_msg(P({{"k", 1.0}, {"n", 2.5}}), "'n' expects a integer");
  expect_msg(P({{"k", 1.0}, {"n", 9.0}}), "out of range [1, 5]");
  // an integer beyond 2^53 is refused by size, before it could overflow (seed = 1e20)
  expect_msg(P({{"k", 1.0}, {"n", 1e20}}), "'n' = 1e+20 is too large for an integer");
  expect_msg(P({{"k", 1.0}, {"mode", std::string("c")}}), "is not one of \"a\" \"b\"");
  expect_msg(P({{"k", 1.0}, {"v", std::vector<double>{1}}}), "needs 2 to 3 values");
  auto ok = s.validate(P({{"k", 2.0}}));
  EXPECT_EQ(ok.integer("n"), 3);
  EXPECT_EQ(ok.str("mode"), "a");
  EXPECT_EQ(ok.vec3("v"), Vec3::Zero());
}

TEST(NodeStore, PropertiesAreAllocatedOnlyOnRequest) {
  Simulation sim(2, 1);
  sim.add_chain("w", wiggly_chain(5, 2, 1), 1.0, false);
  sim.add_bond("spring", P({{"k", 10.0}}));
  sim.set_integrator("verlet", P({{"dt", 0.01}}));
  EXPECT_EQ(sim.nodes().property_names().size(), 4u);  // position velocity force mass
  sim.set_integrator("gear", P({{"values", 5.0}}));
  EXPECT_TRUE(sim.nodes().has("gear.r4"));
  EXPECT_FALSE(sim.nodes().has("gear.r5"));
  // growing the scene grows every property
  sim.nodes().add(Vec3(9, 9, 0), 1.0);
  EXPECT_EQ(sim.nodes().find<Vec3>("gear.r3")->size(), 6u);
  // asking with another type is a programming error
  EXPECT_THROW(sim.nodes().require<double>("gear.r2"), std::logic_error);
}

TEST(Topology, ChainsGrowAtEitherEnd) {
  Simulation sim(2, 1);
  Chain& c = sim.add_chain("w", {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0)}, 1.0, false);
  EXPECT_EQ(c.n_edges(), 2);
  EXPECT_EQ(c.n_hinges(), 1);
  int n = static_cast<int>(sim.nodes().add(Vec3(-1, 0, 0), 1.0));
  c.grow_front(n, 1.0);
  EXPECT_EQ(c.nodes.front(), n);
  EXPECT_EQ(c.n_hinges(), 2);
  EXPECT_THROW(sim.add_chain("w", {Vec3(0, 0, 0), Vec3(1, 0, 0)}, 1.0, false), InputError);
  EXPECT_THROW(sim.add_chain("z", {Vec3(0, 0, 0), Vec3(0, 0, 0)}, 1.0, false), InputError);
}

TEST(Regions, ContainmentOfCircleSphereBox) {
  Simulation sim(3, 1);
  auto& c =
      sim.add_region("c", "circle", P({{"radius", 2.0}, {"center", std::vector<double>{1, 0}}}));
  EXPECT_TRUE(c.contains(Vec3(2.9, 0, 100)));  // a z-aligned cylinder in 3D
  EXPECT_FALSE(c.contains(Vec3(3.1, 0, 0)));
  auto& s = sim.add_region("s", "sphere", P({{"radius", 1.0}}));
  EXPECT_TRUE(s.contains(Vec3(0.5, 0.5, 0.5)));
  EXPECT_FALSE(s.contains(Vec3(0.6, 0.6, 0.6)));
  auto& b = sim.add_region(
      "b", "box", P({{"lo", std::vector<double>{0, 0, 0}}, {"hi", std::vector<double>{1, 2, 3}}}));
  EXPECT_TRUE(b.contains(Vec3(0.5, 1.5, 2.5)));
  EXPECT_FALSE(b.contains(Vec3(0.5, 2.5, 2.5)));
  EXPECT_THROW(sim.add_region(
                   "bad", "box",
                   P({{"lo", std::vector<double>{1, 0, 0}}, {"hi", std::vector<double>{0, 1, 1}}})),
               InputError);
  EXPECT_THROW(sim.add_region("c", "sphere", P({{"radius", 1.0}})), InputError);
}

TEST(Computes, EnergyAndCount) {
  Simulation sim(2, 1);
  sim.add_chain("w", wiggly_chain(6, 2, 4), 2.0, false);
  sim.add_bond("spring", P({{"k", 10.0}}));
  sim.add_bond("bend2d", P({{"k", 3.0}}));
  sim.add_compute("e", "energy", {});
  sim.add_compute("n", "count", {});
  for (auto& v : sim.nodes().v) v = Vec3(1, 0, 0);
  sim.compute_forces();
  EXPECT_NEAR(sim.column("e.kinetic"), 0.5 * 2.0 * 6, 1e-12);
  EXPECT_NEAR(sim.column("e.total"), 6.0 + sim.column("e.stretch") + sim.column("e.bend"), 1e-12);
  EXPECT_GT(sim.column("e.bend"), 0.0);
  EXPECT_EQ(sim.column("e.contact"), 0.0);
  EXPECT_EQ(sim.column("n.nodes"), 6.0);
  EXPECT_EQ(sim.column("n.edges"), 5.0);
  EXPECT_THROW(sim.column("n.bogus"), InputError);
  EXPECT_THROW(sim.column("bogus"), InputError);
}

TEST(Simulation, TwoScenesInOneProcessAreIndependent) {
  auto make = [](std::uint64_t seed) {
    auto s = std::make_unique<Simulation>(2, seed);
    s->verbose = false;
    auto pts = wiggly_chain(20, 2, 1, 0.0);
    std::uniform_real_distribution<double> u(-0.05, 0.05);
    for (auto& p : pts) p.y() += u(s->rng());
    s->add_chain("w", pts, 1.0, false);
    s->add_bond("spring", P({{"k", 100.0}}));
    s->add_bond("bend2d", P({{"k", 5.0}}));
    s->set_integrator("gear", P({{"dt", 0.005}}));
    return s;
  };
  auto a = make(1), b = make(1), c = make(2);
  a->run(RunOptions{200, 0, {}});
  c->run(RunOptions{200, 0, {}});  // interleaved: must not disturb a or b
  b->run(RunOptions{200, 0, {}});
  for (size_t i = 0; i < 20; ++i) EXPECT_EQ(a->nodes().x[i], b->nodes().x[i]);
  EXPECT_NE(a->nodes().x[5], c->nodes().x[5]);
}

TEST(Guard, CatchesNonFiniteForceAndNamesAStableDt) {
  Simulation sim(2, 1);
  sim.verbose = false;
  sim.guard.last_good_file = "guard_test_last_good.h5";
  sim.add_chain("w", wiggly_chain(10, 2, 2, 0.1), 1.0, false);
  sim.add_bond("spring", P({{"k", 1000.0}}));
  sim.nodes().v[4] = Vec3(0.01, 0.02, 0);          // rest lengths come from the start: kick it
  sim.set_integrator("verlet", P({{"dt", 0.2}}));  // omega dt = 13: unstable
  try {
    sim.run(RunOptions{100000, 0, {}});
    FAIL() << "no instability detected";
  } catch (const InstabilityError& e) {
    std::string m = e.what();
    EXPECT_NE(m.find("instability at step"), std::string::npos) << m;
    EXPECT_NE(m.find("rerun with dt <="), std::string::npos) << m;
    EXPECT_LT(sim.step, 100);  // caught within a few checks, not after a long NaN run
  }
  std::remove("guard_test_last_good.h5");
}

#ifdef SLENDER_HAVE_HDF5
TEST(Guard, LastGoodStateHoldsNoNaNAndTheSceneReturnsToIt) {
  Simulation sim(2, 1);
  sim.verbose = false;
  sim.guard.last_good_file = "guard_test_gear.h5";
  sim.guard.every = 50;  // let NaN reach the Gear history arrays before the check
  sim.guard.max_step_fraction = 1e300;
  sim.guard.ke_factor = 1e300;
  sim.add_chain("w", wiggly_chain(10, 2, 2, 0.1), 1.0, false);
  sim.add_bond("spring", P({{"k", 1000.0}}));
  sim.add_bond("bend2d", P({{"k", 60.0}}));
  sim.set_integrator("gear", P({{"values", 6.0}, {"dt", 0.3}}));
  EXPECT_THROW(sim.run(RunOptions{100000, 0, {}}), InstabilityError);
  EXPECT_EQ(sim.step % 50, 0);
  for (auto& x : sim.nodes().x) EXPECT_TRUE(x.allFinite());
  auto f = h5::open_file("guard_test_gear.h5", false);
  for (auto group : {"nodes", "properties", "state/energy"}) {
    auto g = h5::open_group(f, group);
    for (auto& name : h5::children(g))
      for (double v : h5::read_doubles(g, name))
        ASSERT_TRUE(std::isfinite(v)) << group << "/" << name;
  }
  std::remove("guard_test_gear.h5");
}
#endif

// The last good state is the whole state of the good step: plastic curvatures (a node
// property), the hysteresis bond's dissipated energy and the contact history (style state)
// come back with the positions, in memory and in the last-good file. (They kept the values
// of the diverged steps: plastic curvatures of 3.1 rad in a "step 0" state.)
TEST(Guard, RollbackRestoresPlasticityAndStyleState) {
  Simulation sim(2, 1);
  sim.verbose = false;
  sim.guard.last_good_file = "guard_test_plastic.h5";
  sim.add_chain("w", wiggly_chain(40, 2, 4, 0.4), 1.0, false);
  sim.add_bond("spring", P({{"k", 1000.0}}));
  sim.add_bond("bend2d/hysteresis", P({{"k", 60.0}, {"yield_curvature", 0.05}}));
  sim.add_pair("contact/node-edge", P({{"diameter", 0.5}, {"stiffness", 1e3}, {"mu_static", 0.5}}));
  sim.set_integrator("verlet", P({{"dt", 0.002}}));
  sim.run(RunOptions{200, 0, {}});
  auto* kpl = sim.nodes().find<double>("bend.plastic_curvature");
  ASSERT_TRUE(kpl);
  const std::vector<double> kpl_good = kpl->values();
  double most = 0.0;
  for (double k : kpl_good) most = std::max(most, std::abs(k));
  ASSERT_GT(most, 0.01);  // the wiggles yielded: there is plastic state to get wrong
  const double lost_good = sim.find_style("bend2d/hysteresis")->value("dissipated");
  ASSERT_GT(lost_good, 0.0);
  const std::vector<Vec3> x_good = sim.nodes().x;
  sim.set_integrator("verlet", P({{"dt", 0.5}}));  // far above the stable step
  EXPECT_THROW(sim.run(RunOptions{1000, 0, {}}), InstabilityError);
  EXPECT_EQ(sim.nodes().x, x_good);
  EXPECT_EQ(sim.nodes().find<double>("bend.plastic_curvature")->values(), kpl_good);
  EXPECT_EQ(sim.find_style("bend2d/hysteresis")->value("dissipated"), lost_good);
#ifdef SLENDER_HAVE_HDF5
  // the file holds the same state, all finite
  Simulation back(2, 1);
  back.verbose = false;
  back.add_chain("w", wiggly_chain(40, 2, 4, 0.4), 1.0, false);
  back.add_bond("spring", P({{"k", 1000.0}}));
  back.add_bond("bend2d/hysteresis", P({{"k", 60.0}, {"yield_curvature", 0.05}}));
  back.add_pair("contact/node-edge",
                P({{"diameter", 0.5}, {"stiffness", 1e3}, {"mu_static", 0.5}}));
  back.set_integrator("verlet", P({{"dt", 0.002}}));
  back.read_checkpoint("guard_test_plastic.h5");
  EXPECT_EQ(back.nodes().x, x_good);
  EXPECT_EQ(back.nodes().find<double>("bend.plastic_curvature")->values(), kpl_good);
  EXPECT_EQ(back.find_style("bend2d/hysteresis")->value("dissipated"), lost_good);
#endif
  std::remove("guard_test_plastic.h5");
}

TEST(Guard, NodeLeavingEveryBoundingRegionStopsTheRun) {
  Simulation sim(2, 1);
  sim.verbose = false;
  sim.guard.last_good_file = "guard_test_bounds.h5";
  sim.add_chain("w", {Vec3(0, 0, 0), Vec3(1, 0, 0)}, 1.0, false);
  sim.add_bond("spring", P({{"k", 1000.0}}));  // stiff: the pair moves as a whole
  sim.add_region("box", "box",
                 P({{"lo", std::vector<double>{-1, -1}}, {"hi", std::vector<double>{3, 1}}}));
  EXPECT_THROW(sim.add_region("b2", "sphere", P({{"radius", -1.0}})), InputError);
  sim.add_region("domain", "sphere", P({{"radius", 2.0}, {"bounds", true}}));
  sim.set_group("end", {1});
  sim.add_fix("push", "force/constant",
              P({{"group", std::string("end")}, {"force", std::vector<double>{5, 0}}}));
  sim.set_integrator("verlet", P({{"dt", 0.01}}));
  try {
    sim.run(RunOptions{100000, 0, {}});
    FAIL() << "the node left the domain unnoticed";
  } catch (const InstabilityError& e) {
    EXPECT_NE(std::string(e.what()).find("left every bounding region"), std::string::npos)
        << e.what();
  }
  std::remove("guard_test_bounds.h5");
}

TEST(Guard, ATornWireStopsTheRun) {
  Simulation sim(2, 1);
  sim.verbose = false;
  sim.guard.last_good_file = "guard_test_torn.h5";
  sim.add_chain("w", {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0)}, 1.0, false);
  sim.add_bond("spring", P({{"k", 10.0}}));
  sim.set_group("end", {2});
  sim.add_fix("pull", "force/constant",
              P({{"group", std::string("end")}, {"force", std::vector<double>{20, 0}}}));
  sim.set_integrator("verlet", P({{"dt", 0.01}}));
  try {
    sim.run(RunOptions{100000, 0, {}});
    FAIL() << "the torn wire went unnoticed";
  } catch (const InstabilityError& e) {
    EXPECT_NE(std::string(e.what()).find("of chain 'w' (nodes 2-3) is at"), std::string::npos)
        << e.what();
  }
  std::remove("guard_test_torn.h5");
}

TEST(StableDt, AutoUsesTheIntegratorLimit) {
  for (auto [style, limit] : {std::pair<const char*, double>{"verlet", 2.0}, {"gear", 0.42}}) {
    Simulation sim(2, 1);
    sim.verbose = false;
    sim.add_chain("w", wiggly_chain(5, 2, 1, 0.0), 1.0, false);
    sim.add_bond("spring", P({{"k", 400.0}}));
    sim.set_integrator(style, P({{"safety", 0.5}}));
    sim.run(RunOptions{1, 0, {}});
    EXPECT_NEAR(sim.dt, 0.5 * limit / 40.0, 1e-12) << style;  // omega_max = 2 sqrt(400)
  }
}

// A run that continues where the last one ended, in the same scene or appending to the
// file of a restarted one, does not repeat the row of the step it starts from.
TEST(Thermo, ContinuedRunsWriteEachStepOnceAndInOrder) {
  auto make = [](bool append) {
    auto s = std::make_unique<Simulation>(2, 9);
    s->verbose = false;
    s->add_chain("w", wiggly_chain(5, 2, 8, 0.2), 1.0, false);
    s->add_bond("spring", P({{"k", 200.0}}));
    s->set_integrator("verlet", P({{"dt", 0.001}}));
    s->thermo.every = 5;
    s->thermo.columns = {"step", "time"};
    s->thermo.file = "thermo_once.csv";
    s->thermo.append = append;
    return s;
  };
  auto steps_in_file = [] {
    std::ifstream in("thermo_once.csv");
    std::string line;
    std::vector<long> steps;
    std::getline(in, line);
    EXPECT_EQ(line, "step,time");
    while (std::getline(in, line)) steps.push_back(std::stol(line.substr(0, line.find(','))));
    return steps;
  };
  {
    auto a = make(false);
    a->run(RunOptions{10, 0, {}});
    a->run(RunOptions{10, 0, {}});
  }
  EXPECT_EQ(steps_in_file(), (std::vector<long>{0, 5, 10, 15, 20}));
  {
    auto b = make(true);  // as a restart from the checkpoint of step 20
    b->step = 20;
    b->time = 7.0;  // marks the rows this run writes
    b->run(RunOptions{10, 0, {}});
  }
  EXPECT_EQ(steps_in_file(), (std::vector<long>{0, 5, 10, 15, 20, 25, 30}));
  {
    // the row of the checkpoint's step is the first run's (a restart's first row would
    // lack the per-step counts, such as contacts, that only a force evaluation makes)
    std::ifstream in("thermo_once.csv");
    std::string line;
    std::vector<double> times;
    std::getline(in, line);
    while (std::getline(in, line)) times.push_back(std::stod(line.substr(line.find(',') + 1)));
    ASSERT_EQ(times.size(), 7u);
    EXPECT_NEAR(times[4], 0.02, 1e-12);
    EXPECT_NEAR(times[5], 7.005, 1e-12);
  }
  {
    // a restart from an older checkpoint (step 10): the rows the first run wrote after
    // it are redone, not repeated out of order
    auto c = make(true);
    c->step = 10;
    c->run(RunOptions{5, 0, {}});
  }
  EXPECT_EQ(steps_in_file(), (std::vector<long>{0, 5, 10, 15}));
  std::remove("thermo_once.csv");
}

#ifdef SLENDER_HAVE_HDF5
TEST(H5mdDump, WritesFiniteFramesAndAnXdmfSideFile) {
  const std::string file = "test_dump.h5";
  {
    Simulation sim(2, 3);
    sim.verbose = false;
    sim.add_chain("w", wiggly_chain(7, 2, 3), 1.0, false);
    sim.add_bond("spring", P({{"k", 50.0}}));
    sim.set_integrator("verlet", P({{"dt", 0.01}}));
    sim.add_dump("d", "h5md",
                 P({{"file", file},
                    {"every", 10.0},
                    {"fields", std::vector<std::string>{"position", "velocity"}}}));
    sim.run(RunOptions{50, 0, {}});
    EXPECT_THROW(sim.add_dump("e", "h5md",
                              P({{"file", std::string("x.h5")},
                                 {"every", 1.0},
                                 {"fields", std::vector<std::string>{"torque"}}})),
                 InputError);
  }
  auto f = h5::open_file(file, false);
  std::vector<hsize_t> dims;
  auto pos = h5::read_doubles(f, "particles/all/position/value", &dims);
  ASSERT_EQ(dims.size(), 3u);
  EXPECT_EQ(dims[0], 6u);  // steps 0, 10, ..., 50
  EXPECT_EQ(dims[1], 7u);
  EXPECT_EQ(dims[2], 2u);
  for (double v : pos) EXPECT_TRUE(std::isfinite(v));
  auto steps = h5::read_doubles(f, "particles/all/position/step");
  EXPECT_EQ(steps.back(), 50.0);
  std::vector<hsize_t> edims;
  h5::read_doubles(f, "connectivity/edges/value", &edims);
  EXPECT_EQ(edims[1], 6u);
  // one open chain of 7 nodes is one XDMF polyline: cell type 2, 7 nodes, the nodes in order
  std::vector<hsize_t> ldims;
  auto lines = h5::read_doubles(f, "xdmf/polylines/value", &ldims);
  ASSERT_EQ(ldims.size(), 2u);  // one value per row: [frames][values], no component axis
  EXPECT_EQ(ldims[1], 9u);
  std::vector<double> first(lines.begin(), lines.begin() + 9);
  EXPECT_EQ(first, (std::vector<double>{2, 7, 0, 1, 2, 3, 4, 5, 6}));
  std::ifstream x(file + ".xdmf");
  std::stringstream ss;
  ss << x.rdbuf();
  EXPECT_NE(ss.str().find("TopologyType=\"Mixed\" NumberOfElements=\"1\""), std::string::npos);
  EXPECT_NE(ss.str().find("test_dump.h5:/xdmf/polylines/value"), std::string::npos);
  EXPECT_NE(ss.str().find("test_dump.h5:/particles/all/velocity/value"), std::string::npos);
  // H5MD 1.1: the node index, one value per node, is [frames][nodes]
  std::vector<hsize_t> idims;
  h5::read_doubles(f, "particles/all/id/value", &idims);
  EXPECT_EQ(idims.size(), 2u);
  std::remove(file.c_str());
  std::remove((file + ".xdmf").c_str());
}

TEST(H5mdDump, WallsAreDrawnInTheirOwnXdmfFile) {
  // a circular wall of radius 5 with two openings (on the x axis): two arcs on the circle,
  // in /xdmf/wall_points and /xdmf/wall_polylines, described by <file>.walls.xdmf
  const std::string file = "test_dump_walls.h5";
  {
    Simulation sim(2, 3);
    sim.verbose = false;
    sim.add_chain("w", wiggly_chain(7, 2, 3), 1.0, false);
    sim.add_bond("spring", P({{"k", 50.0}}));
    sim.add_fix("cavity", "wall/circle",
                P({{"radius", 5.0},
                   {"stiffness", 100.0},
                   {"openings", std::vector<double>{0.0, M_PI}},
                   {"opening_width", 1.0}}));
    sim.set_integrator("verlet", P({{"dt", 0.01}}));
    sim.add_dump("d", "h5md", P({{"file", file}, {"every", 10.0}}));
    sim.run(RunOptions{20, 0, {}});
  }
  auto f = h5::open_file(file, false);
  std::vector<hsize_t> pdims, ldims;
  auto pts = h5::read_doubles(f, "xdmf/wall_points/value", &pdims);
  auto lines = h5::read_doubles(f, "xdmf/wall_polylines/value", &ldims);
  ASSERT_EQ(pdims.size(), 3u);
  EXPECT_EQ(pdims[0], 3u);  // steps 0, 10, 20
  EXPECT_EQ(pdims[2], 2u);
  for (std::size_t k = 0; k < pdims[1]; ++k)
    EXPECT_NEAR(std::hypot(pts[2 * k], pts[2 * k + 1]), 5.0, 1e-12);
  // two polylines (cell type 2), neither touching the openings at angles 0 and pi
  ASSERT_EQ(lines[0], 2.0);
  const auto n1 = static_cast<std::size_t>(lines[1]);
  ASSERT_EQ(lines[2 + n1], 2.0);
  const auto n2 = static_cast<std::size_t>(lines[3 + n1]);
  EXPECT_EQ(n1 + n2, pdims[1]);
  EXPECT_GT(n1, 100u);
  EXPECT_GT(n2, 100u);
  for (std::size_t k = 0; k < pdims[1]; ++k)
    EXPECT_GT(std::abs(pts[2 * k + 1]), 5.0 * std::sin(0.09)) << k;  // half the gap: 0.1 rad
  std::ifstream x(file + ".walls.xdmf");
  std::stringstream ss;
  ss << x.rdbuf();
  EXPECT_NE(ss.str().find("TopologyType=\"Mixed\" NumberOfElements=\"2\""), std::string::npos);
  EXPECT_NE(ss.str().find("test_dump_walls.h5:/xdmf/wall_points/value"), std::string::npos);
  std::remove(file.c_str());
  std::remove((file + ".xdmf").c_str());
  std::remove((file + ".walls.xdmf").c_str());
}

TEST(H5mdDump, ARunThatStopsWritesItsLastStateOffThePeriod) {
  // a jam (any request_stop) ends the run between two frames: the stopped state is
  // the run's result, so the trajectory gets it as its last frame
  const std::string file = "test_dump_stop.h5";
  {
    Simulation sim(2, 3);
    sim.verbose = false;
    sim.add_chain("w", wiggly_chain(7, 2, 3), 1.0, false);
    sim.add_bond("spring", P({{"k", 50.0}}));
    sim.set_integrator("verlet", P({{"dt", 0.01}}));
    sim.add_dump("d", "h5md", P({{"file", file}, {"every", 10.0}}));
    sim.run(RunOptions{50, 1, [](Simulation& s) {
                         if (s.step == 23) s.request_stop("a threshold");
                         return false;
                       }});
    EXPECT_EQ(sim.step, 24);
  }
  auto f = h5::open_file(file, false);
  EXPECT_EQ(h5::read_doubles(f, "particles/all/position/step"),
            (std::vector<double>{0, 10, 20, 24}));
  std::remove(file.c_str());
  std::remove((file + ".xdmf").c_str());
}

TEST(Checkpoint, ARestartUnderOtherParametersSaysWhichDiffer) {
  // the checkpoint records every style's parameters; a deck that differs (a stiffer spring,
  // a modified one) is told which values changed, and the same deck is told nothing
  auto make = [](double k) {
    auto s = std::make_unique<Simulation>(2, 9);
    s->verbose = false;
    s->add_chain("w", wiggly_chain(9, 2, 8, 0.2), 1.0, false);
    s->add_bond("spring", P({{"k", k}}));
    s->add_fix("drag", "damping/viscous", P({{"gamma", 0.1}}));
    s->set_integrator("verlet", P({{"dt", 0.01}}));
    return s;
  };
  auto a = make(200.0);
  a->run(RunOptions{10, 0, {}});
  a->write_checkpoint("test_ck_params.h5");
  auto same = make(200.0);
  testing::internal::CaptureStderr();
  same->read_checkpoint("test_ck_params.h5");
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
  auto other = make(250.0);
  other->find_style("drag")->note_modified(P({{"gamma", 0.3}}));  // as sim:modify records it
  testing::internal::CaptureStderr();
  other->read_checkpoint("test_ck_params.h5");
  const std::string said = testing::internal::GetCapturedStderr();
  EXPECT_NE(said.find("bond 'spring' (spring): k 200 in the checkpoint, 250 here"),
            std::string::npos)
      << said;
  EXPECT_NE(said.find("fix 'drag' (damping/viscous): gamma 0.1 in the checkpoint, 0.3 here"),
            std::string::npos)
      << said;
  // a deck that rolls back to its own checkpoint after sim:modify (a retry with another
  // value, as the e-cone ramp does) changed that key deliberately: not said; others still are
  auto back = make(250.0);
  back->modify_style("drag", P({{"gamma", 0.3}}));
  testing::internal::CaptureStderr();
  back->read_checkpoint("test_ck_params.h5");
  const std::string said_back = testing::internal::GetCapturedStderr();
  EXPECT_EQ(said_back.find("gamma"), std::string::npos) << said_back;
  EXPECT_NE(said_back.find("k 200 in the checkpoint, 250 here"), std::string::npos) << said_back;
  std::remove("test_ck_params.h5");
}

TEST(Checkpoint, RestartIsBitIdenticalAndRejectsOtherScenes) {
  auto make = [] {
    auto s = std::make_unique<Simulation>(2, 9);
    s->verbose = false;
    s->add_chain("w", wiggly_chain(15, 2, 8, 0.2), 1.0, false);
    s->add_bond("spring", P({{"k", 200.0}}));
    s->add_bond("bend2d", P({{"k", 8.0}}));
    s->set_integrator("gear", P({{"values", 6.0}, {"dt", 0.004}}));
    return s;
  };
  auto a = make();
  a->run(RunOptions{100, 0, {}});
  a->write_checkpoint("test_ck.h5");
  a->run(RunOptions{100, 0, {}});
  auto b = make();
  b->read_checkpoint("test_ck.h5");
  b->run(RunOptions{100, 0, {}});
  for (size_t i = 0; i < 15; ++i) EXPECT_EQ(a->nodes().x[i], b->nodes().x[i]);
  // a scene with other node properties cannot take this checkpoint
  Simulation other(2, 9);
  other.add_chain("w", wiggly_chain(15, 2, 8, 0.2), 1.0, false);
  other.set_integrator("verlet", P({{"dt", 0.01}}));
  EXPECT_THROW(other.read_checkpoint("test_ck.h5"), InputError);
  EXPECT_THROW(other.read_checkpoint("does_not_exist.h5"), InputError);
  // a checkpoint of two chains into a scene of one of them: refused, and nothing is read
  // (the second chain's nodes would stay in the arrays as orphans)
  auto two = make();
  two->add_chain("v", wiggly_chain(15, 2, 8, 0.2), 1.0, false);
  two->run(RunOptions{10, 0, {}});
  two->write_checkpoint("test_ck2.h5");
  auto one = make();
  const Vec3 x0 = one->nodes().x[3];
  try {
    one->read_checkpoint("test_ck2.h5");
    ADD_FAILURE() << "a checkpoint with an extra chain was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("has chain 'v' that this scene does not define"),
              std::string::npos)
        << e.what();
  }
  EXPECT_EQ(one->nodes().size(), 15u);
  EXPECT_EQ(one->nodes().x[3], x0);
  std::remove("test_ck.h5");
  std::remove("test_ck2.h5");
}
#endif

// lowest_stiffness (src/stiffness.cpp): the lowest eigenvalue of the difference
// Hessian. A string of stiffness k pulled by F has transverse stiffness F / l at its
// loaded end (and k along it); pushed, -|F| / l: a compressed string is unstable.
TEST(LowestStiffness, StringUnderTensionAndCompression) {
  for (double F : {0.5, -0.5}) {
    Simulation sim(2, 1);
    sim.verbose = false;
    sim.add_chain("s", {Vec3(0, 0, 0), Vec3(2, 0, 0)}, 1.0, false);
    sim.add_bond("spring", P({{"k", 10.0}}));
    sim.set_group("root", {0});
    sim.set_group("tip", {1});
    sim.add_fix("root", "clamp", P({{"group", std::string("root")}}));
    sim.add_fix("pull", "force/constant",
                P({{"group", std::string("tip")}, {"force", std::vector<double>{F, 0.0}}}));
    sim.set_integrator("verlet", P({{"dt", 0.01}}));
    sim.minimize(1e-12, 100000);
    const double l = sim.nodes().x[1].x();
    EXPECT_NEAR(l, 2.0 + F / 10.0, 1e-10);
    const StiffnessResult r = lowest_stiffness(sim, 1e-6);
    EXPECT_EQ(r.dofs, 2);  // the clamped node's components are not degrees of freedom
    EXPECT_NEAR(r.lowest, F / l, 1e-6) << F;
    EXPECT_NEAR(sim.nodes().x[1].x(), l, 1e-15);  // the state is restored
  }
}

// A free, straight, untwisted Cosserat rod: rigid motions and a common twist of the
// frames are free (eigenvalue zero), nothing is negative; frames add three tangent
// degrees of freedom each.
TEST(LowestStiffness, FreeCosseratRodHasZeroModesOnly) {
  Simulation sim(3, 1);
  sim.verbose = false;
  std::vector<Vec3> pts;
  for (int i = 0; i < 6; ++i) pts.emplace_back(0.5 * i, 0.1 * i, 0);
  sim.add_chain("r", pts, 1.0, false);
  sim.add_bond("spring", P({{"k", 100.0}}));
  sim.add_bond("rod/cosserat",
               P({{"YI", 2.0}, {"GJ", 1.5}, {"coupling", 50.0}, {"rot_inertia", 0.1}}));
  const StiffnessResult r = lowest_stiffness(sim, 1e-6);
  EXPECT_EQ(r.dofs, 6 * 3 + 5 * 3);
  EXPECT_NEAR(r.lowest, 0.0, 1e-7);
}

// A thermo interval (time) writes its lines at the same times whatever the step: each
// multiple of the interval once, at the first step that reaches it.
TEST(Thermo, IntervalWritesTheSameTimesAtAnyStep) {
  auto times_at = [](double dt) {
    Simulation s(2, 9);
    s.verbose = false;
    s.add_chain("w", wiggly_chain(5, 2, 8, 0.2), 1.0, false);
    s.add_bond("spring", P({{"k", 200.0}}));
    s.set_integrator("verlet", P({{"dt", dt}}));
    s.thermo.interval = 0.05;
    s.thermo.columns = {"step", "time"};
    s.thermo.file = "thermo_interval.csv";
    s.run(RunOptions{static_cast<long>(std::lround(0.2 / dt)), 0, {}});
    std::ifstream in("thermo_interval.csv");
    std::string line;
    std::getline(in, line);
    std::vector<double> t;
    while (std::getline(in, line)) t.push_back(std::stod(line.substr(line.find(',') + 1)));
    std::remove("thermo_interval.csv");
    return t;
  };
  const auto a = times_at(0.001), b = times_at(0.0005);
  ASSERT_EQ(a.size(), 5u);  // t = 0, 0.05, 0.1, 0.15, 0.2
  ASSERT_EQ(b.size(), 5u);
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_NEAR(a[i], 0.05 * static_cast<double>(i), 1e-9);
    EXPECT_NEAR(b[i], a[i], 1e-9);
  }
  // an interval that no step lands on exactly: one line per multiple passed
  Cadence c{0, 0.3};
  int lines = 0;
  for (int k = 1; k <= 1000; ++k) lines += c.due(k, (k - 1) * 0.007, k * 0.007);
  EXPECT_EQ(lines, static_cast<int>(std::floor(1000 * 0.007 / 0.3)));
  EXPECT_TRUE(c.due_at(0, 0.0));
  EXPECT_FALSE(c.due_at(5, 0.035));
}

// Scene construction through the C++ API (src/scene_build.hpp), as decks reach it: generated
// and explicit wires, groups, and the inputs it refuses instead of ignoring.
TEST(SceneBuild, WiresAndGroupsFromParameters) {
  Simulation sim(2, 1);
  sim.verbose = false;
  Chain& ring = add_wire(sim, P({{"name", std::string("ring")}, {"nodes", 12.0}, {"radius", 3.0}}));
  EXPECT_TRUE(ring.closed);
  EXPECT_NEAR(sim.nodes().x[ring.nodes[3]].y(), 3.0, 1e-12);
  Chain& line =
      add_wire(sim, P({{"name", std::string("line")}, {"nodes", 5.0}, {"spacing", 0.5}}), {});
  EXPECT_EQ(line.n_nodes(), 5);
  EXPECT_DOUBLE_EQ(line.rest_length[0], 0.5);
  EXPECT_EQ(add_group(sim, "ends",
                      P({{"chain", std::string("line")}, {"nodes", std::vector<double>{1, -1}}})),
            2u);
  EXPECT_EQ(sim.group("ends"), (std::vector<int>{line.nodes.front(), line.nodes.back()}));
  const std::size_t before = sim.nodes().size();
  auto refuses = [&](auto&& build, const std::string& says) {
    try {
      build();
      ADD_FAILURE() << "accepted; expected: " << says;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what();
    }
    EXPECT_EQ(sim.nodes().size(), before) << "a refused command left nodes behind";
  };
  refuses(
      [&] {
        add_wire(sim, P({{"name", std::string("p")}, {"nodes", 9.0}}),
                 {Vec3(0, 0, 0), Vec3(1, 0, 0)});
      },
      "'nodes' describes a generated wire");
  refuses(
      [&] {
        add_wire(
            sim,
            P({{"name", std::string("c")}, {"nodes", 9.0}, {"radius", 2.0}, {"closed", false}}));
      },
      "closed = false contradicts it");
  refuses(
      [&] {
        add_wire(
            sim, P({{"name", std::string("inf")}}),
            {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(std::numeric_limits<double>::infinity(), 0, 0)});
      },
      "node 3 has a non-finite position");
  refuses(
      [&] {
        add_wire(sim, P({{"name", std::string("nan")}}), {Vec3(0, 0, 0), Vec3(std::nan(""), 0, 0)});
      },
      "node 2 has a non-finite position");
  refuses(
      [&] {
        add_wire(sim, P({{"name", std::string("same")}}),
                 {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 0, 0)});
      },
      "nodes 2 and 3 coincide");
  refuses(
      [&] {
        add_group(sim, "all", P({{"chain", std::string("line")}}));
      },
      "group 'all' is already defined (17 nodes, every node)");
  refuses(
      [&] {
        add_group(sim, "g", P({{"chain", std::string("line")}, {"nodes", std::vector<double>{6}}}));
      },
      "node index 6 out of range 1..5");
}

#ifdef SLENDER_HAVE_SHELL
// sim:mesh{...} through the C++ API: a generated disc with its ghost layer and groups.
TEST(SceneBuild, MeshFromParameters) {
  Simulation sim(3, 1);
  sim.verbose = false;
  const auto [nodes, tris] = add_mesh(sim, P({{"name", std::string("s")},
                                              {"shape", std::string("disc")},
                                              {"radius", 2.0},
                                              {"edge", 0.5}}));
  EXPECT_GT(nodes, 20);
  EXPECT_GT(tris, nodes);  // a disc triangulation: about twice as many triangles as nodes
  EXPECT_EQ(sim.group("s").size(), static_cast<std::size_t>(nodes));
  EXPECT_TRUE(sim.has_group("s.boundary"));
  EXPECT_GT(sim.nodes().size(), static_cast<std::size_t>(nodes));            // the ghosts
  EXPECT_THROW(add_mesh(sim, P({{"name", std::string("t")}})), InputError);  // no shape, no file
  // an edge the generator cannot reach names edge (not an internal refinement count)
  try {
    add_mesh(sim, P({{"name", std::string("u")}, {"shape", std::string("disc")}, {"edge", 1e-5}}));
    ADD_FAILURE() << "edge = 1e-5 was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(
        std::string(e.what()).find(
            "mesh: edge = 0.000010 on a disc of radius 1.000000 needs 17 refinements, at most 9"),
        std::string::npos)
        << e.what();
  }
  EXPECT_THROW(add_mesh(sim, P({{"name", std::string("r")},
                                {"shape", std::string("rectangle")},
                                {"size", std::vector<double>{10, 10}},
                                {"edge", 1e-3}})),
               InputError);
  // extra refinements multiply the count: a buildable disc refined six more times would be
  // 6e9 triangles; refused before any memory is taken, naming both keys (fuzz finding)
  try {
    add_mesh(sim, P({{"name", std::string("v")},
                     {"shape", std::string("disc")},
                     {"edge", 0.01},
                     {"refine", 6.0}}));
    ADD_FAILURE() << "a disc of 6e9 triangles was attempted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("edge = 0.010000, refine = 6 give a disc of about"),
              std::string::npos)
        << e.what();
  }
  // the core refinement of a disc counts too (a core as wide as the disc, 6 more levels)
  try {
    add_mesh(sim, P({{"name", std::string("w")},
                     {"shape", std::string("disc")},
                     {"edge", 0.002},
                     {"refine_center", 1.0},
                     {"refine_levels", 6.0}}));
    ADD_FAILURE() << "a disc of 4e7 triangles was attempted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("refine_levels = 6 within refine_center"),
              std::string::npos)
        << e.what();
  }
  // and a refinement that stays small is still made
  const auto [n2, t2] = add_mesh(sim, P({{"name", std::string("x")},
                                         {"shape", std::string("disc")},
                                         {"edge", 0.5},
                                         {"refine", 1.0}}));
  // radius 1 at edge 0.5 (one level) refined once is radius 2 at edge 0.5 (two levels)
  EXPECT_EQ(t2, tris);
  EXPECT_EQ(n2, nodes);
}
#endif

// Function-valued parameters (a run callback, a growth law) go through the declaration
// like any other: documented, required or optional, and a value of another type refused.
TEST(ParamSpec, FunctionParametersAreDeclaredAndChecked) {
  ParamSpec s("growth", "function", "test");
  s.add("fn", ParamType::Function, "the law").required();
  EXPECT_NO_THROW(s.validate(RawParams{{"fn", DeckFunction{}}}));
  try {
    s.validate(RawParams{{"fn", 3.0}});
    FAIL() << "a number was accepted as a function";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("must be a Lua function, got a number"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(s.validate(RawParams{}), InputError);
  EXPECT_NE(s.help_text().find("fn (function, required)"), std::string::npos);
  // a function where a number is declared is a type error, not silently dropped
  ParamSpec n("fix", "x", "test");
  n.real("k", "a number");
  EXPECT_THROW(n.validate(RawParams{{"k", DeckFunction{}}}), InputError);
}
