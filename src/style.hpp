// Base classes of the style families. A force style (bond, pair, shell, fix, growth,
// region) receives the scene's Context (src/context.hpp) at construction and in every
// call; integrators, computes and dumps drive or observe the run and receive the
// Simulation. A style requests the node properties it needs at construction.
#pragma once

#include <algorithm>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "cadence.hpp"
#include "nodes.hpp"
#include "params.hpp"

namespace slender {

class Simulation;
class Context;
class Hessian;

// Named arrays a style saves in checkpoints so a restart is bit-identical.
using StateMap = std::map<std::string, std::vector<double>>;

// What a style measured with the forces a checkpoint restores (contact counts, force sums):
// the forces are not recomputed on a restart, so these come back with them.
inline void save_measured(StateMap& st, std::vector<double> values) {
  st["measured"] = std::move(values);
}
// The saved values, or none if the checkpoint has no n of them (older files).
inline const std::vector<double>* load_measured(const StateMap& st, std::size_t n) {
  auto it = st.find("measured");
  return it != st.end() && it->second.size() == n ? &it->second : nullptr;
}

// An index read from a checkpoint, or -1 if the number is none (negative, fractional,
// NaN, beyond int): check_loaded() then reports it instead of indexing with it.
inline int saved_index(double d) {
  return d >= 0 && d < 2147483647.0 && d == static_cast<double>(static_cast<long long>(d))
             ? static_cast<int>(d)
             : -1;
}

// A saved array of a style's state holding at least n values; a checkpoint that lacks it or
// holds fewer is refused (read_checkpoint names the file and the style), never indexed past
// its end.
inline const std::vector<double>& saved_array(const StateMap& st, const std::string& key,
                                              std::size_t n = 0) {
  auto it = st.find(key);
  if (it == st.end()) throw InputError("its saved state lacks the array '" + key + "'");
  if (it->second.size() < n)
    throw InputError("its saved array '" + key + "' holds " + std::to_string(it->second.size()) +
                     " values, at least " + std::to_string(n) + " expected");
  return it->second;
}
// A count or flag read from a checkpoint, clamped into the type's range: the cast of a
// damaged file's 1e20 would be undefined (the values are finite: read_checkpoint checks).
inline int saved_int(double d) {
  return static_cast<int>(std::clamp(d, -2147483648.0, 2147483647.0));
}
inline long saved_long(double d) {
  return static_cast<long>(std::clamp(d, -9.2e18, 9.2e18));
}

class Style {
 public:
  // Whether the family's constructors and calls take the Context (else the Simulation).
  static constexpr bool kSeesContext = false;
  virtual ~Style() = default;
  const std::string& style_name() const { return style_name_; }
  void set_style_name(const std::string& s) { style_name_ = s; }
  const std::string& id() const { return id_; }
  void set_id(const std::string& s) { id_ = s; }
  // The validated parameters it was made with (ParamValues::text), updated by sim:modify;
  // checkpoints record them, and a restart under other values is reported.
  const std::string& parameters() const { return parameters_; }
  void set_parameters(std::string text) { parameters_ = std::move(text); }
  // sim:modify's new values into parameters(), key by key
  void note_modified(const RawParams& raw);

  // The family this style belongs to ("bond", "pair", ...), for messages and summaries.
  virtual const char* family_name() const = 0;
  // Highest angular frequency this style can excite (0 for styles that add no force), for
  // the stable time step; styles that measure their contacts also report the frequency
  // measured at the last evaluation, which an adaptive step follows (Simulation::omega_now).
  virtual double max_frequency(const Context&) const { return 0.0; }
  virtual bool measures_frequency() const { return false; }
  // Negative: this style measures nothing (a fix without contacts), and its nominal
  // max_frequency stands for it also where the measured frequencies are trusted alone.
  virtual double measured_frequency() const { return -1.0; }

