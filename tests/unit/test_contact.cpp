// Unit tests of the shared contact law through contact/node-edge and wall/circle
// Covers styles/pair/contact_node_edge.cpp, src/contact_law.hpp and the friction of
// styles/fix/wall_sphere.cpp. (docs/models.md §2.3).
#include <cmath>
#include <memory>

#include "contact_law.hpp"
#include "helpers.hpp"

using namespace std::string_literals;

using namespace slender;
using namespace slender::test;

namespace {

// Two wires lying across each other with several overlapping node-edge pairs.
void crossing_scene(Simulation& sim) {
  std::vector<Vec3> a, b;
  for (int i = 0; i < 8; ++i) a.emplace_back(i * 0.9, 0.05 * std::sin(i), 0);
  for (int i = 0; i < 8; ++i) b.emplace_back(0.2 + i * 0.85, 0.75 + 0.04 * std::cos(2 * i), 0);
  sim.add_chain("a", a, 1.0, false);
  sim.add_chain("b", b, 1.0, false);
}

}  // namespace

TEST(NodeEdgeContactPair, NormalForceMatchesEnergyGradient) {
  for (double p : {1.0, 2.0}) {
    Simulation sim(2, 1);
    crossing_scene(sim);
    sim.add_pair("contact/node-edge", P({{"diameter", 1.0}, {"stiffness", 1e3}, {"exponent", p}}));
    sim.compute_forces();
    EXPECT_GE(sim.pairs()[0]->value("contacts"), 6.0);
    EXPECT_GT(sim.energies().at("contact"), 0.0);
    EXPECT_LT(fd_force_error(sim, 1e-7), 1e-5) << "p = " << p;
  }
}

TEST(NodeEdgeContactPair, ConservesMomentumWithFrictionAndDamping) {
  Simulation sim(2, 1);
  crossing_scene(sim);
  std::mt19937 g(3);
  std::uniform_real_distribution<double> u(-1, 1);
  for (auto& v : sim.nodes().v) v = Vec3(u(g), u(g), 0);
  sim.dt = 0.01;
  sim.add_pair("contact/node-edge", P({{"stiffness", 1e3},
                                       {"damping", 5.0},
                                       {"mu_static", 0.6},
                                       {"mu_dynamic", 0.5},
                                       {"slip_velocity", 0.5}}));
  for (int rep = 0; rep < 5; ++rep) {  // stick springs build up over evaluations
    sim.compute_forces();
    Vec3 sum = Vec3::Zero();
    double fmax = 0;
    for (auto& f : sim.nodes().f) {
      sum += f;
      fmax = std::max(fmax, f.norm());
    }
    EXPECT_GT(fmax, 1.0);
    EXPECT_LT(sum.norm(), 1e-13 * fmax);
    for (auto& x : sim.nodes().x) x += 0.002 * Vec3(1, -0.5, 0);
  }
}

TEST(NodeEdgeContactPair, CrossingWiresDoNotPassThrough) {
  for (double speed : {0.05, 0.2, 0.5, 3.0}) {
    Simulation sim(2, 1);
    sim.verbose = false;
    std::vector<Vec3> floor, stick;
    for (int i = 0; i <= 20; ++i) floor.emplace_back(-10.0 + i, 0, 0);
    for (int i = 0; i < 5; ++i)
      stick.emplace_back(0.5, 3.0 + i, 0);  // vertical, falling on an edge
    sim.add_chain("floor", floor, 1.0, false);
    sim.add_chain("stick", stick, 1.0, false);
    sim.add_bond("spring", P({{"k", 1000.0}}));
    sim.add_bond("bend2d", P({{"k", 60.0}}));
    sim.add_pair("contact/node-edge", P({{"stiffness", 1e4}, {"damping", 20.0}}));
    sim.add_fix("hold", "clamp", P({{"group", std::string("floor")}}));
    for (int i : sim.group("stick")) sim.nodes().v[i] = Vec3(0, -speed, 0);
    sim.set_integrator("gear", P({{"dt", "auto"s}}));
    double ymin = 1e9;
    sim.run(RunOptions{static_cast<long>(8.0 / speed / 0.002), 200, [&](Simulation& s) {
                         for (int i : s.group("stick")) ymin = std::min(ymin, s.nodes().x[i].y());
                         return false;
                       }});
    // the lowest node stops at about one diameter above the floor's edge
    EXPECT_GT(ymin, 0.5) << "speed " << speed;
    EXPECT_LT(ymin, 1.0) << "speed " << speed;
  }
}

