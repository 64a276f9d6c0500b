// Unit tests of the neighbour service (src/neighbors.hpp): one rebuild decision per force
// evaluation for every pair list of a scene, one displacement scan, the smallest skin.
#include <cmath>

#include "helpers.hpp"
#include "neighbors.hpp"

using namespace slender;
using namespace slender::test;

TEST(NeighborService, OneDecisionForAllListsAtTheSmallestSkin) {
  NeighborService n;
  int wide = 0, narrow = 0;  // owners
  const int a = n.request(&wide, 1.0, 0), b = n.request(&narrow, 0.4, 0);
  EXPECT_EQ(n.request(&wide, 1.0, 0), a);  // once per owner
  std::vector<Vec3> x(5, Vec3::Zero());
  for (int k = 0; k < 5; ++k) x[k] = Vec3(k, 0, 0);

  n.begin_evaluation();  // first evaluation: nothing built yet
  EXPECT_TRUE(n.due(a, x, 0));
  EXPECT_TRUE(n.due(b, x, 0));
  n.built(a, 0);
  n.built(b, 0);

  n.begin_evaluation();
  x[3].y() += 0.15;  // below half of either skin
  EXPECT_FALSE(n.due(a, x, 1));
  EXPECT_FALSE(n.due(b, x, 1));

  n.begin_evaluation();
  x[3].y() += 0.1;  // 0.25 from the build: past half the narrow skin, not the wide one
  EXPECT_TRUE(n.due(a, x, 2)) << "lists are rebuilt together";
  EXPECT_TRUE(n.due(b, x, 2));
  n.built(a, 2);
  n.built(b, 2);
  EXPECT_EQ(n.rebuilds(), 2);

  // several queries in one evaluation scan the positions once
  const long scans = n.scans();
  n.begin_evaluation();
  for (int k = 0; k < 4; ++k) {
    EXPECT_FALSE(n.due(a, x, 3));
    EXPECT_FALSE(n.due(b, x, 3));
  }
  EXPECT_EQ(n.scans(), scans + 1);

  // a list the last common build left out (its style re-bound) is due by itself, and a
  // forced rebuild makes every list due
  n.invalidate();
  EXPECT_TRUE(n.due(b, x, 3));
  EXPECT_TRUE(n.due(a, x, 3));

  n.built(a, 3);
  n.built(b, 3);

  // two styles that both force a rebuild in one evaluation (both re-bound at a run's
  // start) get one common rebuild, not a second one that leaves the first list behind
  const long before = n.rebuilds();
  n.begin_evaluation();
  n.invalidate();
  EXPECT_TRUE(n.due(a, x, 3));
  n.built(a, 3);
  n.invalidate();
  EXPECT_TRUE(n.due(b, x, 3));
  n.built(b, 3);
  EXPECT_EQ(n.rebuilds(), before + 1);
  n.begin_evaluation();
  EXPECT_FALSE(n.due(a, x, 4));
  EXPECT_FALSE(n.due(b, x, 4));

  // a node more (a chain grew): everything is rebuilt
  x.push_back(Vec3(9, 9, 0));
  n.begin_evaluation();
  EXPECT_TRUE(n.due(a, x, 4));
}

TEST(NeighborService, FixedIntervalsNeedNoScan) {
  NeighborService n;
  int owner = 0;
  const int h = n.request(&owner, 0.0, 3);  // no skin: the interval alone
  std::vector<Vec3> x(3, Vec3::Zero());
  n.begin_evaluation();
  EXPECT_TRUE(n.due(h, x, 0));
  n.built(h, 0);
  for (long step = 1; step < 3; ++step) {
    n.begin_evaluation();
    x[1].x() += 5.0;  // far beyond the skin: the interval rules, as asked
    EXPECT_FALSE(n.due(h, x, step));
  }
  n.begin_evaluation();
  EXPECT_TRUE(n.due(h, x, 3));
  EXPECT_EQ(n.scans(), 0);
}

