// Unit tests of the fix styles: walls, constant force, clamp, viscous damping.
// Covers styles/fix/{wall_sphere,force_constant,clamp,viscous}.cpp.
#include <cmath>

#include "helpers.hpp"

using namespace slender;
using namespace slender::test;

TEST(SphereWallFix, ForceMatchesEnergyGradientInside) {
  for (double p : {1.0, 2.0}) {
    Simulation sim(3, 1);
    // nodes near and beyond a sphere of radius 3 centred at (0.5, 0, 0)
    sim.add_chain(
        "w", {Vec3(3.2, 0.3, 0.1), Vec3(0.5, 3.4, 0.2), Vec3(0.1, 0.2, 0.3), Vec3(-2.3, -0.4, 1.2)},
        1.0, false);
    sim.add_fix("wall", "wall/sphere",
                P({{"radius", 3.0},
                   {"stiffness", 50.0},
                   {"exponent", p},
                   {"diameter", 1.0},
                   {"center", std::vector<double>{0.5, 0, 0}}}));
    sim.compute_forces();
    EXPECT_GT(sim.energies().at("external"), 0.0) << p;
    EXPECT_LT(fd_force_error(sim), 1e-6) << p;
    // the node at the centre region feels nothing; the overlapping ones are pushed inward
    EXPECT_EQ(sim.nodes().f[2].norm(), 0.0);
    EXPECT_LT(sim.nodes().f[1].y(), 0.0);
    EXPECT_DOUBLE_EQ(sim.fix("wall").value("contacts"), 3.0);
  }
}

TEST(SphereWallFix, QuadraticLawValueAndOutsideSide) {
  Simulation sim(2, 1);
  sim.add_chain("w", {Vec3(10.2, 0, 0), Vec3(0, 0, 0)}, 1.0, false);
  sim.add_fix("cavity", "wall/circle",
              P({{"radius", 10.0}, {"stiffness", 1e4}, {"exponent", 2.0}, {"diameter", 1.0}}));
  sim.compute_forces();
  // overlap = 10.2 + 0.5 - 10 = 0.7 -> F = k 0.49 along -x (docs/models.md §2.3)
  EXPECT_NEAR(sim.nodes().f[0].x(), -1e4 * 0.49, 1e-8);
  Simulation out(2, 1);
  out.add_chain("w", {Vec3(1.2, 0, 0), Vec3(5, 0, 0)}, 1.0, false);
  out.add_fix("post", "wall/circle",
              P({{"radius", 1.0},
                 {"stiffness", 10.0},
                 {"exponent", 1.0},
                 {"side", std::string("outside")}}));
  out.compute_forces();
  EXPECT_EQ(out.nodes().f[0].norm(), 0.0);  // at 1.2 > R, no overlap with a zero diameter
  out.nodes().x[0] = Vec3(0.8, 0, 0);
  out.compute_forces();
  EXPECT_NEAR(out.nodes().f[0].x(), 10.0 * 0.2, 1e-12);  // pushed outward
  EXPECT_LT(fd_force_error(out), 1e-6);
}

