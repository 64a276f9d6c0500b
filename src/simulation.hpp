// One scene: nodes, topology, styles, integrator, outputs and random stream.
// There is no global state; several Simulations can live in one process.
#pragma once

#include <csignal>
#include <cstdint>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "cadence.hpp"
#include "neighbors.hpp"
#include "nodes.hpp"
#include "params.hpp"
#include "schedule.hpp"
#include "style.hpp"
#include "thermo_writer.hpp"
#include "threads.hpp"
#include "topology.hpp"

namespace slender {

class StaticSystem;

// The run became unstable; the message says what, when, and which dt is stable.
struct InstabilityError : std::runtime_error {
  using std::runtime_error::runtime_error;
};
// A signal (SIGINT, SIGTERM) asked the run to stop: it finished its step, wrote a last frame
// of every dump and a checkpoint; the message says where.
struct InterruptedError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct GuardOptions {
  long every = 10;                 // steps between checks
  double max_step_fraction = 0.5;  // max |v| dt as a fraction of the shortest rest length
  double ke_factor = 100.0;        // kinetic energy may not exceed this times the energy scale
  double max_strain = 0.5;         // an edge beyond (1 +- this) times its rest length has torn
  std::string last_good_file = "slender_last_good.h5";
};

// Generalised coordinates integrated besides the node positions: four components
// per node (the edge quaternions of a Cosserat rod, docs/models.md §4.4) with their
// velocities, generalised forces and scalar masses. A unit set stays on |q| = 1:
// its forces are projected onto the tangent space and the integrators renormalise
// q and remove the radial part of its derivatives after every step.
// Bits of the node property "dof_mask": a set bit holds that position component (its
// force is zeroed after every evaluation). Clamps set some; kinematically driven nodes
// (injection channels, shell ghosts and clamped rows) hold all three.
inline constexpr int kMaskX = 1, kMaskY = 2, kMaskZ = 4;
inline constexpr int kMaskAll = kMaskX | kMaskY | kMaskZ;
// The node property holding those bits (Context::held_components()).
inline constexpr const char* kHeldComponents = "dof_mask";

struct Coordinates {
  std::string name;
  Property<Vec4>* q = nullptr;
  Property<Vec4>* v = nullptr;
  Property<Vec4>* f = nullptr;
  Property<double>* m = nullptr;
  Property<int>* fixed = nullptr;  // nonzero: prescribed (not integrated, zero force)
  bool unit = true;
  // Set by a style that moves these coordinates with the positions inside the force
  // evaluation (rod frames carried onto their tangents): an integrator that keeps its own
  // history of q (gear) cannot run them.
  bool follows_positions = false;
  // The rate after a step keeps its length (carried along the great circle of the step)
  // instead of losing its radial part only, which takes cos(h |dq/dt|) off the speed:
  // a first-order energy loss of a fast spin. Off by default (runs of the penalty
  // rod stay as they were).
  bool keep_speed = false;
  // back onto |q| = 1 after an update; the derivatives lose their radial part
  void constrain(std::size_t i, std::initializer_list<Vec4*> derivs) const {
    Vec4& qi = (*q)[i];
    qi.normalize();
    bool first = true;
    for (Vec4* d : derivs) {
      if (!d) continue;
      const double speed = first && keep_speed ? d->norm() : 0.0;
      *d -= d->dot(qi) * qi;
      if (speed > 0.0) *d *= speed / d->norm();
      first = false;
    }
  }
};

struct RunOptions {
  long steps = 0;
  long every = 0;                             // callback interval
  std::function<bool(Simulation&)> callback;  // returns true to stop the run
};

class Simulation {
 public:
  explicit Simulation(int dimension = 3, std::uint64_t seed = 1);
  ~Simulation();
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  int dimension() const { return dim_; }
  // What the force styles see of this scene (src/context.hpp).
  Context& context() { return *context_; }
  // The static system of the scene (src/statics.hpp), kept between minimisations so that
  // the sparse ordering and the last Levenberg shift carry over from one load increment to
  // the next.
  StaticSystem& static_system();
  NodeStore& nodes() { return nodes_; }
  const NodeStore& nodes() const { return nodes_; }
  Topology& topology() { return topo_; }
  const Topology& topology() const { return topo_; }
  std::mt19937_64& rng() { return rng_; }
  std::uint64_t seed() const { return seed_; }
  // Threads of the force kernels and the integrators (slender -t N, or OMP_NUM_THREADS;
  // 1: serial). A run is bit-identical to itself for the same thread count.
  // A scene of fewer than threads_min_nodes() nodes runs on one thread: below that the
  // cores pass the node arrays back and forth between the kernels (each splits the work
  // its own way) and the forks cost more than the halves of the work save
  // (docs/performance.md, "Threads"). A function of the node count only, so still
  // deterministic; a growing wire changes over as it crosses the size.
  int threads() const { return nodes_.n_owned() >= threads_min_nodes_ ? threads_ : 1; }
  int requested_threads() const { return threads_; }
  void set_threads(int n);
  std::size_t threads_min_nodes() const { return threads_min_nodes_; }
  void set_threads_min_nodes(std::size_t n) { threads_min_nodes_ = n; }
  // When the contact pair lists are rebuilt, decided once per evaluation (neighbors.hpp).
  NeighborService& neighbors() { return neighbors_; }
  const NeighborService& neighbors() const { return neighbors_; }
  // Per-thread force buffers the kernels share (see threads.hpp).
  ForceScratch& force_scratch() { return scratch_; }
  // parallel_forces() onto the node forces with this simulation's threads.
  template <class Kernel>
  double parallel_node_forces(std::size_t n, Kernel&& kernel) {
    return parallel_forces(threads(), scratch_, nodes_.f, n, std::forward<Kernel>(kernel));
  }
  // The same for kernels whose items are heavy (shell elements' Gauss points, hundreds of
  // nanoseconds each): they take the requested threads at any scene size, the node-count
  // gate of threads() being set for light per-node work.
  template <class Kernel>
  double parallel_heavy_forces(std::size_t n, Kernel&& kernel) {
    return parallel_forces(threads_, scratch_, nodes_.f, n, std::forward<Kernel>(kernel));
  }
  // The same for a kernel over the items of one chain (src/threads.hpp, ChainForces):
  // bit-identical to one thread, without per-thread force buffers.
  template <class Kernel>
  double parallel_chain_forces(std::size_t n, bool closed, long n_positions, long lo, long hi,
                               Kernel&& kernel) {
    return slender::parallel_chain_forces(threads(), chain_halos_, nodes_.f, n, closed, n_positions,
                                          lo, hi, std::forward<Kernel>(kernel));
  }

