// Reading and setting the rod frames of a scene from the API and decks (sim:frame,
// sim:set_frame): bond rod/cosserat keeps one unit quaternion per edge (docs/models.md
// §4.1), stored at the edge's tail node in the coordinates "rod.q"; "rod.q.born" says
// which slots hold a frame (1), which is an open chain's last node without an edge (2),
// and which edge gets its frame at the next setup (0). A frame set before the first run
// is kept by that setup: a rod can start twisted.
#pragma once

#include <cmath>
#include <string>

#include "quaternion_rod.hpp"
#include "simulation.hpp"

namespace slender {

inline constexpr const char* kRodFrames = "rod.q";

// The scene's rod frames, or an error that says how to get them.
inline Coordinates& rod_frame_coordinates(Simulation& sim, const std::string& who) {
  for (auto& c : sim.extra_coordinates())
    if (c->name == kRodFrames) return *c;
  throw InputError(who + ": the scene has no rod frames (they come with bond rod/cosserat)");
}

// The frame of the edge that starts at `node` (0-based), as a unit quaternion
// (scalar first; its rotation matrix has the directors d1, d2, d3 as columns).
inline Vec4 rod_frame(Simulation& sim, int node) {
  Coordinates& c = rod_frame_coordinates(sim, "frame");
  const Property<int>* born = sim.nodes().find<int>(std::string(kRodFrames) + ".born");
  const int b = born ? (*born)[static_cast<std::size_t>(node)] : 0;
  if (b == 2)
    throw InputError("frame: node " + std::to_string(node + 1) +
                     " ends its chain and starts no edge, so it carries no frame");
  if (b != 1)
    throw InputError("frame: the edge from node " + std::to_string(node + 1) +
                     " has no frame yet: the rod gives its edges their frames when a run "
                     "sets up (sim:run(0)), or set one with sim:set_frame");
  return (*c.q)[static_cast<std::size_t>(node)];
}

// The unit quaternion of the frame {d1, d3 x d1, d3}; d1 and d3 must be orthonormal to
// 1e-6 (they are not silently fixed: a frame off by more is a mistake in the deck).
inline Vec4 frame_from_directors(const Vec3& d1, const Vec3& d3) {
  const double tol = 1e-6;
  if (!d1.allFinite() || !d3.allFinite() || std::abs(d1.norm() - 1) > tol ||
      std::abs(d3.norm() - 1) > tol || std::abs(d1.dot(d3)) > tol)
    throw InputError(
        "set_frame: d1 and d3 must be unit vectors at right angles (to 1e-6); got |d1| = " +
        std::to_string(d1.norm()) + ", |d3| = " + std::to_string(d3.norm()) +
        ", d1 . d3 = " + std::to_string(d1.dot(d3)));
  Eigen::Matrix3d R;
  R.col(0) = d1;
  R.col(1) = d3.cross(d1);
  R.col(2) = d3;
  const Eigen::Quaterniond q(R);
  return Vec4(q.w(), q.x(), q.y(), q.z());
}

// Sets the frame of the edge that starts at `node` to the unit quaternion q (normalised;
// its rate is set to zero). The next evaluation sees it; integrators with history restart.
inline void set_rod_frame(Simulation& sim, int node, const Vec4& q) {
  Coordinates& c = rod_frame_coordinates(sim, "set_frame");
  auto& born = sim.nodes().require<int>(std::string(kRodFrames) + ".born", 0);
  const std::size_t i = static_cast<std::size_t>(node);
  if (born[i] == 2)
    throw InputError("set_frame: node " + std::to_string(node + 1) +
                     " ends its chain and starts no edge, so it carries no frame");
  const double len = q.norm();
  if (!q.allFinite() || !(len > 1e-12))
    throw InputError("set_frame: the quaternion of node " + std::to_string(node + 1) +
                     " must be finite and nonzero");
  (*c.q)[i] = q / len;
  (*c.v)[i].setZero();
  born[i] = 1;
  sim.forces_valid = false;
  ++sim.state_epoch;
}

}  // namespace slender
