// Prescribed motion (fix prescribe, styles/fix/prescribe.cpp; docs/models.md §9.5):
// displacement control in statics and continuation, rotations, the ramp of a dynamic run.
#include <cmath>
#include <memory>

#include "context.hpp"
#include "continuation.hpp"
#include "helpers.hpp"
#include "quaternion_rod.hpp"

using namespace slender;
using namespace slender::test;

namespace {

// A clamped 2D wire along x with EI = 1, EA = 1e5 and length L = 1 from the staggered clamp
// (the cantilever of examples/validation/cantilever2d.lua), nodes + 1 nodes.
std::unique_ptr<Simulation> cantilever(int nodes) {
  auto sim = std::make_unique<Simulation>(2, 1);
  sim->verbose = false;
  const double h = 1.0 / (nodes - 0.5);
  std::vector<Vec3> pts;
  for (int i = 0; i <= nodes; ++i) pts.emplace_back(-h / 2 + i * h, 0.0, 0.0);
  sim->add_chain("beam", pts, h, false);
  sim->add_bond("spring", P({{"k", 1e5 / h}}));
  sim->add_bond("bend2d", P({{"k", 1.0 / h}}));
  sim->set_group("base", {0, 1});
  sim->set_group("tip", {nodes});
  sim->add_fix("clamp", "clamp", P({{"group", std::string("base")}}));
  return sim;
}

}  // namespace

TEST(PrescribeFix, TipDeflectionGivesTheCantileversReaction) {
  // the tip held at w = -1e-3 (y only; x free): the support pushes with 3 EI w / L^3, the
  // tip force of Euler-Bernoulli for that deflection (the discrete wire converges as h^2)
  const double w = 1e-3;
  auto sim = cantilever(40);
  sim->add_fix("move", "prescribe",
               P({{"group", std::string("tip")},
                  {"displacement", std::vector<double>{0.0, -w}},
                  {"components", std::string("y")}}));
  sim->set_integrator("newton", {});
  sim->minimize(1e-10, 100, "newton");
  EXPECT_DOUBLE_EQ(sim->nodes().x[40].y(), -w);
  const double reaction = sim->fix("move").value("reaction_y");
  EXPECT_NEAR(reaction, -3.0 * w, 2e-3 * 3.0 * w);               // the support pulls the tip down
  EXPECT_NEAR(sim->fix("move").value("reaction_x"), 0.0, 1e-9);  // x is not held: no reaction
  // the load factor moves the held nodes at once (before any evaluation)
  sim->fix("move").set_continuation_parameter(0.5);
  EXPECT_DOUBLE_EQ(sim->nodes().x[40].y(), -0.5 * w);
}

TEST(PrescribeFix, ContinuationDrivesTheTipThroughLargeDeflections) {
  // sim:continuation with the prescribed tip as its load: lambda is the share of the tip's
  // descent w = 0.3 L. At small lambda the reaction is the linear 3 EI w / L^3; at the
  // end it equals a direct Newton solve at the full descent (a path-independent elastic
  // state); no point is unstable (the free components are held by the wire's stiffness)
  const double w = 0.3;
  auto drive = [&](Simulation& s) {
    s.add_fix("move", "prescribe",
              P({{"group", std::string("tip")},
                 {"displacement", std::vector<double>{0.0, -w}},
                 {"components", std::string("y")}}));
  };
  auto sim = cantilever(20);
  drive(*sim);
  ContinuationOptions opt;
  opt.load = "move";
  opt.ds = 0.01;
  opt.ds_max = 0.05;
  opt.points = 500;
  opt.ftol = 1e-8;  // the axial springs (EA = 1e5) leave round-off above 1e-10
  opt.lambda_max = 1.0;
  double first_ratio = 0.0, last = 0.0;
  long unstable = 0;
  opt.callback = [&](Simulation& s, const ContinuationPoint& p) {
    EXPECT_NEAR(s.nodes().x[20].y(), -w * p.lambda, 1e-12);
    if (p.index == 1) first_ratio = s.fix("move").value("reaction_y") / (-3.0 * w * p.lambda);
    unstable += p.negative_pivots;
    last = p.lambda;
    return p.lambda >= 1.0 - 1e-12;
  };
  continuation(*sim, opt);
  EXPECT_NEAR(first_ratio, 1.0, 0.02);
  EXPECT_EQ(unstable, 0);
  ASSERT_GT(last, 0.999);
  sim->fix("move").set_continuation_parameter(1.0);  // back from the step past lambda_max
  sim->compute_forces();
  sim->set_integrator("newton", {});
  sim->minimize(1e-8, 100, "newton");
  const double along_path = sim->fix("move").value("reaction_y");
  auto direct = cantilever(20);
  drive(*direct);
  direct->set_integrator("newton", {});
  direct->minimize(1e-8, 100, "newton");
  EXPECT_NEAR(along_path, direct->fix("move").value("reaction_y"), 1e-6 * std::abs(along_path));
  // large deflection: stiffer than linear (the wire also shortens its reach)
  EXPECT_LT(along_path, -3.0 * w);
}