  // --- building the scene
  Chain& add_chain(const std::string& name, const std::vector<Vec3>& pos, double mass_per_node,
                   bool closed);
  // Adds a node at one end of a chain (injection): every property grows, the chain's
  // group follows, and styles re-bind before the next force evaluation.
  int grow_chain(const std::string& chain, bool at_front, const Vec3& pos, double mass,
                 double rest);
  RegionStyle& add_region(const std::string& id, const std::string& style, const RawParams& p);
  RegionStyle& region(const std::string& id);
  void set_group(const std::string& name, std::vector<int> nodes);
  // Node indices of a group; "all" is every owned node.
  std::vector<int> group(const std::string& name) const;
  bool has_group(const std::string& name) const;
  BondStyle& add_bond(const std::string& style, const RawParams& p);
  PairStyle& add_pair(const std::string& style, const RawParams& p);
  ShellStyle& add_shell(const std::string& style, const RawParams& p);
  GrowthStyle& add_growth(const std::string& id, const std::string& style, const RawParams& p);
  GrowthStyle& growth(const std::string& id);
  FixStyle& add_fix(const std::string& id, const std::string& style, const RawParams& p);
  ComputeStyle& add_compute(const std::string& id, const std::string& style, const RawParams& p);
  DumpStyle& add_dump(const std::string& id, const std::string& style, const RawParams& p);
  IntegratorStyle& set_integrator(const std::string& style, const RawParams& p);
  void remove_fix(const std::string& id);
  FixStyle& fix(const std::string& id);
  ComputeStyle& compute(const std::string& id);
  Style* find_style(const std::string& id);
  // sim:modify: new values for some of a style's parameters between runs. A checkpoint read
  // back later may differ from the scene in exactly these keys (a deck that rolls back and
  // retries with another value), so read_checkpoint does not warn about them.
  void modify_style(const std::string& id, const RawParams& raw);
  // Every style of the scene, families in a fixed order (shells, growths, bonds, pairs,
  // fixes, computes, dumps, the integrator), each in the order the deck added it.
  std::vector<Style*> styles() const;
  IntegratorStyle* integrator() { return integrator_.get(); }
  const std::vector<std::unique_ptr<BondStyle>>& bonds() const { return bonds_; }
  const std::vector<std::unique_ptr<PairStyle>>& pairs() const { return pairs_; }
  const std::vector<std::unique_ptr<ShellStyle>>& shells() const { return shells_; }
  const std::vector<std::unique_ptr<FixStyle>>& fixes() const { return fixes_; }