TEST(ConstantForceFix, EnergyIsMinusWorkAndRampsInTime) {
  Simulation sim(2, 1);
  sim.add_chain("w", wiggly_chain(4, 2, 3), 1.0, false);
  sim.set_group("ends", {0, 3});
  sim.add_fix("load", "force/constant",
              P({{"group", std::string("ends")},
                 {"force", std::vector<double>{1.0, -2.0}},
                 {"rate", std::vector<double>{0.5, 0.0}}}));
  sim.nodes().x[0] += Vec3(0.3, 0.1, 0);
  EXPECT_LT(fd_force_error(sim), 1e-6);
  sim.compute_forces();
  EXPECT_NEAR(sim.energies().at("external"), -(1.0 * 0.3 - 2.0 * 0.1), 1e-12);
  EXPECT_EQ(sim.nodes().f[1].norm(), 0.0);
  sim.time = 2.0;
  sim.compute_forces();
  EXPECT_NEAR(sim.nodes().f[3].x(), 1.0 + 0.5 * 2.0, 1e-12);
  EXPECT_THROW(
      sim.add_fix("x", "force/constant",
                  P({{"group", std::string("nope")}, {"force", std::vector<double>{1, 0}}})),
      InputError);
  // a z component in a 2D scene would be dropped: refused, also through sim:modify; a 3-vector
  // in the plane is fine
  try {
    sim.add_fix("down", "force/constant",
                P({{"group", std::string("ends")}, {"force", std::vector<double>{0, 0, -1}}}));
    ADD_FAILURE() << "a z load in 2D was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("z component in a 2D scene"), std::string::npos)
        << e.what();
  }
  sim.add_fix("flat", "force/constant",
              P({{"group", std::string("ends")}, {"force", std::vector<double>{0, -1, 0}}}));
  EXPECT_THROW(sim.fix("flat").modify(P({{"rate", std::vector<double>{0, 0, 1}}})), InputError);
}