TEST(NodeEdgeContactPair, OverloadedContactHoldsInsteadOfTunnelling) {
  // a load beyond k_c d^2 pushes the nodes past the edge's centre line; the contact
  // remembers the side it was made from and keeps pushing back, so the block is
  // held within a diameter of the floor instead of tunnelling through it
  Simulation sim(2, 1);
  sim.verbose = false;
  sim.add_chain("floor", {Vec3(-50, 0, 0), Vec3(50, 0, 0)}, 1.0, false);
  sim.add_chain("block", {Vec3(-0.5, 0.95, 0), Vec3(0.5, 0.95, 0)}, 1.0, false);
  sim.add_fix("hold", "clamp", P({{"group", std::string("floor")}}));
  sim.add_bond("spring", P({{"k", 100.0}, {"chains", std::vector<std::string>{"block"}}}));
  sim.add_pair("contact/node-edge", P({{"stiffness", 100.0}, {"damping", 20.0}}));
  sim.add_fix("press", "force/constant",
              P({{"group", std::string("block")}, {"force", std::vector<double>{0, -150.0}}}));
  sim.guard.max_step_fraction = 1e300;
  sim.guard.ke_factor = 1e300;
  sim.set_integrator("verlet", P({{"dt", 0.005}}));
  sim.run(RunOptions{4000, 0, {}});
  for (int i : sim.group("block")) {
    EXPECT_GT(sim.nodes().x[i].y(), -1.0);
    // held where k_c (d + |y|)^2 = F: |y| = sqrt(1.5) - 1
    EXPECT_NEAR(sim.nodes().x[i].y(), -(std::sqrt(1.5) - 1.0), 0.02);
  }
}

namespace {

// A two-node block resting on a clamped floor edge, pressed down by N per node and
// pulled sideways by a slowly growing force; returns T/N when it starts to slide.
double slip_ratio(double mu_s, bool wall) {
  Simulation sim(2, 1);
  sim.verbose = false;
  const double N = 1.0, rate = 2e-3;
  if (wall) {
    // nodes inside a big circle, touching it at the bottom
    sim.add_chain("block", {Vec3(-0.5, -99.5, 0), Vec3(0.5, -99.5, 0)}, 1.0, false);
    sim.add_fix("wall", "wall/circle",
                P({{"radius", 100.0},
                   {"diameter", 1.0},
                   {"stiffness", 1e3},
                   {"damping", 10.0},
                   {"mu_static", mu_s},
                   {"stick_stiffness", 100.0}}));
  } else {
    sim.add_chain("floor", {Vec3(-50, 0, 0), Vec3(50, 0, 0)}, 1.0, false);
    sim.add_chain("block", {Vec3(-0.5, 0.99, 0), Vec3(0.5, 0.99, 0)}, 1.0, false);
    sim.add_fix("hold", "clamp", P({{"group", std::string("floor")}}));
    sim.add_pair("contact/node-edge", P({{"stiffness", 1e3},
                                         {"damping", 10.0},
                                         {"mu_static", mu_s},
                                         {"stick_stiffness", 100.0}}));
  }
  sim.add_bond("spring", P({{"k", 100.0}, {"chains", std::vector<std::string>{"block"}}}));
  sim.add_fix("press", "force/constant",
              P({{"group", std::string("block")}, {"force", std::vector<double>{0, -N}}}));
  sim.set_integrator("verlet", P({{"dt", 0.01}}));
  sim.run(RunOptions{2000, 0, {}});  // settle under the normal load
  // then pull sideways with a force growing from zero
  sim.add_fix("pull", "force/constant",
              P({{"group", std::string("block")},
                 {"force", std::vector<double>{0, 0}},
                 {"rate", std::vector<double>{rate, 0}}}));
  const double x0 = sim.nodes().x[sim.group("block")[0]].x(), t0 = sim.time;
  double ratio = -1;
  sim.run(RunOptions{1000000, 10, [&](Simulation& s) {
                       if (std::abs(s.nodes().x[s.group("block")[0]].x() - x0) > 0.05) {
                         ratio = rate * (s.time - t0) / N;
                         return true;
                       }
                       return false;
                     }});
  return ratio;
}

}  // namespace

