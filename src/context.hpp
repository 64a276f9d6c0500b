// What a force style (bond, pair, shell, fix, growth, region) sees of its scene: the
// nodes and their properties, the topology and groups, the clock (read-only), the random
// stream, the threads, energies by category, a stop request, the one topology change a
// style may make (a chain grows at injection), and typed handles for the shared
// constraints (held position components, prescribed frames). Not the run loop, the
// integrator, the guard, outputs or the other styles: a style that needs another one
// asks for it by kind (a growth by id). Integrators, computes and dumps drive or observe
// the whole run and keep the Simulation.
//
// The Simulation owns one Context and passes it to every force style; each call here
// is an inline forward, so the hot loops pay nothing for the narrowing.
#pragma once

#include <random>
#include <string>
#include <utility>
#include <vector>

#include "simulation.hpp"

namespace slender {

class Context {
 public:
  explicit Context(Simulation& sim) : sim_(sim) {}
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  int dimension() const { return sim_.dimension(); }
  NodeStore& nodes() { return sim_.nodes(); }
  const NodeStore& nodes() const { return sim_.nodes(); }
  Topology& topology() { return sim_.topology(); }
  const Topology& topology() const { return sim_.topology(); }
  std::mt19937_64& rng() { return sim_.rng(); }
  // Console lines besides thermo (e.g. a shell's ramp messages).
  bool verbose() const { return sim_.verbose; }

  // --- the clock, read-only: the run loop and the integrator advance it
  double dt() const { return sim_.dt; }
  double time() const { return sim_.time; }
  long step() const { return sim_.step; }
  // Bumped when the state changed outside the equations of motion (positions set from a
  // deck, a minimisation, a guard rollback): styles with history restart it.
  long state_epoch() const { return sim_.state_epoch; }

  // --- threads (src/threads.hpp)
  int threads() const { return sim_.threads(); }
  // Threads for kernels of a few hundred nanoseconds per item (shell elements, triangle
  // pairs): the requested count at any scene size, not gated by the node count.
  int heavy_threads() const { return sim_.requested_threads(); }
  template <class Kernel>
  double parallel_node_forces(std::size_t n, Kernel&& kernel) {
    return sim_.parallel_node_forces(n, std::forward<Kernel>(kernel));
  }
  template <class Kernel>
  double parallel_heavy_forces(std::size_t n, Kernel&& kernel) {
    return sim_.parallel_heavy_forces(n, std::forward<Kernel>(kernel));
  }
  template <class Kernel>
  double parallel_chain_forces(std::size_t n, bool closed, long n_positions, long lo, long hi,
                               Kernel&& kernel) {
    return sim_.parallel_chain_forces(n, closed, n_positions, lo, hi, std::forward<Kernel>(kernel));
  }

  // --- the neighbour service: one rebuild decision per evaluation for every pair list
  NeighborService& neighbors() { return sim_.neighbors(); }

  // --- groups
  std::vector<int> group(const std::string& name) const { return sim_.group(name); }
  bool has_group(const std::string& name) const { return sim_.has_group(name); }
  void set_group(const std::string& name, std::vector<int> nodes) {
    sim_.set_group(name, std::move(nodes));
  }

  // --- generalised coordinates (rod frames), energies, stop requests
  Coordinates& coordinates(const std::string& name) { return sim_.coordinates(name); }
  const std::vector<std::unique_ptr<Coordinates>>& extra_coordinates() const {
    return sim_.extra_coordinates();
  }
  // The frames of a rod style prescribes in place ("rod.q"), or null if the scene has none.
  Property<int>* prescribed_frames(const std::string& name) {
    for (auto& c : sim_.extra_coordinates())
      if (c->name == name) return c->fixed;
    return nullptr;
  }
  void add_energy(const std::string& category, double e) { sim_.add_energy(category, e); }
  void request_stop(const std::string& why) { sim_.request_stop(why); }

  // --- shared constraints: the position components held in place (clamps, driven nodes,
  // shell ghosts); bits kMaskX | kMaskY | kMaskZ per node. held_components() creates the
  // mask on first use (a scene without clamps has none: held_components_if_any() is null).
  Property<int>& held_components() { return sim_.nodes().require<int>(kHeldComponents, 0); }
  Property<int>* held_components_if_any() { return sim_.nodes().find<int>(kHeldComponents); }
  const Property<int>* held_components_if_any() const {
    return sim_.nodes().find<int>(kHeldComponents);
  }

  // --- the topology change a style may make: a node at one end of a chain (injection)
  int grow_chain(const std::string& chain, bool at_front, const Vec3& pos, double mass,
                 double rest) {
    return sim_.grow_chain(chain, at_front, pos, mass, rest);
  }
  // Another style by kind: a growth law by its id.
  GrowthStyle& growth(const std::string& id) { return sim_.growth(id); }

 private:
  Simulation& sim_;
};

}  // namespace slender