// A table of per-node forces (`forces`): node k of the group gets its own vector (plus the
// ramp), the energy is their potential, the load factor of a continuation scales the
// table, a checkpoint keeps it, and a table of the wrong length is refused in the
// deck's words.
TEST(ConstantForceFix, PerNodeTable) {
  Simulation sim(2, 1);
  sim.add_chain("w", wiggly_chain(4, 2, 3), 1.0, false);
  sim.set_group("ends", {0, 3});
  sim.add_fix("load", "force/constant",
              P({{"group", std::string("ends")},
                 {"forces", std::vector<double>{1.0, -2.0, 0.0, 3.0}},
                 {"rate", std::vector<double>{0.5, 0.0}}}));
  sim.nodes().x[0] += Vec3(0.3, 0.1, 0);
  sim.nodes().x[3] += Vec3(-0.2, 0.4, 0);
  EXPECT_LT(fd_force_error(sim), 1e-6);
  sim.compute_forces();
  EXPECT_NEAR(sim.energies().at("external"), -(1.0 * 0.3 - 2.0 * 0.1) - 3.0 * 0.4, 1e-12);
  EXPECT_EQ(sim.nodes().f[0], Vec3(1.0, -2.0, 0.0));
  EXPECT_EQ(sim.nodes().f[3], Vec3(0.0, 3.0, 0.0));
  EXPECT_NEAR(sim.fix("load").value("fy"), 1.0, 1e-15);  // the total over the group
  sim.time = 2.0;
  sim.compute_forces();
  EXPECT_NEAR(sim.nodes().f[3].x(), 0.5 * 2.0, 1e-12);
  ASSERT_TRUE(sim.fix("load").set_continuation_parameter(0.5));
  sim.time = 0.0;
  sim.compute_forces();
  EXPECT_NEAR(sim.nodes().f[3].y(), 1.5, 1e-15);
  StateMap st;
  sim.fix("load").save_state(st);
  sim.fix("load").modify(P({{"forces", std::vector<double>{0, 0, 0, 0}}}));
  sim.fix("load").load_state(st);
  sim.compute_forces();
  EXPECT_NEAR(sim.nodes().f[0].y(), -1.0, 1e-15);
  auto message = [&](RawParams p) {
    try {
      sim.add_fix("bad", "force/constant", p);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(message(P({{"group", std::string("ends")}, {"forces", std::vector<double>{1, 2, 3}}}))
                .find("holds 3 numbers; group 'ends' has 2 nodes, so it needs 4"),
            std::string::npos);
  EXPECT_NE(message(P({{"group", std::string("ends")},
                       {"force", std::vector<double>{1, 2}},
                       {"forces", std::vector<double>{1, 2, 3, 4}}}))
                .find("not both"),
            std::string::npos);
  EXPECT_NE(message(P({{"group", std::string("ends")}})).find("one of them"), std::string::npos);
}

TEST(ClampFix, ClampedComponentsNeverMove) {
  Simulation sim(2, 7);
  sim.verbose = false;
  sim.add_chain("w", wiggly_chain(12, 2, 9, 0.2), 1.0, false);
  sim.add_bond("spring", P({{"k", 100.0}}));
  sim.add_bond("bend2d", P({{"k", 10.0}}));
  sim.set_group("first", {0});
  sim.set_group("last", {11});
  sim.add_fix("root", "clamp", P({{"group", std::string("first")}, {"rotation", true}}));
  sim.add_fix("slide", "clamp",
              P({{"group", std::string("last")}, {"components", std::string("y")}}));
  const Vec3 x0 = sim.nodes().x[0], x1 = sim.nodes().x[1], x11 = sim.nodes().x[11];
  for (auto* integ : {"verlet", "gear", "fire"}) {
    sim.set_integrator(integ, P({{"dt", 0.005}}));
    sim.run(RunOptions{500, 0, {}});
    EXPECT_EQ(sim.nodes().x[0], x0) << integ;
    EXPECT_EQ(sim.nodes().x[1], x1) << integ << ": rotation clamp holds the neighbour";
    EXPECT_EQ(sim.nodes().x[11].y(), x11.y()) << integ;
  }
  EXPECT_NE(sim.nodes().x[11].x(), x11.x());  // the free component did move
  EXPECT_THROW(sim.add_fix("bad", "clamp",
                           P({{"group", std::string("first")}, {"components", std::string("xw")}})),
               InputError);
}

// sim:unfix on a clamp releases its nodes; a second clamp of the same node keeps holding
// the components it clamps (each clamp sets its own mask bits).
TEST(ClampFix, UnfixReleasesTheNodesAndKeepsOtherClamps) {
  Simulation sim(2, 7);
  sim.verbose = false;
  sim.add_chain("w", wiggly_chain(6, 2, 3, 0.1), 1.0, false);
  sim.add_bond("spring", P({{"k", 100.0}}));
  sim.set_group("first", {0});
  sim.add_fix("root", "clamp", P({{"group", std::string("first")}}));
  sim.add_fix("root_y", "clamp",
              P({{"group", std::string("first")}, {"components", std::string("y")}}));
  sim.add_fix("load", "force/constant",
              P({{"group", std::string("all")}, {"force", std::vector<double>{1.0, 1.0}}}));
  sim.set_integrator("verlet", P({{"dt", 0.01}}));
  const Vec3 x0 = sim.nodes().x[0];
  sim.run(RunOptions{100, 0, {}});
  EXPECT_EQ(sim.nodes().x[0], x0);
  sim.remove_fix("root");
  sim.run(RunOptions{100, 0, {}});
  EXPECT_GT(sim.nodes().x[0].x(), x0.x() + 0.1) << "released in x";
  EXPECT_EQ(sim.nodes().x[0].y(), x0.y()) << "root_y still holds y";
  sim.remove_fix("root_y");
  sim.run(RunOptions{100, 0, {}});
  EXPECT_GT(sim.nodes().x[0].y(), x0.y() + 0.1) << "released in y";
}

TEST(ViscousDampingFix, ForceIsMinusGammaV) {
  Simulation sim(3, 1);
  sim.add_chain("w", wiggly_chain(3, 3, 1), 2.0, false);
  sim.nodes().v[1] = Vec3(1, -2, 3);
  sim.add_fix("drag", "damping/viscous", P({{"gamma", 0.5}}));
  for (auto& f : sim.fixes()) f->setup(sim.context());
  sim.nodes().f[1].setZero();
  sim.fix("drag").post_force(sim.context());
  EXPECT_EQ(sim.nodes().f[1], Vec3(-0.5, 1.0, -1.5));
  EXPECT_NEAR(sim.fix("drag").max_frequency(sim.context()), 0.25, 1e-15);
}