  // Order within each stage of the schedule (src/schedule.hpp): lower first; equal
  // priorities keep the order the deck added the styles. Family defaults: shells -100,
  // bonds and fixes 0, pairs 100.
  virtual int priority() const { return 0; }
  // Called once the style has its id, before any run: the place to request node
  // properties whose names depend on the id.
  virtual void attach(Context&) {}
  virtual void save_state(StateMap&) const {}
  virtual void load_state(const StateMap&) {}
  // Continuation (sim:continuation, docs/models.md §9.4): sets the parameter lambda that
  // the continuation walks. For a load it is a linear factor (1: the load as the deck gave
  // it; force/constant, moment2d, prescribe, the koiter shell's loads); for growth econe it
  // is the excess angle phi_e itself. False where the style has no such parameter.
  virtual bool set_continuation_parameter(double) { return false; }
  // After a checkpoint was read (nodes, chains and every style's state in place): what is
  // wrong with the loaded state (indices past the nodes or edges, short arrays), or "".
  virtual std::string check_loaded(const Context&) const { return ""; }
  // The guard's last good state (src/simulation_guard.cpp): keep() records what save_state()
  // writes, restore_kept() puts it back after diverged steps, so that a rollback and the
  // last-good file hold no state of the bad steps. Styles whose state is large (pair lists)
  // override both with direct copies.
  virtual void keep() {
    kept_.clear();
    save_state(kept_);
  }
  virtual void restore_kept() {
    if (!kept_.empty()) load_state(kept_);
  }
  // How far the run is toward this style's own stop condition, in [0, 1] (a packing density
  // toward its target), with `what` naming it; -1 when the style has none. The run's
  // progress line turns it into an ETA.
  virtual double stop_progress(std::string* what) const {
    (void)what;
    return -1.0;
  }
  // Scalars this style offers to thermo as "<id>.<key>".
  // Default: the outputs of the style's declaration (ParamSpec::output).
  virtual std::vector<std::string> value_keys() const;
  virtual double value(const std::string& key) const;
  // Changes parameters between runs (sim:modify). Default: not supported.
  virtual void modify(const RawParams& raw);
  // Lines that draw the rigid body this style stands for (a wall) as it is now, for the
  // trajectory dumps (the XDMF side file of the walls); none by default.
  virtual std::vector<std::vector<Vec3>> outline() const { return {}; }
  // Per-element arrays (shell faces) this style offers to dumps, e.g. "Ub"; null if none.
  virtual const std::vector<double>* face_values(const std::string&) const { return nullptr; }
  // The Hessian of this style's energy over the node positions at the current state,
  // added to H (src/hessian.hpp), for Newton statics (integrator "newton"). Returns false
  // where the style has none (the solver then names it); a style whose forces do not depend
  // on the positions at rest (a constant load, a dashpot) returns true and adds nothing.
  virtual bool add_hessian(Context&, Hessian&) const { return false; }

 private:
  std::string style_name_, id_, parameters_;
  StateMap kept_;
};

// Interactions along chains (stretching, bending, torsion, hysteresis).
class BondStyle : public Style {
 public:
  static const char* family() { return "bond"; }
  const char* family_name() const override { return family(); }
  static constexpr bool kSeesContext = true;
  // Adds forces to nodes().f and returns the energy of this style.
  virtual double compute(Context& sim) = 0;
  // Energy category for thermo ("stretch", "bend", ...).
  virtual const char* energy_category() const = 0;
  double max_frequency(const Context& sim) const override = 0;
  // Chains this instance acts on.
  virtual void setup(Context&) {}
};

// Contacts found by neighbour search (families in later issues).
class PairStyle : public Style {
 public:
  static const char* family() { return "pair"; }
  const char* family_name() const override { return family(); }
  static constexpr bool kSeesContext = true;
  int priority() const override { return 100; }
  virtual void setup(Context&) {}
  virtual double compute(Context& sim) = 0;
  double max_frequency(const Context& sim) const override = 0;
  // The frequency of its contacts as they are now, at the last force evaluation (0 where
  // none); the adaptive step uses the larger of this and max_frequency.
  bool measures_frequency() const override { return true; }
  // The neighbour search this pair builds (for the scene inventory), e.g. "linked cells".
  virtual std::string neighbor_structure() const { return "pair list"; }
};

// Step stages a fix can act at. A fix that reads the complete forces in post_force (a
// measured injection force) returns a priority above every other fix's, e.g.
// kMeasuresForces.
enum FixStage : unsigned {
  kSetup = 1u << 0,
  kPostForce = 1u << 1,
  kEndOfStep = 1u << 2,
};
inline constexpr int kMeasuresForces = 1000;

class FixStyle : public Style {
 public:
  static const char* family() { return "fix"; }
  const char* family_name() const override { return family(); }
  static constexpr bool kSeesContext = true;
  virtual unsigned stages() const = 0;
  virtual void setup(Context&) {}
  // Called by sim:unfix before the fix is destroyed: release what it holds in shared
  // node data (a clamp's mask bits).
  virtual void detach(Context&) {}
  // Adds forces; returns the potential energy of conservative fixes (else 0).
  virtual double post_force(Context&) { return 0.0; }
  virtual void end_of_step(Context&) {}
  // Fixes report their contacts' frequency as pairs do (walls in contact now).
  bool measures_frequency() const override { return true; }
};

// Thin shells on triangle meshes (docs/models.md §6): their own family, evaluated
// before bonds and pairs because they also place the ghost nodes of their mesh.
class ShellStyle : public Style {
 public:
  static const char* family() { return "shell"; }
  const char* family_name() const override { return family(); }
  static constexpr bool kSeesContext = true;
  // first in the force stage: a shell places its ghost nodes, which bonds may read
  int priority() const override { return -100; }
  virtual void setup(Context&) {}
  // Adds forces; records its energies with Context::add_energy.
  virtual void compute(Context& sim) = 0;
  double max_frequency(const Context& sim) const override = 0;
};

// In-plane growth tensors G(X, t) of the multiplicative decomposition F = A G
// (docs/models.md §6.2, §6.9), evaluated at reference positions.
class GrowthStyle : public Style {
 public:
  static const char* family() { return "growth"; }
  const char* family_name() const override { return family(); }
  static constexpr bool kSeesContext = true;
  // 3x3 world-frame tensor; only its action on tangent vectors matters.
  virtual Eigen::Matrix3d tensor(const Vec3& X, double time) const = 0;
  // Depends on time by itself (not only through sim:modify).
  virtual bool time_dependent() const { return false; }
  // Styles defined by a deck function receive it here (growth "function").
  using Function = std::function<Eigen::Matrix3d(const Vec3&, double)>;
  virtual bool wants_function() const { return false; }
  virtual void set_function(Function) {}
  // Bumped by modify(), so shells know when to recompute their growth data.
  long version() const { return version_; }