TEST(NodeEdgeContactPair, StickSlipTransitionAtTheStaticCoefficient) {
  for (double mu : {0.2, 0.5}) {
    const double r = slip_ratio(mu, false);
    EXPECT_NEAR(r, mu, 0.03 * mu + 0.005) << "mu_static " << mu;
  }
  // frictionless: it slides at once (0.05 in t = (0.3 / rate)^(1/3) gives T/N ~ 0.011)
  EXPECT_LT(slip_ratio(0.0, false), 0.02);
}

TEST(NodeEdgeContactPair, ASlidingBlockStopsAndStaysStuck) {
  // dynamic friction decelerates the block; when its velocity reverses within a step
  // the contact sticks again instead of chattering with the full force mu_d N
  Simulation sim(2, 1);
  sim.verbose = false;
  sim.add_chain("floor", {Vec3(-50, 0, 0), Vec3(50, 0, 0)}, 1.0, false);
  sim.add_chain("block", {Vec3(-0.5, 0.97, 0), Vec3(0.5, 0.97, 0)}, 1.0, false);
  sim.add_fix("hold", "clamp", P({{"group", std::string("floor")}}));
  sim.add_bond("spring", P({{"k", 100.0}, {"chains", std::vector<std::string>{"block"}}}));
  sim.add_pair(
      "contact/node-edge",
      P({{"stiffness", 1e3}, {"damping", 10.0}, {"mu_static", 0.5}, {"stick_stiffness", 100.0}}));
  sim.add_fix("press", "force/constant",
              P({{"group", std::string("block")}, {"force", std::vector<double>{0, -1.0}}}));
  sim.set_integrator("verlet", P({{"dt", 0.01}}));
  sim.run(RunOptions{2000, 0, {}});  // settle
  for (int i : sim.group("block")) sim.nodes().v[i].x() = 0.5;
  sim.run(RunOptions{3000, 0, {}});  // slides about v^2 / (2 mu_d g) = 0.28, then stops
  const Vec3 x = sim.nodes().x[sim.group("block")[0]];
  double vmax = 0.0;
  sim.run(RunOptions{2000, 1, [&](Simulation& s) {
                       for (int i : s.group("block"))
                         vmax = std::max(vmax, std::abs(s.nodes().v[i].x()));
                       return false;
                     }});
  EXPECT_NEAR(x.x(), -0.5 + 0.25 / (2 * 0.45), 0.05);  // it did slide and stop
  // stuck: it only rings on the (undamped) stick spring, far below the sliding speed
  EXPECT_LT(vmax, 0.01);
  EXPECT_LT(std::abs(sim.nodes().x[sim.group("block")[0]].x() - x.x()), 1e-3);
}

TEST(ContactLaw, SlipThatReversesSticksAgain) {
  ContactLaw law;
  law.stiffness = 1e3;
  law.mu_static = 0.5;
  law.mu_dynamic = 0.45;
  law.stick_stiffness = 100.0;
  law.slip_velocity = 1e-4;
  FrictionState st;
  st.active = true;
  st.stick = false;
  st.xi = Vec3(1, 0, 0);  // slipping along +x
  const Vec3 n(0, 1, 0);
  double fn = 0.0;
  Vec3 f = law.force(0.1, n, Vec3(0.01, 0, 0), 0.01, st, &fn);
  EXPECT_NEAR(f.x(), -0.45 * fn, 1e-12);  // full dynamic friction against the motion
  EXPECT_FALSE(st.stick);
  // the tangential velocity reversed: it passed through rest, so it sticks again and
  // feels only the fresh stick spring, not mu_d N in the other direction
  f = law.force(0.1, n, Vec3(-0.01, 0, 0), 0.01, st, &fn);
  EXPECT_TRUE(st.stick);
  EXPECT_NEAR(f.x(), 100.0 * 0.01 * 0.01, 1e-12);
}

