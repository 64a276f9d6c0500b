// Loop subdivision limit surface on one element (docs/models.md §6.6): the 12 quartic
// box-spline functions of a regular patch, and irregular elements by local
// subdivision until the point lies in a regular child (Alg. 4, cleaned up).
// Everything is returned as a stencil over the control nodes of the mesh, so the
// element kernel never needs to know which case it is in.
#pragma once

#include <array>
#include <vector>

#include "shell/trimesh.hpp"

namespace slender::shell {

// Value and first/second derivatives in the element parameters (v, w).
struct ShapeRow {
  int node = 0;
  double N = 0, Nv = 0, Nw = 0, Nvv = 0, Nvw = 0, Nww = 0;
};
using Stencil = std::vector<ShapeRow>;

// The 12 box-spline functions at (v, w) with the node layout of §6.6:
// out[I-1] for node I, derivatives included.
std::array<ShapeRow, 12> box_splines(double v, double w);

// The 12 control nodes of a regular patch for the element (p4, p7, p8).
std::array<int, 12> gather_regular(const Rings& rings, int p4, int p7, int p8);

// The element's corners ordered so that its irregular node (if any) comes first.
Tri oriented_element(const GhostedMesh& g, int t);

// Limit surface weights at (v, w) of element `corners` (from oriented_element).
Stencil evaluate(const GhostedMesh& g, const Tri& corners, double v, double w);

// Limit position of a control node (Loop's limit mask) as a stencil.
Stencil limit_mask(const GhostedMesh& g, int node);

// Loop's vertex weight omega(V) of (5.22).
double loop_omega(int valence);

}  // namespace slender::shell
