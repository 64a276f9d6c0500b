// Triangle meshes for the shell family (docs/models.md §6.6, §6.7, §6.12): generators,
// OBJ/OFF input and output, Loop's topological refinement, counter-clockwise
// 1-rings, and the ghost layer that completes the rings of boundary nodes.
#pragma once

#include <algorithm>
#include <array>
#include <functional>
#include <istream>
#include <limits>
#include <string>
#include <vector>

#include "nodes.hpp"

namespace slender::shell {

using Tri = std::array<int, 3>;

struct TriMesh {
  std::vector<Vec3> x;
  std::vector<Tri> tri;  // counter-clockwise seen from the side the normals point to
  int n_nodes() const { return static_cast<int>(x.size()); }
  int n_tris() const { return static_cast<int>(tri.size()); }
};

// --- generators (unit normals along +z for the flat ones)
// Hexagon of 6 triangles refined `refinements` times, nodes moved radially onto the disc.
// core_levels > 0 refines the core further (red-green): level k within
// core_radius / 2^(k-1), so the edge at the centre is 2^-core_levels of the outer edge.
TriMesh make_disc(double radius, int refinements, double core_radius = 0.0, int core_levels = 0);
// Structured annulus: n_r rings of edges between r_in and r_out, n_phi nodes round.
TriMesh make_ring(double r_in, double r_out, int n_r, int n_phi);
// Structured rectangle [0,lx]x[0,ly] split into nx x ny quads, each with one diagonal
// in the same direction (valence 6 inside).
TriMesh make_rectangle(double lx, double ly, int nx, int ny);
// Icosahedron refined `refinements` times and projected on the sphere.
TriMesh make_sphere(double radius, int refinements);

// One Loop refinement of the connectivity: every triangle split into four, new
// nodes at edge midpoints (positions are not smoothed; generators project them).
void refine(TriMesh& m);
// Red-green refinement of the triangles whose centroid is `inside`: those split into four
// (with every triangle that would get two split edges), their neighbours with one split
// edge halved. The nodes on the transition get valences 5, 7 or 8: one global refine()
// afterwards isolates them for Loop's irregular elements.
void refine_where(TriMesh& m, const std::function<bool(const Vec3&)>& inside);

// Reads a Wavefront OBJ ("v" and "f" lines; polygons must be triangles) or an OFF
// file, chosen by extension; throws with the file and line on bad input.
TriMesh read_mesh(const std::string& path);
// The same from a stream in `format` ("obj" or "off"); `name` names it in messages.
// Refuses what would fail later or silently: indices out of range, non-finite or huge
// coordinates, vertices no triangle uses, two vertices at one position, repeated triangles,
// OFF files longer than their header says.
TriMesh parse_mesh(std::istream& in, const std::string& format, const std::string& name);
void write_mesh(const std::string& path, const TriMesh& m);

// Counter-clockwise 1-rings. For node v, next[v] maps a neighbour a to b for every
// triangle (v, a, b). A ring is closed when it is a cycle.
struct Rings {
  std::vector<std::vector<int>> ring;  // ccw neighbours; open rings start at the boundary
  std::vector<char> closed;
  std::vector<std::vector<int>> tris;  // triangles incident to each node
};
Rings build_rings(int n_nodes, const std::vector<Tri>& tri);
// The ring of v rotated to start at neighbour `first` (which must be in the ring).
std::vector<int> ring_from(const Rings& r, int v, int first);

// A mesh with its ghost layer (§6.7): for each boundary edge (b0, b2) with interior
// triangle (b0, i1, b2) a ghost g = b0 + b2 - i1 and the triangle across the edge;
// at every boundary node one triangle joining the ghosts of its two boundary edges.
struct GhostedMesh {
  TriMesh mesh;  // real nodes first, then ghosts; real triangles first
  int n_real_nodes = 0;
  int n_real_tris = 0;
  struct Ghost {
    int node, b0, b2, interior;  // g = b0 + b2 - interior (mirror rule (5.34))
  };
  std::vector<Ghost> ghosts;
  std::vector<int> boundary;   // real nodes on the boundary
  std::vector<int> first_row;  // interior nodes that have a ghost mirrored from them
  Rings rings;                 // of the completed mesh
  std::vector<int> valence;    // of the completed mesh (ghost rings may be open)
};
GhostedMesh add_ghosts(const TriMesh& m);

// Shortest and mean edge of the real triangles in the reference (each triangle's three
// edges, so interior edges count twice): the length scales of elements, ghosts, contact.
struct EdgeStats {
  double min = 0, mean = 0;
};
// (inline: the Newmark integrator uses it in builds without the shell family too)
inline EdgeStats reference_edges(const GhostedMesh& g) {
  EdgeStats e{std::numeric_limits<double>::max(), 0.0};
  int n = 0;
  for (int t = 0; t < g.n_real_tris; ++t)
    for (int k = 0; k < 3; ++k) {
      const double l = (g.mesh.x[g.mesh.tri[t][k]] - g.mesh.x[g.mesh.tri[t][(k + 1) % 3]]).norm();
      e.min = std::min(e.min, l);
      e.mean += l;
      ++n;
    }
  e.mean /= std::max(1, n);
  return e;
}

// Throws a message naming the triangle when a real triangle has more than one
// irregular node (valence != 6 in the completed mesh) or an incomplete ring.
void check_patches(const GhostedMesh& g);

}  // namespace slender::shell