 protected:
  void bump() { ++version_; }

 private:
  long version_ = 0;
};

class ComputeStyle : public Style {
 public:
  static const char* family() { return "compute"; }
  const char* family_name() const override { return family(); }
  virtual void evaluate(Simulation& sim) = 0;
};

class DumpStyle : public Style {
 public:
  static const char* family() { return "dump"; }
  const char* family_name() const override { return family(); }
  // When a frame is due: every N steps or every T time units (the style's every/interval).
  const Cadence& cadence() const { return cadence_; }
  virtual void write(Simulation& sim) = 0;
  virtual void flush() {}

 protected:
  void set_cadence(const Cadence& c) { cadence_ = c; }

 private:
  Cadence cadence_;
};

class IntegratorStyle : public Style {
 public:
  static const char* family() { return "integrator"; }
  const char* family_name() const override { return family(); }
  // Prepares state (e.g. higher derivatives) before the first step of a run.
  virtual void setup(Simulation& sim) = 0;
  virtual void step(Simulation& sim) = 0;
  // A style added generalised coordinates (Simulation::coordinates): an integrator
  // with history arrays allocates them now, so that checkpoints find them.
  virtual void coordinates_added(Simulation&) {}
  // Largest omega*dt for which the scheme is stable on an undamped oscillator.
  virtual double stability_limit() const = 0;
  // False for a minimiser that is not a time stepper (L-BFGS): the scene's clock stands.
  virtual bool advances_time() const { return true; }
  // Requested time step, or <= 0 for "auto".
  double requested_dt() const { return dt_; }
  double safety() const { return safety_; }
  // The run sets dt before every step from the measured stiffness (Simulation::omega_now).
  virtual bool adaptive() const { return false; }
  // With adaptive(): the contacts' measured frequencies stand alone, also below their
  // nominal estimates, and dt = "auto" may grow up to the stable step of the terms that
  // measure nothing (bonds, shells, damping) instead of stopping at the nominal step.
  virtual bool trusts_measured() const { return false; }

 protected:
  // The "dt" and "safety" keys every integrator takes.
  static void declare_time_step(ParamSpec& s, const std::string& dt_help) {
    s.add("dt", ParamType::RealOrAuto, dt_help).def(std::string("auto")).positive();
    s.real("safety", "fraction of the stable step used by dt = \"auto\"")
        .def(0.5)
        .positive()
        .max(1.0);
  }
  void read_time_step(const ParamValues& p) {
    dt_ = p.is_auto("dt") ? 0.0 : p.real("dt");
    safety_ = p.real("safety");
  }

 private:
  double dt_ = 0.0, safety_ = 0.5;
};

class RegionStyle : public Style {
 public:
  static const char* family() { return "region"; }
  const char* family_name() const override { return family(); }
  static constexpr bool kSeesContext = true;
  virtual bool contains(const Vec3& x) const = 0;
  // Part of the domain: a node outside every bounding region stops the run.
  bool bounds() const { return bounds_; }
  void set_bounds(bool b) { bounds_ = b; }

 private:
  bool bounds_ = false;
};

}  // namespace slender
