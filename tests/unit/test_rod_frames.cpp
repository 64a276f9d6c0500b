// Reading and setting rod frames (src/rod_frames.hpp, sim:frame / sim:set_frame): a frame
// set before the first run is kept by the rod's setup, so a straight rod whose frames are
// set twisted holds the discrete twist energy of docs/models.md §4.3; the directors give
// back the frame they were built from; bad frames and rods without frames are refused.
#include <cmath>

#include "helpers.hpp"
#include "quaternion_rod.hpp"
#include "rod_frames.hpp"

using namespace slender;
using namespace slender::test;

namespace {
// The frame along x turned by angle a about x.
Vec4 twisted(double a) {
  const Eigen::Quaterniond r(Eigen::AngleAxisd(a, Vec3::UnitX()));
  const Vec4 base = qrod::aligned_with(Vec3::UnitX());
  return qrod::mul(qrod::Quat(r.w(), r.x(), r.y(), r.z()), base);
}
}  // namespace

TEST(RodFrames, FramesSetBeforeTheRunAreKeptAndTwistTheRod) {
  const int n = 12;
  const double l = 0.5, GJ = 1.5, step = 0.05;
  Simulation sim(3, 1);
  straight_cosserat_rod(sim, n, l, GJ);
  for (int e = 0; e < n - 1; ++e) set_rod_frame(sim, e, twisted(step * e));
  sim.compute_forces();
  // n - 2 hinges, each turned by `step` about the tangent: (l/2) GJ (2 sin(step/2) / l)^2
  const double expected = (n - 2) * (l / 2) * GJ * std::pow(2 * std::sin(step / 2) / l, 2);
  EXPECT_NEAR(sim.energies().at("twist"), expected, 1e-12 * expected);
  EXPECT_NEAR(sim.energies().at("bend"), 0.0, 1e-20);
  // read back: the frame set, and its directors
  for (int e : {0, 5, n - 2}) {
    const Vec4 q = rod_frame(sim, e);
    EXPECT_NEAR(std::abs(q.dot(twisted(step * e))), 1.0, 1e-14);
    EXPECT_NEAR((qrod::d3(q) - Vec3::UnitX()).norm(), 0.0, 1e-14);
  }
  // the last node of the open chain starts no edge
  EXPECT_THROW(rod_frame(sim, n - 1), InputError);
  EXPECT_THROW(set_rod_frame(sim, n - 1, twisted(0.0)), InputError);
}

TEST(RodFrames, UnsetFramesGetTheirValuesAtSetup) {
  Simulation sim(3, 1);
  straight_cosserat_rod(sim, 5, 1.0, 1.0);
  EXPECT_THROW(rod_frame(sim, 0), InputError);  // not given yet
  sim.compute_forces();
  const Vec4 q = rod_frame(sim, 0);
  EXPECT_NEAR((qrod::d3(q) - Vec3::UnitX()).norm(), 0.0, 1e-14);
  EXPECT_NEAR(sim.energies().at("twist"), 0.0, 1e-20);
}

TEST(RodFrames, DirectorsGiveBackTheirFrame) {
  const Vec3 d3 = Vec3(1, 2, 2).normalized();
  const Vec3 d1 = Vec3(2, -1, 0).normalized();
  const Vec4 q = frame_from_directors(d1, d3);
  EXPECT_NEAR(q.norm(), 1.0, 1e-14);
  EXPECT_NEAR((qrod::d1(q) - d1).norm(), 0.0, 1e-14);
  EXPECT_NEAR((qrod::d3(q) - d3).norm(), 0.0, 1e-14);
  EXPECT_NEAR((qrod::d2(q) - d3.cross(d1)).norm(), 0.0, 1e-14);
  // not at right angles, not unit: refused, not fixed
  EXPECT_THROW(frame_from_directors(Vec3(1, 0, 0), Vec3(0.1, 0, 1).normalized()), InputError);
  EXPECT_THROW(frame_from_directors(Vec3(2, 0, 0), Vec3(0, 0, 1)), InputError);
}

TEST(RodFrames, ScenesWithoutFramesAndBadQuaternionsAreRefused) {
  Simulation bare(3, 1);
  bare.verbose = false;
  bare.add_chain("w", {Vec3(0, 0, 0), Vec3(1, 0, 0)}, 1.0, false);
  bare.add_bond("spring", P({{"k", 1.0}}));
  EXPECT_THROW(rod_frame(bare, 0), InputError);
  EXPECT_THROW(set_rod_frame(bare, 0, twisted(0.0)), InputError);
  Simulation sim(3, 1);
  straight_cosserat_rod(sim, 4, 1.0, 1.0);
  EXPECT_THROW(set_rod_frame(sim, 0, Vec4::Zero()), InputError);
  EXPECT_THROW(set_rod_frame(sim, 0, Vec4(NAN, 0, 0, 0)), InputError);
  // a quaternion of any length is taken as its direction
  set_rod_frame(sim, 1, 3.0 * twisted(0.2));
  EXPECT_NEAR(rod_frame(sim, 1).norm(), 1.0, 1e-15);
}