// new_contacts: a contact that is made while sliding fast starts stuck by default (the
// fresh stick spring), and slipping (mu_d N against the motion) with "by_speed" unless it
// is slower than v_th (docs/models.md §2.3).
TEST(ContactLaw, NewContactsStickOrFollowTheirSpeed) {
  ContactLaw law;
  law.stiffness = 1e3;
  law.mu_static = 0.5;
  law.mu_dynamic = 0.45;
  law.stick_stiffness = 100.0;
  law.slip_velocity = 1e-3;
  const Vec3 n(0, 1, 0);
  double fn = 0.0;
  FrictionState a;  // new (not active)
  Vec3 f = law.force(0.1, n, Vec3(0.01, 0, 0), 0.01, a, &fn);
  EXPECT_TRUE(a.stick);
  EXPECT_NEAR(f.x(), -100.0 * 0.01 * 0.01, 1e-12);  // the stick spring stretched by v dt
  law.new_stick_always = false;
  FrictionState b;
  f = law.force(0.1, n, Vec3(0.01, 0, 0), 0.01, b, &fn);
  EXPECT_FALSE(b.stick);
  EXPECT_NEAR(f.x(), -0.45 * fn, 1e-12);  // slipping from the first contact
  FrictionState c;                        // slower than v_th: sticks as before
  f = law.force(0.1, n, Vec3(5e-4, 0, 0), 0.01, c, &fn);
  EXPECT_TRUE(c.stick);
  EXPECT_NEAR(f.x(), -100.0 * 5e-4 * 0.01, 1e-12);
  // the deck key
  ParamSpec s("pair", "t", "test");
  ContactLaw::declare(s);
  EXPECT_TRUE(ContactLaw::from(s.validate(RawParams{{"stiffness", 1.0}}), 1.0).new_stick_always);
  EXPECT_FALSE(
      ContactLaw::from(
          s.validate(RawParams{{"stiffness", 1.0}, {"new_contacts", std::string("by_speed")}}), 1.0)
          .new_stick_always);
  EXPECT_THROW(s.validate(RawParams{{"stiffness", 1.0}, {"new_contacts", std::string("slip")}}),
               InputError);
}

TEST(SphereWallFix, StickSlipTransitionAtTheStaticCoefficient) {
  EXPECT_NEAR(slip_ratio(0.4, true), 0.4, 0.02);
}

TEST(NodeEdgeContactPair, RebuildPoliciesGiveIdenticalTrajectories) {
  auto run = [](double every) {
    auto sim = std::make_unique<Simulation>(2, 5);
    sim->verbose = false;
    // an Archimedean spiral, turns 1.3 d apart, nodes 1 d apart along it
    std::vector<Vec3> pts;
    double th = 0.0;
    for (int i = 0; i < 60; ++i) {
      const double r = 2.5 + 1.3 * th / (2 * M_PI);
      pts.emplace_back(r * std::cos(th), r * std::sin(th), 0);
      th += 1.0 / r;
    }
    sim->add_chain("w", pts, 1.0, false);
    sim->add_bond("spring", P({{"k", 1000.0}}));
    sim->add_bond("bend2d", P({{"k", 60.0}}));
    sim->add_pair(
        "contact/node-edge",
        P({{"stiffness", 1e4}, {"damping", 10.0}, {"mu_static", 0.3}, {"rebuild_every", every}}));
    sim->add_fix("cavity", "wall/circle",
                 P({{"radius", 8.0}, {"diameter", 1.0}, {"stiffness", 1e4}}));
    for (auto& v : sim->nodes().v) v = Vec3(0.5, -0.3, 0);
    sim->set_integrator("verlet", P({{"dt", 0.004}}));
    double most = 0;
    sim->run(RunOptions{3000, 10, [&](Simulation& s) {
                          most = std::max(most, s.pairs()[0]->value("contacts"));
                          return false;
                        }});
    EXPECT_GE(most, 5.0);  // the wire does touch itself
    return sim;
  };
  auto a = run(0.0), b = run(1.0);
  for (size_t i = 0; i < a->nodes().size(); ++i) EXPECT_EQ(a->nodes().x[i], b->nodes().x[i]) << i;
  EXPECT_LT(a->pairs()[0]->value("builds"), b->pairs()[0]->value("builds") / 10);
  std::printf("pair-list builds over 3000 steps: displacement %g, every step %g\n",
              a->pairs()[0]->value("builds"), b->pairs()[0]->value("builds"));
}