TEST(PrescribeFix, RotatesAGroupAboutAnAxisAndRampsInADynamicRun) {
  Simulation sim(2, 1);
  sim.verbose = false;
  sim.add_chain("bar", {Vec3(1, 0, 0), Vec3(2, 0, 0), Vec3(3, 0, 0)}, 1.0, false);
  sim.add_bond("spring", P({{"k", 10.0}}));
  sim.set_group("ends", {0, 2});
  // a quarter turn about z through (2, 0) and a shift of (0, 1), over 20 time units
  sim.add_fix("turn", "prescribe",
              P({{"group", std::string("ends")},
                 {"angle", M_PI / 2},
                 {"center", std::vector<double>{2.0, 0.0}},
                 {"displacement", std::vector<double>{0.0, 1.0}},
                 {"duration", 20.0}}));
  sim.set_integrator("verlet", P({{"dt", 0.01}}));
  sim.run(RunOptions{1000, 0, {}});  // half the ramp: an eighth of a turn, half the shift
  const double s = sim.fix("turn").value("factor");
  EXPECT_NEAR(s, 0.5, 1e-9);
  const double c = std::cos(M_PI / 4), sn = std::sin(M_PI / 4);
  EXPECT_NEAR((sim.nodes().x[0] - Vec3(2 - c, -sn + 0.5, 0)).norm(), 0.0, 1e-9);
  EXPECT_NEAR((sim.nodes().x[2] - Vec3(2 + c, sn + 0.5, 0)).norm(), 0.0, 1e-9);
  // the held nodes move along the path: at mid-ramp d(smoothstep)/dtau = 1.5, so the end
  // node's speed is 1.5 times the path's per unit of the factor, over the duration
  EXPECT_NEAR(sim.nodes().v[2].y(), 1.5 * (M_PI / 2 * c + 1.0) / 20.0, 1e-3);
  sim.run(RunOptions{1200, 0, {}});  // past the ramp: at rest at the end of the path
  EXPECT_NEAR((sim.nodes().x[2] - Vec3(2, 2, 0)).norm(), 0.0, 1e-9);
  EXPECT_NEAR(sim.nodes().v[2].norm(), 0.0, 1e-12);
  // the middle node is free: the springs pull it along, it stays finite
  EXPECT_TRUE(sim.nodes().x[1].allFinite());
}

TEST(PrescribeFix, TwistsARodEndByAnAngleAndHoldsItsFrames) {
  // a straight Cosserat rod along x, its first edges held (angle 0) and its last edge's
  // frame turned by Theta about the axis: relaxed, the twist is uniform over the hinges
  // between the held edges, E = m (l / 2) GJ (2 sin(Theta / 2m) / l)^2 for m hinges of
  // length l (the discrete torsion of docs/models.md §4.3), -> GJ Theta^2 / 2 L
  const int n = 12;
  const double l = 0.5, GJ = 1.5, theta = 1.2;
  Simulation sim(3, 1);
  straight_cosserat_rod(sim, n, l, GJ);
  sim.set_group("root", {0, 1});
  sim.set_group("end", {n - 2, n - 1});
  sim.add_fix("hold", "prescribe", P({{"group", std::string("root")}, {"frames", true}}));
  sim.add_fix("twist", "prescribe",
              P({{"group", std::string("end")},
                 {"angle", theta},
                 {"axis", std::vector<double>{1.0, 0.0, 0.0}},
                 {"frames", true}}));
  const long steps = sim.minimize(1e-9, 400000);
  EXPECT_LT(steps, 400000);
  // the root group {0, 1} holds the frames of edges 0 and 1, the end group those of the
  // last edge n - 2 (and node n - 1's unused slot): m = n - 3 hinges between edges 1, n - 2
  const int m = n - 3;
  const double discrete = m * (l / 2) * GJ * std::pow(2 * std::sin(theta / (2 * m)) / l, 2);
  EXPECT_NEAR(sim.energies().at("twist"), discrete, 1e-6 * discrete);
  EXPECT_NEAR(discrete, GJ * theta * theta / (2 * m * l), 2e-3 * discrete);
  // the end frame is the root's turned by Theta about the axis (d3 along it), and the
  // positions did not move
  auto& q = sim.coordinates("rod.q").q->values();
  EXPECT_NEAR((qrod::d3(q[n - 2]) - Vec3(1, 0, 0)).norm(), 0.0, 1e-9);
  const Vec3 a0 = qrod::d1(q[0]), a1 = qrod::d1(q[n - 2]);
  EXPECT_NEAR(std::atan2(a0.cross(a1).dot(Vec3(1, 0, 0)), a0.dot(a1)), theta, 1e-9);
  for (int i = 0; i < n; ++i) EXPECT_NEAR((sim.nodes().x[i] - Vec3(l * i, 0, 0)).norm(), 0.0, 1e-6);
  // without a rod, frames = true is refused at the first evaluation
  Simulation bare(3, 1);
  bare.verbose = false;
  bare.add_chain("w", {Vec3(0, 0, 0), Vec3(1, 0, 0)}, 1.0, false);
  bare.add_bond("spring", P({{"k", 1.0}}));
  bare.set_group("one", {1});
  bare.add_fix("t", "prescribe", P({{"group", std::string("one")}, {"frames", true}}));
  EXPECT_THROW(bare.compute_forces(), InputError);
}

TEST(PrescribeFix, RefusesBadInput) {
  Simulation sim(2, 1);
  sim.verbose = false;
  sim.add_chain("bar", {Vec3(0, 0, 0), Vec3(1, 0, 0)}, 1.0, false);
  sim.set_group("one", {1});
  EXPECT_THROW(sim.add_fix("a", "prescribe",
                           P({{"group", std::string("one")}, {"components", std::string("xq")}})),
               InputError);
  EXPECT_THROW(sim.add_fix("b", "prescribe",
                           P({{"group", std::string("one")},
                              {"angle", 1.0},
                              {"axis", std::vector<double>{1.0, 0.0, 0.0}}})),
               InputError);  // 2D turns about z
}
