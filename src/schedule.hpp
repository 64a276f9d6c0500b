// The step's call lists (the role of LAMMPS's Modify): which style acts at which stage of
// a force evaluation or step, in which order. Styles declare their stages (a fix's
// stages()) and a priority (Style::priority(): lower first; equal priorities keep the
// order the deck added them); the schedule is resolved once when the scene changes and
// printed at `run`. Integrators call Simulation::compute_forces() and end_of_step(),
// which run these lists.
#pragma once

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "style.hpp"

namespace slender {

class Simulation;

enum class Stage { kForce, kPostForce, kConstrain, kEndOfStep };

class Schedule {
 public:
  // What the core itself does in the constrain stage after the styles' forces.
  struct Constraints {
    bool dof_mask = false;                      // clamped components keep zero force
    bool plane = false;                         // 2D: no force out of the plane
    std::vector<std::string> unit_coordinates;  // quaternions kept on |q| = 1
  };

  // Resolves the call lists from the scene's styles (in the order the deck added them).
  void build(const std::vector<ShellStyle*>& shells, const std::vector<BondStyle*>& bonds,
             const std::vector<PairStyle*>& pairs, const std::vector<FixStyle*>& fixes,
             Constraints constraints);

  // The force and post-force stages; energies by category ("stretch", "contact",
  // "external", and what shells record themselves).
  void forces(Simulation& sim, std::map<std::string, double>& energy) const;
  void end_of_step(Simulation& sim) const;
  const Constraints& constraints() const { return constraints_; }
  // Fixes in the post-force stage, in call order (the scene inventory lists them).
  std::vector<const FixStyle*> post_force_fixes() const;

  // One line per stage, e.g. "force: shell koiter (-100); bond spring (0); ..." — printed at
  // `run` and compared by the golden test.
  std::string describe() const;

  // Wall seconds spent in each call since the last reset (kept across rebuilds of the lists
  // for the styles that stay), for the end-of-run summary: (family id [stage], seconds).
  std::vector<std::pair<std::string, double>> timings() const;
  void reset_timings();

 private:
  struct Call {
    Stage stage;
    int priority;
    ShellStyle* shell = nullptr;
    BondStyle* bond = nullptr;
    PairStyle* pair = nullptr;
    FixStyle* fix = nullptr;
    mutable double seconds = 0.0;
    const Style* style() const;
    std::string label() const;
  };
  std::vector<Call> calls_;  // sorted by stage, then priority, then the deck's order
  Constraints constraints_;
};

}  // namespace slender
