// Simulation: energy minimisation (FIRE, L-BFGS) by swapping in a minimiser as integrator.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "registry.hpp"
#include "simulation.hpp"

namespace slender {

long Simulation::minimize(double ftol, long max_steps, const std::string& method,
                          const RawParams& params, double ketol) {
  const bool dynamics = method == "dynamics";
  if (method != "fire" && method != "lbfgs" && method != "newton" && !dynamics)
    throw InputError(
        "minimize: method must be \"fire\", \"lbfgs\", \"newton\" or \"dynamics\", got \"" +
        method + "\"");
  if (dynamics && !integrator_)
    throw InputError(
        "minimize: method \"dynamics\" relaxes with the scene's integrator and its damping; "
        "set one with sim:integrator first");
  if (dynamics && !std::isfinite(ketol))
    throw InputError(
        "minimize: method \"dynamics\" needs ketol (a kinetic energy tolerance): a damped "
        "oscillation passes the force tolerance at every swing through equilibrium");
  std::unique_ptr<IntegratorStyle> saved;
  double saved_dt = dt;
  if (!dynamics) {
    saved = std::move(integrator_);
    RawParams p = params;
    if (saved && saved->requested_dt() > 0) p["dt"] = saved->requested_dt();
    integrator_ = Registry<IntegratorStyle>::create(method, *this, p);
    integrator_->set_id("minimize");
  }
  const bool clock = integrator_->advances_time();
  auto settled = [&] { return max_force() < ftol && kinetic_energy() <= ketol; };
  long taken = 0;
  try {
    setup_run();
    if (thermo_cadence().active()) write_thermo(true);
    thermo_written_ = true;
    for (; taken < max_steps; ++taken) {
      if (settled()) break;
      const double t0 = time;
      integrator_->step(*this);
      ++step;
      if (clock) time += dt;
      after_step(taken + 1, false, t0);
      if (interrupted()) {
        ++taken;
        break;
      }
    }
    check_guard(taken);
    if (thermo_cadence().active() && !thermo_written_) write_thermo(false);
    for (auto& d : dumps_) d->flush();
    if (interrupted()) finish_interrupted();
  } catch (...) {
    if (!dynamics) integrator_ = std::move(saved);
    throw;
  }
  const double ke = kinetic_energy();
  auto g3 = [](double v) {
    char b[32];
    std::snprintf(b, sizeof b, "%.3g", v);
    return std::string(b);
  };
  for (auto& v : nodes_.v) v.setZero();
  for (auto& c : coords_)
    for (auto& v : c->v->values()) v.setZero();
  ++state_epoch;
  std::string extra;
  if (dynamics) {
    extra = " (" + integrator_->style_name() + ")";
  } else {
    for (const auto& key : integrator_->value_keys())  // e.g. L-BFGS force evaluations
      extra += ", " + key + " " + std::to_string(static_cast<long>(integrator_->value(key)));
    integrator_ = std::move(saved);
    if (saved_dt > 0) dt = saved_dt;  // else keep FIRE's last step as the scene's dt
  }
  if (std::isfinite(ketol))
    extra += ", kinetic energy " + g3(ke) + " (tolerance " + g3(ketol) + ")";
  if (verbose)
    std::printf("minimize: %ld %s steps%s, max |f| = %.3g (tolerance %.3g)\n", taken,
                method == "fire"     ? "FIRE"
                : method == "lbfgs"  ? "L-BFGS"
                : method == "newton" ? "Newton"
                                     : "damped dynamics",
                extra.c_str(), max_force(), ftol);
  return taken;
}

}  // namespace slender