  // --- running
  void run(const RunOptions& opt);
  // Relaxes to a static equilibrium (max |f| < ftol and, where given, kinetic energy <= ketol)
  // with the minimiser `method` (an integrator style: "fire", or "lbfgs" for the node positions
  // only) and its parameters, or with "dynamics": the scene's own integrator and damping, which
  // needs ketol (a damped oscillation passes max |f| < ftol at every swing through
  // equilibrium). Returns the iterations taken.
  long minimize(double ftol, long max_steps, const std::string& method = "fire",
                const RawParams& params = {},
                double ketol = std::numeric_limits<double>::infinity());
  // Zeroes forces and runs the schedule's force, post-force and constrain stages;
  // records energies by category. Every force evaluation (integrators, minimisers,
  // observables) comes through here.
  void compute_forces();
  void end_of_step();
  // A style asks the run to end cleanly after the current step (e.g. jamming);
  // run() reports the reason and clears the request.
  void request_stop(const std::string& why) { stop_reason_ = why; }
  const std::string& stop_reason() const { return last_stop_; }
  // The resolved call lists (resolved now if the scene changed since).
  const Schedule& schedule();
  // Free degrees of freedom: masked components (clamps) keep zero force.
  const Property<int>* dof_mask() const { return dof_mask_; }
  void set_dof_mask(Property<int>* m) { dof_mask_ = m; }

  double dt = 0.0;
  double time = 0.0;
  long step = 0;
  bool forces_valid = false;  // forces correspond to the current state
  // Bumped whenever the state is changed outside the equations of motion
  // (minimisation, positions set from a deck); integrators with history restart it.
  long state_epoch = 0;
  GuardOptions guard;
  ThermoOptions thermo;

  // --- generalised coordinates (created on first request, stable references)
  Coordinates& coordinates(const std::string& name);
  const std::vector<std::unique_ptr<Coordinates>>& extra_coordinates() const { return coords_; }
  // Styles that compute several kinds of energy add the others here during compute().
  void add_energy(const std::string& category, double e) { energy_[category] += e; }

  // What the scene holds, as one JSON object: node properties and extra coordinates
  // with their bytes, styles by family, neighbour structures, chains and surfaces.
  // (Leave out what a scene does not need: the example tests compare it with what
  // each deck uses.)
  std::string inventory_json() const;

  // --- observables
  double kinetic_energy() const;
  // the rod frames' share of it (no frames: 0)
  double rotational_kinetic_energy() const;
  double potential_energy() const;
  const std::map<std::string, double>& energies() const { return energy_; }
  // A thermo column: step, time, dt, nodes, ke, pe, etotal, <id>.<key>.
  double column(const std::string& name);
  // The columns column() knows without a style id.
  static const std::vector<std::string>& builtin_columns();
  double max_force() const;
  // Highest frequency of all stiff terms, and the dt the integrator can take.
  double omega_max(std::string* who = nullptr) const;
  double suggest_dt(double safety = 1.0) const;
  // The same bound with the contacts as they are now (docs/models.md has no such term: it is the
  // measured stiffness of several contacts per node and deep overlaps), never below the
  // nominal one; `who` names the stiffest term. Cheap: the nominal values are cached per run.
  double omega_now(std::string* who = nullptr) const;
  double stability_limit() const;

  // --- restart files (HDF5)
  void write_checkpoint(const std::string& path);
  // Refuses, naming the file and the dataset, a file whose shapes, indices or values do
  // not fit the scene (a foreign, damaged or hand-edited file).
  void read_checkpoint(const std::string& path);