TEST(NodeEdgeContactPair, ExcludesChainNeighboursAndNeeds2D) {
  Simulation sim(2, 1);
  // a tight hairpin: nodes 0 and 2 are close but chain neighbours
  sim.add_chain("w", {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.2, 0.3, 0), Vec3(1.0, 0.6, 0)}, 1.0,
                false);
  sim.add_pair("contact/node-edge", P({{"stiffness", 1e3}}));
  sim.compute_forces();
  EXPECT_EQ(sim.pairs()[0]->value("contacts"), 0.0);
  Simulation s3(3, 1);
  EXPECT_THROW(s3.add_pair("contact/node-edge", P({{"stiffness", 1.0}})), InputError);
  EXPECT_THROW(sim.add_pair("contact/node-edge",
                            P({{"stiffness", 1.0}, {"mu_static", 0.1}, {"mu_dynamic", 0.2}})),
               InputError);
}

namespace {
// A stuck contact of wire b on edge [3, 4] of wire a builds up its stick spring; then
// wire a grows a node at its front (injection), which renumbers all of its edges. The
// friction force must carry on from its stretched spring (history matched by node
// ids), not restart from zero on a fresh contact.
double friction_jump_on_front_growth(int dim, const RawParams& pair) {
  Simulation sim(dim, 1);
  sim.verbose = false;
  std::vector<Vec3> a;
  for (int i = 0; i < 8; ++i) a.emplace_back(i, 0, 0);
  sim.add_chain("a", a, 1.0, false);
  // 2D: a node 0.9 above the middle of [3, 4] (d = 1); 3D: a rod across it, 1.95 above
  // (2 a = 2), out of reach of [2, 3] and [4, 5]
  if (dim == 2)
    sim.add_chain("b", {Vec3(3.5, 0.9, 0), Vec3(3.5, 1.9, 0)}, 1.0, false);
  else
    sim.add_chain("b", {Vec3(3.5, 1.95, -0.5), Vec3(3.5, 1.95, 0.5)}, 1.0, false);
  sim.add_pair(dim == 2 ? "contact/node-edge" : "contact/segment", pair);
  sim.dt = 0.01;
  for (int i : sim.group("b")) sim.nodes().v[i] = Vec3(0.5, 0, 0);
  auto tangential = [&] {
    sim.compute_forces();
    double fx = 0;
    for (int i : sim.group("b")) fx += sim.nodes().f[i].x();
    return fx;
  };
  double f0 = 0, f1 = 0;
  for (int k = 0; k < 4; ++k) f0 = f1, f1 = tangential();
  EXPECT_LT(f1, f0);  // the spring is stretching: the force grows against the motion
  sim.grow_chain("a", true, Vec3(-1, 0, 0), 1.0, 1.0);
  const double f2 = tangential();
  // one more step of stretching adds what the last did
  return std::abs((f2 - f1) - (f1 - f0)) / std::abs(f1 - f0);
}
}  // namespace

TEST(NodeEdgeContactPair, FrictionHistoryFollowsTheEdgeWhenAChainGrowsAtItsFront) {
  EXPECT_LT(friction_jump_on_front_growth(2, P({{"diameter", 1.0},
                                                {"stiffness", 1e3},
                                                {"mu_static", 0.9},
                                                {"stick_stiffness", 100.0}})),
            1e-6);
}

