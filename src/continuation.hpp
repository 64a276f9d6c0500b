// Pseudo-arc-length continuation of static equilibria in a load factor (docs/models.md
// §9.4): the path (x, lambda) with f_int(x) + lambda q = 0 is followed through limit
// points, where load control fails, with a tangent predictor and a bordered Newton
// corrector on the exact Hessians (src/statics.hpp). The inertia of K (its negative pivots)
// is tracked along the path: where it changes the path has crossed a limit point (lambda
// turns back) or a bifurcation point (it does not).
#pragma once

#include <functional>
#include <limits>
#include <string>

namespace slender {

class Simulation;

struct ContinuationPoint {
  long index = 0;            // 0: the start; then each converged point
  double lambda = 0.0;       // load factor
  long negative_pivots = 0;  // unstable directions of K (0: a stable equilibrium)
  int iterations = 0;        // corrector iterations it took
  double ds = 0.0;           // arc-length step that reached it
  std::string event;         // "", "limit point" or "bifurcation point" (crossed since the last)
  double critical_lambda = 0.0;  // where the event lies (bisected on the arc length), else lambda
};

struct ContinuationOptions {
  // id of the style whose parameter lambda walks (Style::set_continuation_parameter)
  std::string load;
  double lambda0 = 0.0;
  double lambda_min = -std::numeric_limits<double>::infinity();
  double lambda_max = std::numeric_limits<double>::infinity();
  double ds = 0.05;  // first arc-length step (in the scaled norm, see §9.4)
  double ds_max = 0.5;
  double ds_min = 1e-8;
  long points = 100;        // converged points to take at most
  double ftol = 1e-8;       // largest force at a converged point
  int max_iterations = 25;  // corrector iterations before the step is halved
  // at the first bifurcation point, leave the path onto the bifurcated branch (§9.4)
  bool switch_branch = false;
  // called at every converged point (and the start); returns true to stop
  std::function<bool(Simulation&, const ContinuationPoint&)> callback;
};

struct ContinuationResult {
  long points = 0;
  double lambda = 0.0;
  long limit_points = 0, bifurcation_points = 0;
};

ContinuationResult continuation(Simulation& sim, const ContinuationOptions& opt);

}  // namespace slender