  // Lines printed to the console (thermo, schedule); tests may silence them.
  bool verbose = true;
  // A flag a signal handler sets to the signal's number (slender's main sets SIGINT and
  // SIGTERM): a run or minimisation then stops after its step, writes a last frame of every
  // dump and a checkpoint (its checkpoint dump, else interrupt_file) and throws
  // InterruptedError. Null: not watched.
  void watch_interrupt(const volatile std::sig_atomic_t* flag) { interrupt_ = flag; }
  std::string interrupt_file = "slender_interrupted.h5";

 private:
  void setup_run();
  bool interrupted() const { return interrupt_ && *interrupt_ != 0; }
  // After a run or minimisation stopped for a signal: the last frame and checkpoint, then
  // InterruptedError.
  [[noreturn]] void finish_interrupted();
  const volatile std::sig_atomic_t* interrupt_ = nullptr;
  void read_checkpoint_checked(const std::string& path);
  // Resolves which fixes act at which stage and lets styles bind to the scene.
  void build_schedule();
  void check_guard(long step_in_run);
  // "run summary": steps, wall time, node-steps/s and the time by stage (verbose runs)
  void print_run_summary(long steps, double seconds) const;
  struct RunSeconds {
    double guard = 0.0, output = 0.0;
  };
  RunSeconds run_seconds_;
  void save_good_state();
  std::string last_good_problem() const;
  // Guard, thermo and dumps after step k of a run or minimisation, which took the clock
  // from t0 to time.
  void after_step(long k, bool last, double t0);
  void write_thermo(bool header);
  Cadence thermo_cadence() const { return Cadence{thermo.every, thermo.interval}; }
  bool thermo_written_ = false;  // the last step wrote a thermo line
  void resolve_dt();
  void fail(const std::string& what, long bad_step);

  int dim_;
  std::unique_ptr<Context> context_;
  std::unique_ptr<StaticSystem> static_system_;
  std::uint64_t seed_;
  std::mt19937_64 rng_;
  int threads_ = 1;
  std::size_t threads_min_nodes_ = kThreadsMinNodes;
  ForceScratch scratch_;
  NeighborService neighbors_;
  ChainHalos chain_halos_;
  NodeStore nodes_;
  Topology topo_;
  std::map<std::string, std::unique_ptr<RegionStyle>> regions_;
  std::map<std::string, std::vector<int>> groups_;
  std::vector<std::unique_ptr<BondStyle>> bonds_;
  std::vector<std::unique_ptr<PairStyle>> pairs_;
  std::vector<std::unique_ptr<ShellStyle>> shells_;
  std::map<std::string, std::unique_ptr<GrowthStyle>> growths_;
  std::vector<std::unique_ptr<FixStyle>> fixes_;
  std::vector<std::unique_ptr<ComputeStyle>> computes_;
  std::vector<std::unique_ptr<DumpStyle>> dumps_;
  std::unique_ptr<IntegratorStyle> integrator_;
  Schedule schedule_;
  Property<int>* dof_mask_ = nullptr;
  bool schedule_dirty_ = true;
  std::string stop_reason_, last_stop_;
  std::map<std::string, double> energy_;
  std::vector<std::unique_ptr<Coordinates>> coords_;
  std::vector<std::vector<Vec4>> good_q_, good_qv_;
  ThermoWriter thermo_writer_;
  // guard state
  std::vector<Vec3> good_x_, good_v_;
  long good_step_ = -1;
  std::map<std::string, double> good_energy_;
  // a node was added since the last good state (chains grow at injection): the snapshot
  // no longer matches the arrays
  bool good_state_stale_ = false;
  double good_time_ = 0.0;
  double energy_scale_ = 0.0;
  // nominal frequencies cached at the start of a run (a shell whose growth stiffens it
  // within a run is not followed): omega^2 of the terms that measure nothing, and each
  // style that measures its contacts (pairs, fixes) with its nominal omega
  double omega2_fixed_ = 0.0;
  struct Measuring {
    const Style* style;
    double nominal;
  };
  std::vector<Measuring> measuring_;
  void cache_frequencies();
  // the keys sim:modify changed, per style id (read_checkpoint does not warn about them)
  std::map<std::string, std::set<std::string>> modified_keys_;
};

}  // namespace slender
