// Simulation: the instability guard (checks after steps, the last good state, the stop).
#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <sstream>

#include "registry.hpp"
#include "simulation.hpp"

namespace slender {

void Simulation::fail(const std::string& what, long bad_step) {
  std::ostringstream os;
  os << "instability at step " << bad_step << " (t = " << time << "): " << what << ".";
  std::string who;
  double w = omega_max(&who);
  if (!std::isfinite(w)) {
    // no step is stable: a term's frequency is infinite (a node of zero or vanishing mass,
    // a non-finite stiffness), so advice about dt would be wrong (found by fuzzing)
    os << " No time step is stable: the highest frequency of " << who
       << " is not finite (a node of zero or vanishing mass, or a non-finite stiffness "
          "or state): look at the masses and the stiffnesses the deck or checkpoint gives.";
  } else if (w > 0) {
    double limit = suggest_dt(1.0);
    if (dt > limit && integrator_ && integrator_->adaptive() && integrator_->trusts_measured())
      os << " The adaptive step dt = " << dt
         << " trusted the contacts' measured stiffness (omega now " << omega_now()
         << ") and was above the nominal stable limit " << limit << " (stiffest term: " << who
         << ", combined omega_max = " << w
         << "); rerun with trust_measured = false, or with dt <= " << suggest_dt(0.5) << ".";
    else if (dt > limit)
      os << " The time step dt = " << dt << " is above the stable limit " << limit
         << " of integrator " << integrator_->style_name() << " (stiffest term: " << who
         << ", combined omega_max = " << w << "); rerun with dt <= " << suggest_dt(0.5)
         << " or dt = \"auto\".";
    else
      os << " dt = " << dt << " is below the stable limit " << limit << " of the stiff terms ("
         << who
         << "), so look at contact overlaps, loads or nodes out of place; a smaller dt (e.g. "
         << dt * 0.5 << ") may still help.";
  }
  // Return to the last good state and dump it, so nothing is lost and the user can
  // inspect it or continue with a smaller dt. The forces of the bad steps are reset; node
  // properties (Gear derivatives too) and the styles' state come back as they were, and
  // integrators restart their history (state_epoch).
  if (good_step_ >= 0 && !good_state_stale_ && good_x_.size() == nodes_.size()) {
    nodes_.x = good_x_;
    nodes_.v = good_v_;
    for (size_t k = 0; k < coords_.size() && k < good_q_.size(); ++k) {
      coords_[k]->q->values() = good_q_[k];
      coords_[k]->v->values() = good_qv_[k];
    }
    // every saved node property (plastic curvature, wall springs, ...) and every style's
    // state (pair lists, dissipated energy, the feed) as they were at the good step
    std::string missing;
    for (auto& [name, p] : nodes_.properties())
      if (p->options().restart && !p->restore_kept())
        missing += (missing.empty() ? "" : ", ") + name;
    for (Style* s : styles()) s->restore_kept();
    energy_ = good_energy_;
    step = good_step_;
    time = good_time_;
    for (auto& f : nodes_.f) f.setZero();
    forces_valid = false;
    ++state_epoch;
    // the guard checks its own last good state: a non-finite value there means the
    // divergence began before the last check, and the file would hold garbage
    std::string bad =
        missing.empty() ? last_good_problem() : "node properties " + missing + " were not kept";
    if (!bad.empty()) {
      os << " The last good state (step " << good_step_ << ") is not usable (" << bad
         << "); nothing was written.";
    } else {
      try {
        write_checkpoint(guard.last_good_file);
        os << " Last good state (step " << good_step_ << ") written to " << guard.last_good_file
           << ".";
      } catch (const std::exception& e) {
        os << " (could not write the last good state: " << e.what() << ")";
      }
    }
    for (auto& d : dumps_) d->flush();
  } else if (good_step_ >= 0) {
    os << " No last good state was written: a node was added since the last check (step "
       << good_step_ << "); guard{every = ...} checks more often.";
    for (auto& d : dumps_) d->flush();
  }
  throw InstabilityError(os.str());
}

// The state a failed run returns to. Copy-assignment into the kept vectors reuses their
// memory (the guard runs every few steps; the quaternion snapshots were reallocated each
// time).
void Simulation::save_good_state() {
  good_x_ = nodes_.x;
  good_v_ = nodes_.v;
  for (auto& [name, p] : nodes_.properties())
    if (p->options().restart) p->keep();
  for (Style* s : styles()) s->keep();
  good_energy_ = energy_;
  good_state_stale_ = false;
  good_q_.resize(coords_.size());
  good_qv_.resize(coords_.size());
  for (size_t k = 0; k < coords_.size(); ++k) {
    good_q_[k] = coords_[k]->q->values();
    good_qv_[k] = coords_[k]->v->values();
  }
}

// What is not finite in the state the guard returned to, or "" if all is (positions,
// velocities, frames, saved node properties, the styles' saved state, energies).
std::string Simulation::last_good_problem() const {
  auto finite = [](const std::vector<double>& v) {
    for (double x : v)
      if (!std::isfinite(x)) return false;
    return true;
  };
  for (size_t i = 0; i < nodes_.size(); ++i)
    if (!nodes_.x[i].allFinite() || !nodes_.v[i].allFinite())
      return "node " + std::to_string(i + 1) + " position or velocity";
  for (auto& c : coords_)
    for (auto& q : c->q->values())
      if (!q.allFinite()) return "frames " + c->name;
  for (auto& [name, p] : nodes_.properties())
    if (p->options().restart && !finite(p->to_flat())) return "node property " + name;
  for (Style* s : styles()) {
    StateMap st;
    s->save_state(st);
    for (auto& [key, v] : st)
      if (!finite(v)) return "state '" + key + "' of " + s->id();
  }
  for (auto& [k, e] : energy_)
    if (!std::isfinite(e)) return "energy " + k;
  return "";
}

void Simulation::check_guard(long) {
  const size_t n = nodes_.n_owned();
  // One pass on the threads' node ranges (threads.hpp): each range's first non-finite node
  // and its fastest node (the first of equals); the ranges are taken in order, so the
  // verdict and the node named are those of a serial scan.
  // The same pass sums the kinetic energy of the dynamics: components a fix drives (held
  // in dof_mask: a prescribed motion, injection channels) move as told, from rest too, and
  // are no runaway.
  struct Scan {
    size_t bad = SIZE_MAX;
    bool bad_force = false;
    double vmax = 0.0;
    size_t imax = 0;
    double ke = 0.0;
  };
  const Property<int>* held = nodes_.find<int>(kHeldComponents);
  std::array<Scan, kMaxThreads> scans{};
  const int T = parallel_ranges(
      threads(), n,
      [&](int tid, size_t begin, size_t end) {
        Scan s;
        for (size_t i = begin; i < end; ++i) {
          const Vec3& v = nodes_.v[i];
          if (s.bad == SIZE_MAX) {
            if (!nodes_.x[i].allFinite() || !v.allFinite()) {
              s.bad = i;
            } else if (!nodes_.f[i].allFinite()) {
              s.bad = i;
              s.bad_force = true;
            }
          }
          double v2 = v.squaredNorm();
          const double sp = std::sqrt(v2);
          if (sp > s.vmax) {
            s.vmax = sp;
            s.imax = i;
          }
          if (held)
            if (const int bits = (*held)[i])
              for (int c = 0; c < 3; ++c)
                if (bits & (1 << c)) v2 -= v[c] * v[c];
          s.ke += 0.5 * nodes_.mass[i] * v2;
        }
        scans[static_cast<size_t>(tid)] = s;
      },
      kMinLightItemsPerThread);
  double vmax = 0.0, ke = 0.0;
  size_t imax = 0;
  for (int t = 0; t < T; ++t) {
    const Scan& s = scans[static_cast<size_t>(t)];
    if (s.bad != SIZE_MAX) {
      if (s.bad_force) fail("non-finite force on node " + std::to_string(s.bad + 1), step);
      fail("non-finite position or velocity of node " + std::to_string(s.bad + 1), step);
    }
    if (s.vmax > vmax) {
      vmax = s.vmax;
      imax = s.imax;
    }
    ke += s.ke;
  }
  ke += rotational_kinetic_energy();
  double lmin = topo_.min_rest_length();
  if (lmin < 1e299) {
    if (vmax * dt > guard.max_step_fraction * lmin) {
      // advise from the last good state's speed when this one has already blown up
      double vgood = 0.0;
      for (const Vec3& vg : good_v_) vgood = std::max(vgood, vg.norm());
      const double vref = good_step_ >= 0 && vmax > 10 * vgood && vgood > 0 ? vgood : vmax;
      std::ostringstream os;
      os << "node " << imax + 1 << " moves " << vmax * dt << " per step (speed " << vmax
         << "), more than " << guard.max_step_fraction << " of the shortest rest length " << lmin;
      // above the stable step the speed is a symptom: fail() names the stable dt instead
      const double limit = suggest_dt(1.0);
      if (!(limit > 0) || dt <= limit)
        os << ", so contacts can be missed; at "
           << (vref < vmax ? "the last good state's " : "this ")
           << "speed dt <= " << 0.5 * guard.max_step_fraction * lmin / vref
           << " keeps it to half of that (or slow the driving down)";
      fail(os.str(), step);
    }
  }
  // a wire torn apart or crushed: far beyond any elastic strain the styles model
  for (auto& c : topo_.chains) {
    // each thread's first edge beyond the strain; the first of them in thread order
    std::array<int, kMaxThreads> first_bad;
    first_bad.fill(INT_MAX);
    const int Te = parallel_ranges(
        threads(), static_cast<size_t>(c.n_edges()),
        [&](int tid, size_t begin, size_t end) {
          for (size_t k = begin; k < end; ++k) {
            const int e = static_cast<int>(k);
            const double ratio =
                (nodes_.x[c.edge_head(e)] - nodes_.x[c.edge_tail(e)]).norm() / c.rest_length[k];
            if (std::abs(ratio - 1.0) > guard.max_strain) {
              first_bad[static_cast<size_t>(tid)] = e;
              return;
            }
          }
        },
        kMinLightItemsPerThread);
    for (int t = 0; t < Te; ++t) {
      const int e = first_bad[static_cast<size_t>(t)];
      if (e == INT_MAX) continue;
      const double ratio =
          (nodes_.x[c.edge_head(e)] - nodes_.x[c.edge_tail(e)]).norm() / c.rest_length[e];
      std::ostringstream os;
      os << "edge " << e + 1 << " of chain '" << c.name << "' (nodes " << c.edge_tail(e) + 1 << "-"
         << c.edge_head(e) + 1 << ") is at " << ratio << " times its rest length (guard max_strain "
         << guard.max_strain << ")";
      fail(os.str(), step);
    }
  }
  ke = std::max(ke, 0.0);
  const double pe = std::abs(potential_energy());
  if (ke > guard.ke_factor * std::max(energy_scale_, pe) && ke > 1e-200) {
    std::ostringstream os;
    os << "runaway kinetic energy " << ke << " (more than " << guard.ke_factor
       << " times the largest energy seen so far, " << std::max(energy_scale_, pe) << ")";
    fail(os.str(), step);
  }
  bool any_bounds = false;
  for (auto& [id, r] : regions_) any_bounds = any_bounds || r->bounds();
  if (any_bounds) {
    for (size_t i = 0; i < n; ++i) {
      bool inside = false;
      for (auto& [id, r] : regions_)
        if (r->bounds() && r->contains(nodes_.x[i])) inside = true;
      if (!inside) fail("node " + std::to_string(i + 1) + " left every bounding region", step);
    }
  }
  energy_scale_ = std::max(energy_scale_, ke + pe);
  save_good_state();
  good_step_ = step;
  good_time_ = time;
}

}  // namespace slender
