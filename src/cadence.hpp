// When a periodic action (a thermo line, a trajectory frame, a checkpoint) is due: every
// N steps, or every T time units. A time cadence means the same output at any dt and
// under an adaptive step; a step cadence of the same deck gives 25x sparser output when
// the step grows 25x.
#pragma once

#include <cmath>
#include <string>

#include "params.hpp"

namespace slender {

struct Cadence {
  long steps = 0;         // > 0: every this many steps
  double interval = 0.0;  // > 0: each time the clock passes a multiple of this

  bool active() const { return steps > 0 || interval > 0; }
  // Due after the step that ended at `step` and took the clock from t0 to t1: the step
  // count is a multiple of `steps`, or the clock passed a multiple of `interval` (each
  // multiple is counted once: the index floor(t / interval) only grows).
  bool due(long step, double t0, double t1) const {
    if (steps > 0) return step % steps == 0;
    if (interval > 0) return index(t1) > index(t0);
    return false;
  }
  // Due at the start of a run at (step, time): a multiple of `steps`, or a clock on a
  // multiple of `interval` (a fresh scene at t = 0).
  bool due_at(long step, double time) const {
    if (steps > 0) return step % steps == 0;
    if (interval > 0) {
      const double q = time / interval;
      return std::abs(q - std::round(q)) < 1e-9;
    }
    return false;
  }
  double index(double t) const { return std::floor(t / interval + 1e-9); }

  // The "every" (steps) and "interval" (time) keys of an output; exactly one is needed
  // where `required`.
  static void declare(ParamSpec& s, const std::string& what) {
    s.integer("every", "steps between " + what + " (or give interval)").min(1);
    s.real("interval",
           "time between " + what +
               " (instead of every: the same output at any dt and under an adaptive step)")
        .positive();
  }
  static Cadence from(const ParamValues& p, const std::string& owner, bool required) {
    Cadence c;
    if (p.has("every") && p.has("interval"))
      throw InputError(owner + ": give every (steps) or interval (time), not both");
    if (p.has("every")) c.steps = p.integer("every");
    if (p.has("interval")) c.interval = p.real("interval");
    if (required && !c.active())
      throw InputError(owner + ": give every (steps) or interval (time units)");
    return c;
  }
};

}  // namespace slender