TEST(SegmentContactPair, FrictionHistoryFollowsTheEdgeWhenAChainGrowsAtItsFront) {
  EXPECT_LT(friction_jump_on_front_growth(3, P({{"radius", 1.0},
                                                {"youngs_modulus", 1000.0},
                                                {"mu_static", 0.9},
                                                {"stick_stiffness", 100.0}})),
            1e-6);
}

TEST(NodeEdgeContactPair, MeasuredFrequencyCountsEveryContactOfANode) {
  // a node pressed between two parallel wires, overlap delta on each side: each contact
  // puts 2 k_t on the node (Gershgorin row sum of k_t w w^T), k_t = 2 k_c delta for the
  // quadratic law, so omega^2 = 2 * 2 * 2 k_c delta / m; one contact alone gives half
  const double kc = 1e4, delta = 0.05, m = 2.0;
  auto omega = [&](bool both) {
    Simulation sim(2, 1);
    // heavy walls: the light node between them has the highest k / m
    sim.add_chain("low", {Vec3(-3, -(1 - delta), 0), Vec3(3, -(1 - delta), 0)}, 1e3, false);
    if (both) sim.add_chain("high", {Vec3(-3, 1 - delta, 0), Vec3(3, 1 - delta, 0)}, 1e3, false);
    sim.add_chain("mid", {Vec3(0, 0, 0), Vec3(0.0, 0.0, 0) + Vec3(1e-3, 0, 0)}, m, false);
    sim.add_pair("contact/node-edge", P({{"diameter", 1.0}, {"stiffness", kc}, {"exclude", 0.0}}));
    sim.compute_forces();
    return sim.pairs()[0]->value("omega");
  };
  EXPECT_NEAR(omega(false), std::sqrt(2 * 2 * kc * delta / m), 1e-6);
  EXPECT_NEAR(omega(true), std::sqrt(2 * 2 * 2 * kc * delta / m), 1e-6);
}

TEST(VelocityVerletIntegrator, AdaptiveStepFollowsTheMeasuredContacts) {
  // a heavy node dropped onto a stiff wall: once it presses deep into the wall, the adaptive
  // step falls below the nominal "auto" step (one contact at a tenth of a diameter), and
  // the run stays stable
  Simulation sim(2, 1);
  sim.verbose = false;
  sim.add_chain("w", {Vec3(0, 8.0, 0), Vec3(0.5, 8.0, 0)}, 1.0, false);
  sim.add_bond("spring", P({{"k", 100.0}}));
  sim.add_fix("cavity", "wall/circle",
              P({{"radius", 9.0}, {"diameter", 1.0}, {"stiffness", 1e4}, {"damping", 5.0}}));
  sim.add_fix("push", "force/constant",
              P({{"group", "all"s}, {"force", std::vector<double>{0, 300}}}));
  sim.set_integrator("verlet", P({{"dt", "auto"s}, {"adaptive", true}}));
  sim.run(RunOptions{20000, 0, {}});
  const double nominal = sim.suggest_dt(0.5);
  EXPECT_GT(sim.fix("cavity").value("contacts"), 0.0);
  EXPECT_GT(sim.fix("cavity").value("omega"), 0.0);
  EXPECT_LT(sim.dt, 0.9 * nominal) << "the adaptive step did not follow the deep contact";
  // dt was set from the contacts at the start of the last step
  EXPECT_NEAR(sim.dt, 0.5 * 2.0 / sim.omega_now(), 1e-3 * sim.dt);
  EXPECT_TRUE(sim.nodes().x[0].allFinite());
}