// A list with a skin and an interval (the shell contact) is rebuilt by whichever comes first.
TEST(NeighborService, SkinAndIntervalTogether) {
  NeighborService n;
  int owner = 0;
  const int h = n.request(&owner, 1.0, 4);
  std::vector<Vec3> x(3, Vec3::Zero());
  n.begin_evaluation();
  EXPECT_TRUE(n.due(h, x, 0));
  n.built(h, 0);
  n.begin_evaluation();
  x[2].x() += 0.4;  // within half the skin
  EXPECT_FALSE(n.due(h, x, 1));
  n.begin_evaluation();
  x[2].x() += 0.2;  // 0.6 > 0.5: moved too far before the interval is up
  EXPECT_TRUE(n.due(h, x, 2));
  n.built(h, 2);
  for (long step = 3; step < 6; ++step) {
    n.begin_evaluation();
    EXPECT_FALSE(n.due(h, x, step));
  }
  n.begin_evaluation();
  EXPECT_TRUE(n.due(h, x, 6));  // nothing moved, the interval is up
  EXPECT_EQ(n.scans(), 5);      // each evaluation that the interval did not decide scanned
}

// Two contact styles in one scene (self-contact of two separate wires, different skins)
// share the decision: they are rebuilt the same number of times, as often as the service
// decided, and the trajectories equal those with lists rebuilt every step.
TEST(NeighborService, ContactStylesOfOneSceneRebuildTogether) {
  auto run = [](double every) {
    auto sim = std::make_unique<Simulation>(2, 5);
    sim->verbose = false;
    for (int w = 0; w < 2; ++w) {
      std::vector<Vec3> pts;
      double th = 0.0;
      for (int i = 0; i < 40; ++i) {  // a spiral, turns 1.3 d apart, beside the other one
        const double r = 2.5 + 1.3 * th / (2 * M_PI);
        pts.emplace_back(r * std::cos(th) + 20.0 * w, r * std::sin(th), 0);
        th += 1.0 / r;
      }
      sim->add_chain(w == 0 ? "a" : "b", pts, 1.0, false);
    }
    sim->add_bond("spring", P({{"k", 1000.0}}));
    sim->add_bond("bend2d", P({{"k", 60.0}}));
    for (int w = 0; w < 2; ++w)
      sim->add_pair("contact/node-edge",
                    P({{"stiffness", 1e4},
                       {"damping", 10.0},
                       {"chains", std::vector<std::string>{w == 0 ? "a" : "b"}},
                       {"skin", w == 0 ? 1.0 : 0.5},
                       {"rebuild_every", every}}));
    for (auto& v : sim->nodes().v) v = Vec3(0.0, -0.8, 0);
    sim->add_fix("floor", "wall/circle",
                 P({{"radius", 30.0},
                    {"center", std::vector<double>{10.0, 22.0}},
                    {"diameter", 1.0},
                    {"stiffness", 1e4}}));
    sim->set_integrator("verlet", P({{"dt", 0.004}}));
    double most = 0;
    sim->run(RunOptions{2500, 10, [&](Simulation& s) {
                          most = std::max(most, s.pairs()[0]->value("contacts") +
                                                    s.pairs()[1]->value("contacts"));
                          return false;
                        }});
    EXPECT_GE(most, 5.0);  // the wires do touch themselves
    return sim;
  };
  auto a = run(0.0), b = run(1.0);
  for (size_t i = 0; i < a->nodes().size(); ++i) EXPECT_EQ(a->nodes().x[i], b->nodes().x[i]) << i;
  const double builds = a->pairs()[0]->value("builds");
  EXPECT_EQ(a->pairs()[1]->value("builds"), builds);
  EXPECT_EQ(static_cast<double>(a->neighbors().rebuilds()), builds);
  EXPECT_GT(builds, 1.0);
  EXPECT_LT(builds, b->pairs()[0]->value("builds") / 10);
  EXPECT_EQ(a->neighbors().requests(), 2u);
}

TEST(NeighborService, ASceneWithoutContactsScansNothing) {
  Simulation sim(2, 1);
  sim.verbose = false;
  sim.add_chain("w", wiggly_chain(20, 2, 3), 1.0, false);
  sim.add_bond("spring", P({{"k", 100.0}}));
  sim.set_integrator("verlet", P({{"dt", 0.01}}));
  sim.run(RunOptions{50, 0, nullptr});
  EXPECT_EQ(sim.neighbors().requests(), 0u);
  EXPECT_EQ(sim.neighbors().scans(), 0);
  EXPECT_NE(sim.inventory_json().find("\"neighbor_service\": {\"requests\": 0"), std::string::npos);
}
