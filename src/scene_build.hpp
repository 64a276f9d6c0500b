// Scene construction from declared parameters: the deck commands `wire`, `group` and `mesh` as a
// C++ API (an embedding program or a test builds the same scenes without Lua; the Lua layer
// only translates its tables). Each command's ParamSpec is the one `slender --help wire`
// prints.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "params.hpp"
#include "simulation.hpp"

namespace slender {

// sim:wire{...}: a straight or circular chain of `nodes`, or one through `points`.
ParamSpec wire_spec();
// Adds the wire described by raw (validated against wire_spec()); `points` are the explicit
// node positions (the deck's points = {...}), empty for a generated wire.
Chain& add_wire(Simulation& sim, const RawParams& raw, std::vector<Vec3> points = {});

// sim:group(name, {...}): nodes of a chain, by index, inside a region.
ParamSpec group_spec();
// Defines the group (validated against group_spec()); returns its size.
std::size_t add_group(Simulation& sim, const std::string& name, const RawParams& raw);

// sim:mesh{...}: a generated or read triangle mesh for shells, with its ghost layer.
ParamSpec mesh_spec();
// Adds the surface (validated against mesh_spec()); returns its real nodes and triangles.
// Refused in a build without the shell family.
std::pair<int, int> add_mesh(Simulation& sim, const RawParams& raw);

// A node index as decks write it (1-based, negative from the end) into [0, n); `what` names
// the command in the error.
int node_index(long i, std::size_t n, const std::string& what);

}  // namespace slender
