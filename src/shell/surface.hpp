// Puts a triangle mesh into a Simulation as a shell surface: real nodes, then one
// ghost node per boundary edge (docs/models.md §6.7), and the node groups
// <name> (real nodes), <name>.boundary, <name>.ghost and <name>.row1 (interior
// nodes mirrored by ghosts: the first row a clamped edge also holds).
#pragma once

#include <string>

#include "shell/trimesh.hpp"

namespace slender {
class Simulation;
struct Surface;
}  // namespace slender

namespace slender::shell {

// `noise` moves the real nodes by a seeded uniform amount in [-noise, noise] along
// the local normal (docs/models.md §6.12); the reference keeps the unperturbed mesh.
Surface& add_surface(Simulation& sim, const std::string& name, const TriMesh& mesh, double noise);

}  // namespace slender::shell