TEST(VelocityVerletIntegrator, TrustingTheMeasuredContactsLetsTheStepGrowWhileTheyAreSoft) {
  // the same drop, with the wall's measured stiffness trusted alone: before the node
  // reaches the wall (no contact) the step is the spring's stable step, above the nominal
  // "auto" step that counts the wall at a tenth of a diameter of overlap; a fast node is
  // held to safety x a tenth of the rest length per step (it may meet a contact within the
  // step); pressed in deep, the step falls below the nominal one as before. The drag,
  // which measures nothing, keeps its nominal share all along.
  auto scene = [](bool trust, double y0, double push) {
    auto sim = std::make_unique<Simulation>(2, 1);
    sim->verbose = false;
    sim->add_chain("w", {Vec3(0, y0, 0), Vec3(0.5, y0, 0)}, 1.0, false);
    sim->add_bond("spring", P({{"k", 100.0}}));
    sim->add_fix("cavity", "wall/circle",
                 P({{"radius", 9.0}, {"diameter", 1.0}, {"stiffness", 1e4}, {"damping", 5.0}}));
    sim->add_fix("drag", "damping/viscous", P({{"gamma", 0.1}}));
    sim->add_fix("push", "force/constant",
                 P({{"group", "all"s}, {"force", std::vector<double>{0, push}}}));
    sim->set_integrator("verlet",
                        P({{"dt", "auto"s}, {"adaptive", true}, {"trust_measured", trust}}));
    return sim;
  };
  auto slow = scene(true, 2.0, 3.0);
  slow->run(RunOptions{3, 0, {}});
  const double nominal = slow->suggest_dt(0.5);
  EXPECT_EQ(slow->fix("cavity").value("contacts"), 0.0);
  const double spring_and_drag =
      std::sqrt(std::pow(slow->bonds()[0]->max_frequency(slow->context()), 2) +
                std::pow(slow->fix("drag").max_frequency(slow->context()), 2));
  const double cap = 0.5 * 2.0 / spring_and_drag;
  EXPECT_NEAR(slow->dt, cap, 1e-12 * cap);
  EXPECT_GT(slow->dt, 1.2 * nominal) << "the step did not grow while no contact was measured";
  auto floor = scene(false, 2.0, 3.0);
  floor->run(RunOptions{3, 0, {}});
  EXPECT_DOUBLE_EQ(floor->dt, nominal) << "without trust_measured the nominal step is the most";
  auto fast = scene(true, 2.0, 300.0);
  fast->run(RunOptions{3, 0, {}});
  const double v = fast->nodes().v[0].norm(), approach = 0.5 * 0.1 * 0.5;
  EXPECT_LT(fast->dt, 0.5 * cap);
  EXPECT_GT(fast->dt * v, 0.5 * approach);  // the bound, not something else, set the step
  EXPECT_LT(fast->dt * v, 1.5 * approach);  // (v grew by a dt within the last step)
  auto pressed = scene(true, 8.0, 300.0);
  pressed->run(RunOptions{20000, 0, {}});
  EXPECT_GT(pressed->fix("cavity").value("contacts"), 0.0);
  EXPECT_LT(pressed->dt, 0.9 * nominal) << "the trusted step did not follow the deep contact";
  EXPECT_TRUE(pressed->nodes().x[0].allFinite());
  EXPECT_THROW(Simulation(2, 1).set_integrator("verlet", P({{"trust_measured", true}})),
               InputError);
}

// A diameter that reaches past the excluded neighbours puts a straight wire at rest in
// contact with itself: refused at setup with what to change, instead of a guard stop later.
TEST(NodeEdgeContactPair, DiameterReachingPastTheExclusionIsRefused) {
  Simulation sim(2, 1);
  sim.verbose = false;
  std::vector<Vec3> pts;
  for (int i = 0; i < 20; ++i) pts.emplace_back(0.3 * i, 0, 0);
  sim.add_chain("w", pts, 1.0, false);
  sim.add_pair("contact/node-edge", P({{"diameter", 1.0}, {"stiffness", 1e3}}));
  try {
    sim.compute_forces();
    ADD_FAILURE() << "a wire touching itself at rest was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("touches itself at rest; raise exclude to at least 3"),
              std::string::npos)
        << e.what();
  }
  Simulation ok(2, 1);
  ok.verbose = false;
  ok.add_chain("w", pts, 1.0, false);
  ok.add_pair("contact/node-edge", P({{"diameter", 1.0}, {"stiffness", 1e3}, {"exclude", 3.0}}));
  ok.compute_forces();
  EXPECT_EQ(ok.pairs()[0]->value("contacts"), 0.0);  // the advice holds: nothing touches
}
