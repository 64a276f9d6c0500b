#include "simulation.hpp"
#include "context.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>

#include "registry.hpp"
#include "statics.hpp"

namespace slender {

std::vector<std::string> Style::value_keys() const {
  std::vector<std::string> keys;
  for (auto& e : Catalog::entries())
    if (e.family == family_name() && e.name == style_name()) {
      for (auto& [key, help] : e.spec().outputs) keys.push_back(key);
      break;
    }
  return keys;
}
double Style::value(const std::string& key) const {
  throw InputError("'" + id() + "' (" + style_name() + ") has no value '" + key + "'");
}
void Style::note_modified(const RawParams& raw) {
  std::map<std::string, std::string> lines;
  std::istringstream in(parameters_);
  for (std::string line; std::getline(in, line);) {
    const auto eq = line.find(" = ");
    if (eq != std::string::npos) lines[line.substr(0, eq)] = line.substr(eq + 3);
  }
  for (auto& [key, v] : raw) lines[key] = ParamValues::exact_text(v);
  parameters_.clear();
  for (auto& [key, text] : lines) parameters_ += key + " = " + text + "\n";
}
void Simulation::modify_style(const std::string& id, const RawParams& raw) {
  Style* s = find_style(id);
  if (!s) throw InputError("modify: no style with id '" + id + "'");
  s->modify(raw);
  s->note_modified(raw);
  for (auto& kv : raw) modified_keys_[id].insert(kv.first);
  forces_valid = false;
}
void Style::modify(const RawParams&) {
  throw InputError("'" + id() + "' (" + style_name() + ") cannot be modified between runs");
}

Simulation::Simulation(int dimension, std::uint64_t seed)
    : dim_(dimension), context_(std::make_unique<Context>(*this)), seed_(seed), rng_(seed) {
  if (dimension != 2 && dimension != 3)
    throw InputError("dimension must be 2 or 3, got " + std::to_string(dimension));
}

Context& context_of(Simulation& sim) {
  return sim.context();
}
Simulation::~Simulation() = default;

StaticSystem& Simulation::static_system() {
  if (!static_system_) static_system_ = std::make_unique<StaticSystem>(*this);
  return *static_system_;
}

void Simulation::set_threads(int n) {
  if (n < 1 || n > kMaxThreads)
    throw InputError("threads must be in [1, " + std::to_string(kMaxThreads) + "], got " +
                     std::to_string(n));
#ifndef _OPENMP
  if (n > 1) throw InputError("threads > 1: this slender was built without OpenMP");
#endif
  threads_ = n;
}

Chain& Simulation::add_chain(const std::string& name, const std::vector<Vec3>& pos,
                             double mass_per_node, bool closed) {
  if (topo_.find(name)) throw InputError("a chain named '" + name + "' already exists");
  if (pos.size() < 2) throw InputError("chain '" + name + "' needs at least 2 nodes");
  if (closed && pos.size() < 3) throw InputError("closed chain '" + name + "' needs 3 nodes");
  // everything is checked before the first node is added: a refused chain leaves no nodes
  std::vector<Vec3> q(pos);
  for (std::size_t i = 0; i < q.size(); ++i) {
    if (dim_ == 2) q[i].z() = 0.0;
    if (!q[i].allFinite())
      throw InputError("chain '" + name + "': node " + std::to_string(i + 1) +
                       " has a non-finite position (" + std::to_string(q[i].x()) + ", " +
                       std::to_string(q[i].y()) + ", " + std::to_string(q[i].z()) + ")");
  }
  Chain c;
  c.name = name;
  c.closed = closed;
  const std::size_t n = q.size(), ne = closed ? n : n - 1;
  for (std::size_t e = 0; e < ne; ++e) {
    const double l = (q[(e + 1) % n] - q[e]).norm();
    if (!(l > 0))
      throw InputError("chain '" + name + "': nodes " + std::to_string(e + 1) + " and " +
                       std::to_string((e + 1) % n + 1) + " coincide (rest length 0)");
    c.rest_length.push_back(l);
  }
  for (auto& p : q) c.nodes.push_back(static_cast<int>(nodes_.add(p, mass_per_node)));
  topo_.chains.push_back(std::move(c));
  groups_[name] = topo_.chains.back().nodes;
  schedule_dirty_ = true;  // chain pointers held by styles may have moved
  return topo_.chains.back();
}

int Simulation::grow_chain(const std::string& name, bool at_front, const Vec3& pos, double mass,
                           double rest) {
  good_state_stale_ = true;  // the guard saves a new one at its next check
  Chain* c = topo_.find(name);
  if (!c) throw InputError("unknown chain '" + name + "'");
  Vec3 q = pos;
  if (dim_ == 2) q.z() = 0.0;
  const int n = static_cast<int>(nodes_.add(q, mass));
  if (at_front)
    c->grow_front(n, rest);
  else
    c->grow_back(n, rest);
  groups_[name] = c->nodes;
  schedule_dirty_ = true;
  return n;
}

RegionStyle& Simulation::add_region(const std::string& id, const std::string& style,
                                    const RawParams& p) {
  if (regions_.count(id)) throw InputError("a region named '" + id + "' already exists");
  auto r = Registry<RegionStyle>::create(style, *this, p);
  r->set_id(id);
  auto& ref = *r;
  regions_[id] = std::move(r);
  return ref;
}

RegionStyle& Simulation::region(const std::string& id) {
  auto it = regions_.find(id);
  if (it == regions_.end()) throw InputError("unknown region '" + id + "'");
  return *it->second;
}

void Simulation::set_group(const std::string& name, std::vector<int> idx) {
  if (name == "all")
    throw InputError("group 'all' is every node and cannot be redefined: choose another name");
  for (int i : idx)
    if (i < 0 || static_cast<size_t>(i) >= nodes_.size())
      throw InputError("group '" + name + "': node index out of range");
  groups_[name] = std::move(idx);
  schedule_dirty_ = true;
}

std::vector<int> Simulation::group(const std::string& name) const {
  if (name == "all") {
    std::vector<int> all(nodes_.n_owned());
    for (size_t i = 0; i < all.size(); ++i) all[i] = static_cast<int>(i);
    return all;
  }
  auto it = groups_.find(name);
  if (it == groups_.end()) throw InputError("unknown group '" + name + "'");
  return it->second;
}
bool Simulation::has_group(const std::string& name) const {
  return name == "all" || groups_.count(name) > 0;
}

namespace {
template <class T>
std::string unique_id(const std::vector<std::unique_ptr<T>>& list, const std::string& base) {
  std::string id = base;
  int n = 1;
  auto taken = [&](const std::string& s) {
    for (auto& x : list)
      if (x->id() == s) return true;
    return false;
  };
  while (taken(id)) id = base + "#" + std::to_string(++n);
  return id;
}
}  // namespace

BondStyle& Simulation::add_bond(const std::string& style, const RawParams& p) {
  auto b = Registry<BondStyle>::create(style, *this, p);
  b->set_id(unique_id(bonds_, style));
  b->attach(*context_);
  bonds_.push_back(std::move(b));
  forces_valid = false;
  schedule_dirty_ = true;
  return *bonds_.back();
}
PairStyle& Simulation::add_pair(const std::string& style, const RawParams& p) {
  auto b = Registry<PairStyle>::create(style, *this, p);
  b->set_id(unique_id(pairs_, style));
  b->attach(*context_);
  pairs_.push_back(std::move(b));
  forces_valid = false;
  schedule_dirty_ = true;
  return *pairs_.back();
}
ShellStyle& Simulation::add_shell(const std::string& style, const RawParams& p) {
  auto b = Registry<ShellStyle>::create(style, *this, p);
  b->set_id(unique_id(shells_, style));
  b->attach(*context_);
  shells_.push_back(std::move(b));
  forces_valid = false;
  schedule_dirty_ = true;
  return *shells_.back();
}
GrowthStyle& Simulation::add_growth(const std::string& id, const std::string& style,
                                    const RawParams& p) {
  if (find_style(id)) throw InputError("the id '" + id + "' is already used");
  auto g = Registry<GrowthStyle>::create(style, *this, p);
  g->set_id(id);
  g->attach(*context_);
  auto& ref = *g;
  growths_[id] = std::move(g);
  forces_valid = false;
  return ref;
}
GrowthStyle& Simulation::growth(const std::string& id) {
  auto it = growths_.find(id);
  if (it == growths_.end()) throw InputError("unknown growth '" + id + "'");
  return *it->second;
}
std::vector<Style*> Simulation::styles() const {
  std::vector<Style*> all;
  for (auto& s : shells_) all.push_back(s.get());
  for (auto& [id, g] : growths_) all.push_back(g.get());
  for (auto& b : bonds_) all.push_back(b.get());
  for (auto& p : pairs_) all.push_back(p.get());
  for (auto& f : fixes_) all.push_back(f.get());
  for (auto& c : computes_) all.push_back(c.get());
  for (auto& d : dumps_) all.push_back(d.get());
  if (integrator_) all.push_back(integrator_.get());
  return all;
}

Style* Simulation::find_style(const std::string& id) {
  for (Style* s : styles())
    if (s->id() == id) return s;
  return nullptr;
}
FixStyle& Simulation::add_fix(const std::string& id, const std::string& style, const RawParams& p) {
  if (find_style(id)) throw InputError("the id '" + id + "' is already used");
  auto f = Registry<FixStyle>::create(style, *this, p);
  f->set_id(id);
  f->attach(*context_);
  fixes_.push_back(std::move(f));
  forces_valid = false;
  schedule_dirty_ = true;
  return *fixes_.back();
}
void Simulation::remove_fix(const std::string& id) {
  for (auto it = fixes_.begin(); it != fixes_.end(); ++it)
    if ((*it)->id() == id) {
      (*it)->detach(*context_);
      fixes_.erase(it);
      forces_valid = false;
      schedule_dirty_ = true;
      return;
    }
  throw InputError("unknown fix '" + id + "'");
}
FixStyle& Simulation::fix(const std::string& id) {
  for (auto& f : fixes_)
    if (f->id() == id) return *f;
  throw InputError("unknown fix '" + id + "'");
}
ComputeStyle& Simulation::add_compute(const std::string& id, const std::string& style,
                                      const RawParams& p) {
  if (find_style(id)) throw InputError("the id '" + id + "' is already used");
  auto c = Registry<ComputeStyle>::create(style, *this, p);
  c->set_id(id);
  c->attach(*context_);
  computes_.push_back(std::move(c));
  return *computes_.back();
}
ComputeStyle& Simulation::compute(const std::string& id) {
  for (auto& c : computes_)
    if (c->id() == id) return *c;
  throw InputError("unknown compute '" + id + "'");
}
DumpStyle& Simulation::add_dump(const std::string& id, const std::string& style,
                                const RawParams& p) {
  if (find_style(id)) throw InputError("the id '" + id + "' is already used");
  auto d = Registry<DumpStyle>::create(style, *this, p);
  d->set_id(id);
  d->attach(*context_);
  dumps_.push_back(std::move(d));
  return *dumps_.back();
}
IntegratorStyle& Simulation::set_integrator(const std::string& style, const RawParams& p) {
  integrator_ = Registry<IntegratorStyle>::create(style, *this, p);
  integrator_->set_id("integrator");
  return *integrator_;
}

// ---------------------------------------------------------------- forces

void Simulation::build_schedule() {
  for (auto& s : shells_) s->setup(*context_);
  for (auto& b : bonds_) b->setup(*context_);
  for (auto& p : pairs_) p->setup(*context_);
  for (auto& f : fixes_)
    if (f->stages() & kSetup) f->setup(*context_);
  dof_mask_ = nodes_.find<int>(kHeldComponents);
  auto raw = [](const auto& v) {
    std::vector<typename std::remove_reference_t<decltype(v)>::value_type::pointer> out;
    for (auto& p : v) out.push_back(p.get());
    return out;
  };
  Schedule::Constraints cons;
  cons.dof_mask = dof_mask_ != nullptr;
  cons.plane = dim_ == 2;
  for (auto& c : coords_)
    if (c->unit) cons.unit_coordinates.push_back(c->name);
  schedule_.build(raw(shells_), raw(bonds_), raw(pairs_), raw(fixes_), std::move(cons));
  schedule_dirty_ = false;
}

const Schedule& Simulation::schedule() {
  if (schedule_dirty_) build_schedule();
  return schedule_;
}

Coordinates& Simulation::coordinates(const std::string& name) {
  for (auto& c : coords_)
    if (c->name == name) return *c;
  auto c = std::make_unique<Coordinates>();
  c->name = name;
  c->q = &nodes_.require<Vec4>(name, Vec4(1, 0, 0, 0));
  c->v = &nodes_.require<Vec4>(name + ".v", Vec4::Zero());
  c->f = &nodes_.require<Vec4>(name + ".f", Vec4::Zero());  // verlet kicks with it
  c->m = &nodes_.require<double>(name + ".m", 1.0);
  c->fixed = &nodes_.require<int>(name + ".fixed", 0);
  coords_.push_back(std::move(c));
  schedule_dirty_ = true;
  if (integrator_) integrator_->coordinates_added(*this);
  return *coords_.back();
}

void Simulation::compute_forces() {
  if (schedule_dirty_) build_schedule();
  neighbors_.begin_evaluation(threads());
  // The passes over every node are light: serial below 2 kMinLightItemsPerThread nodes,
  // where a parallel region costs more than the pass; above, on the threads' node ranges
  // of the kernels and the integrator, so that no core pulls the others' halves of the
  // force array over (threads.hpp).
  const int T = threads();
  const size_t N = nodes_.f.size();
  parallel_ranges(
      T, N,
      [&](int, size_t begin, size_t end) {
        for (size_t i = begin; i < end; ++i) nodes_.f[i].setZero();
        for (auto& c : coords_) {
          auto& f = c->f->values();
          for (size_t i = begin; i < std::min(end, f.size()); ++i) f[i].setZero();
        }
      },
      kMinLightItemsPerThread);
  for (auto& [k, e] : energy_) e = 0.0;
  schedule_.forces(*this, energy_);
  // the constrain stage
  parallel_ranges(
      T, N,
      [&](int, size_t begin, size_t end) {
        if (dof_mask_) {
          auto& m = dof_mask_->values();
          for (size_t i = begin; i < std::min(end, m.size()); ++i)
            if (m[i])
              for (int c = 0; c < 3; ++c)
                if (m[i] & (1 << c)) nodes_.f[i][c] = 0.0;
        }
        if (dim_ == 2)
          for (size_t i = begin; i < end; ++i) nodes_.f[i].z() = 0.0;
        for (auto& c : coords_) {
          auto& f = c->f->values();
          auto& q = c->q->values();
          auto& fixed = c->fixed->values();
          for (size_t i = begin; i < std::min(end, f.size()); ++i) {
            if (fixed[i]) {
              f[i].setZero();
            } else if (c->unit) {
              f[i] -= (f[i].dot(q[i]) / q[i].squaredNorm()) * q[i];  // tangent to |q| = 1
            }
          }
        }
      },
      kMinLightItemsPerThread);
  forces_valid = true;
}

void Simulation::end_of_step() {
  schedule_.end_of_step(*this);
}

double Simulation::kinetic_energy() const {
  double ke = 0.0;
  for (size_t i = 0; i < nodes_.n_owned(); ++i)
    ke += 0.5 * nodes_.mass[i] * nodes_.v[i].squaredNorm();
  return ke + rotational_kinetic_energy();
}
double Simulation::rotational_kinetic_energy() const {
  // 2 I_r |dq/dt|^2 = 1/2 m_q |dq/dt|^2 with m_q = 4 I_r (docs/models.md §4.4)
  double ke = 0.0;
  for (auto& c : coords_)
    for (size_t i = 0; i < nodes_.n_owned(); ++i) ke += 0.5 * (*c->m)[i] * (*c->v)[i].squaredNorm();
  return ke;
}
double Simulation::potential_energy() const {
  double pe = 0.0;
  for (auto& [k, e] : energy_) pe += e;
  return pe;
}
double Simulation::max_force() const {
  double m = 0.0;
  for (size_t i = 0; i < nodes_.n_owned(); ++i) m = std::max(m, nodes_.f[i].norm());
  // rod frames: the generalised force on each free quaternion, tangent to |q| = 1 (its
  // radial part does no work); FIRE has not converged while the frames still turn
  for (auto& c : coords_)
    for (size_t i = 0; i < nodes_.n_owned(); ++i) {
      if ((*c->fixed)[i]) continue;
      const Vec4& q = (*c->q)[i];
      const Vec4& f = (*c->f)[i];
      m = std::max(m, (c->unit ? Vec4(f - f.dot(q) * q) : f).norm());
    }
  return m;
}

double Simulation::omega_max(std::string* who) const {
  // Independent stiff terms add in omega^2 (Gershgorin-style upper bound).
  double w2 = 0.0, best = 0.0;
  for (Style* s : styles()) {
    const double w = s->max_frequency(*context_);
    w2 += w * w;
    if (w > best) {
      best = w;
      if (who) *who = std::string(s->family_name()) + " " + s->id();
    }
  }
  return std::sqrt(w2);
}
void Simulation::cache_frequencies() {
  omega2_fixed_ = 0.0;
  measuring_.clear();
  for (Style* s : styles()) {
    if (s->measures_frequency())
      measuring_.push_back({s, s->max_frequency(*context_)});
    else
      omega2_fixed_ += std::pow(s->max_frequency(*context_), 2);
  }
}

double Simulation::omega_now(std::string* who) const {
  double w2 = omega2_fixed_, best = 0.0;
  const bool alone = integrator_ && integrator_->trusts_measured();
  for (const auto& m : measuring_) {
    const double measured = m.style->measured_frequency();
    // a style that measures nothing (negative) keeps its nominal frequency
    const double w = alone && measured >= 0.0 ? measured : std::max(m.nominal, measured);
    w2 += w * w;
    if (who && measured > m.nominal && w > best) {
      best = w;
      *who = m.style->id() + " (measured)";
    }
  }
  return std::sqrt(w2);
}

double Simulation::stability_limit() const {
  return integrator_ ? integrator_->stability_limit() : 2.0;
}
double Simulation::suggest_dt(double safety) const {
  double w = omega_max();
  if (!(w > 0)) return 0.0;
  return safety * stability_limit() / w;
}

const std::vector<std::string>& Simulation::builtin_columns() {
  static const std::vector<std::string> names{"step",      "time",      "dt",       "nodes",
                                              "ke",        "pe",        "etotal",   "fmax",
                                              "omega_max", "omega_now", "dt_stable"};
  return names;
}

double Simulation::column(const std::string& name) {
  if (name == "step") return static_cast<double>(step);
  if (name == "time") return time;
  if (name == "dt") return dt;
  if (name == "nodes") return static_cast<double>(nodes_.n_owned());
  if (name == "ke") return kinetic_energy();
  if (name == "pe") return potential_energy();
  if (name == "etotal") return kinetic_energy() + potential_energy();
  if (name == "fmax") return max_force();
  if (name == "omega_max") return omega_max();
  if (name == "omega_now") return omega_now();
  if (name == "dt_stable") {
    const double w = omega_now();
    return w > 0 ? stability_limit() / w : 0.0;
  }
  auto dot = name.find('.');
  if (dot == std::string::npos)
    throw InputError(
        "unknown thermo column '" + name +
        "' (built in: step, time, dt, nodes, ke, pe, etotal, fmax, omega_max, omega_now, "
        "dt_stable; or <id>.<key>)");
  std::string id = name.substr(0, dot), key = name.substr(dot + 1);
  if (id == "energy" && !find_style("energy")) {
    // energies by category are always available
    if (key == "kinetic") return kinetic_energy();
    if (key == "potential") return potential_energy();
    if (key == "total") return kinetic_energy() + potential_energy();
    auto it = energy_.find(key);
    if (it != energy_.end()) return it->second;
    // a category of the built-in styles that this scene lacks is 0 (one deck's columns serve
    // scenes with and without torsion); any other name is a typo, not a zero energy. Once
    // the forces have been evaluated every category of the scene (plugins' too) is listed.
    static const char* const built_in[] = {"stretch", "bend",    "twist",   "coupling",
                                           "damping", "contact", "external"};
    for (const char* c : built_in)
      if (key == c) return 0.0;
    if (!forces_valid) return 0.0;
    std::string known = "kinetic, potential, total";
    for (const char* c : built_in) known += std::string(", ") + c;
    for (const auto& [k, e] : energy_)
      if (std::find(std::begin(built_in), std::end(built_in), k) == std::end(built_in))
        known += ", " + k;
    throw InputError("thermo column '" + name + "': no energy '" + key + "' in this scene (" +
                     known + ")");
  }
  Style* s = find_style(id);
  if (!s)
    throw InputError("thermo column '" + name + "': no fix, compute or style with id '" + id + "'");
  if (auto* c = dynamic_cast<ComputeStyle*>(s)) c->evaluate(*this);
  return s->value(key);
}

void Simulation::resolve_dt() {
  if (!integrator_) throw InputError("no integrator: call sim:integrator(...) before run");
  double req = integrator_->requested_dt();
  if (req > 0) {
    dt = req;
    return;
  }
  double s = suggest_dt(integrator_->safety());
  if (!(s > 0))
    throw InputError("dt = \"auto\" needs at least one bond, pair or fix that reports a stiffness");
  dt = s;
}

void Simulation::setup_run() {
  if (nodes_.size() == 0) throw InputError("the scene has no nodes");
  build_schedule();  // styles bind first: some measure their stiffness in setup()
  resolve_dt();
  cache_frequencies();
  if (!forces_valid) compute_forces();
  integrator_->setup(*this);
  if (verbose) {
    std::string who;
    double w = omega_max(&who);
    std::printf("run: integrator %s, dt %.6g", integrator_->style_name().c_str(), dt);
    if (w > 0) std::printf(" (stable estimate %.4g, stiffest: %s)", suggest_dt(1.0), who.c_str());
    // every term's nominal highest frequency: which one limits the step
    std::printf("\n  omega by term:");
    for (Style* st : styles()) {
      const double w = st->max_frequency(*context_);
      if (w > 0) std::printf(" %s %s %.4g;", st->family_name(), st->id().c_str(), w);
    }
    std::printf("\n  schedule [priority]:\n");
    std::string lines = schedule_.describe();
    for (size_t a = 0, b; a < lines.size(); a = b + 1) {
      b = lines.find('\n', a);
      std::printf("    %s\n", lines.substr(a, b - a).c_str());
    }
    std::printf("  node properties:");
    for (auto& n : nodes_.property_names()) std::printf(" %s", n.c_str());
    std::printf("\n");
  }
  save_good_state();
  good_step_ = step;
  good_time_ = time;
  energy_scale_ = std::max(energy_scale_, kinetic_energy() + std::abs(potential_energy()));
}

void Simulation::write_thermo(bool header) {
  std::vector<double> vals;
  vals.reserve(thermo.columns.size());
  for (auto& c : thermo.columns) vals.push_back(column(c));
  thermo_writer_.write(thermo, vals, header, verbose);
}

void Simulation::after_step(long k, bool last, double t0) {
  const bool thermo_now = thermo_cadence().due(step, t0, time);
  thermo_written_ = thermo_now;
  // the state a run stopped in (jammed, a threshold) is its result: every dump
  // (trajectory, checkpoint) gets it, on or off its period
  const bool stopping = !stop_reason_.empty();
  auto due = [&](const DumpStyle& d) {
    return d.cadence().active() && (stopping || d.cadence().due(step, t0, time));
  };
  bool dump_now = false;
  for (auto& d : dumps_) dump_now = dump_now || due(*d);
  using clock = std::chrono::steady_clock;
  // Outputs only ever see a state the guard has passed: no NaN in files.
  if ((guard.every > 0 && k % guard.every == 0) || thermo_now || dump_now || last) {
    const auto g0 = clock::now();
    check_guard(k);
    run_seconds_.guard += std::chrono::duration<double>(clock::now() - g0).count();
  }
  if (!thermo_now && !dump_now) return;
  const auto o0 = clock::now();
  if (thermo_now) write_thermo(false);
  if (dump_now)
    for (auto& d : dumps_)
      if (due(*d)) d->write(*this);
  run_seconds_.output += std::chrono::duration<double>(clock::now() - o0).count();
}

void Simulation::print_run_summary(long steps, double seconds) const {
  if (!verbose || steps <= 0 || !(seconds > 0)) return;
  const double n = static_cast<double>(nodes_.n_owned());
  std::printf(
      "run summary: %ld steps in %.4g s: %.4g steps/s, %.4g node-steps/s (%zu nodes at the end)\n",
      steps, seconds, steps / seconds, steps * n / seconds, nodes_.n_owned());
  // time by stage, largest first; what is left is the integrator, the core's constraints,
  // the adaptive step's estimate and the loop itself
  std::vector<std::pair<std::string, double>> parts = schedule_.timings();
  double styles = 0.0;
  for (auto& [name, t] : parts) styles += t;
  parts.emplace_back("outputs (thermo, dumps)", run_seconds_.output);
  parts.emplace_back("guard", run_seconds_.guard);
  parts.emplace_back("integrator and the rest",
                     std::max(0.0, seconds - styles - run_seconds_.output - run_seconds_.guard));
  std::stable_sort(parts.begin(), parts.end(),
                   [](const auto& a, const auto& b) { return a.second > b.second; });
  std::printf("  time by stage:");
  for (auto& [name, t] : parts)
    if (t >= 0.0005 * seconds) std::printf(" %s %.1f%%;", name.c_str(), 100.0 * t / seconds);
  std::printf("\n");
}

void Simulation::run(const RunOptions& opt) {
  if (opt.steps < 0) throw InputError("run: steps must be >= 0");
  stop_reason_.clear();
  last_stop_.clear();
  setup_run();
  for (auto& d : dumps_)
    if (d->cadence().due_at(step, time)) d->write(*this);
  if (thermo_cadence().active()) write_thermo(true);
  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  auto last_progress = t0;
  const long first = step;
  schedule_.reset_timings();
  run_seconds_ = {};
  // the first style that knows how far the run is toward its own stop (e.g. a target
  // packing density) gives a second ETA besides the step count's
  const Style* goal = nullptr;
  double goal_start = 0.0;
  for (const Style* st : styles())
    if (st->stop_progress(nullptr) >= 0.0) {
      goal = st;
      goal_start = st->stop_progress(nullptr);
      break;
    }
  const bool adaptive = integrator_->adaptive();
  double dt_cap = dt;
  // Trusting the measured contacts, "auto" is capped by the terms that measure nothing,
  // and no node may move more than safety times a tenth of the shortest rest length per
  // step: a contact that begins within a step (a node arriving at speed) then cannot
  // overlap much deeper than the nominal estimate assumes (a tenth of a diameter, with
  // diameters about a rest length), where its stiffness was never measured.
  const bool trust = adaptive && integrator_->trusts_measured();
  const double approach = trust ? integrator_->safety() * 0.1 * topo_.min_rest_length() : 0.0;
  if (trust && integrator_->requested_dt() <= 0) {
    double w2 = omega2_fixed_;
    for (const auto& m : measuring_)
      if (m.style->measured_frequency() < 0.0) w2 += m.nominal * m.nominal;
    if (w2 > 0) dt_cap = integrator_->safety() * stability_limit() / std::sqrt(w2);
  }
  for (long k = 1; k <= opt.steps; ++k) {
    // an adaptive step follows the measured stiffness of the contacts (never above the
    // requested or nominal "auto" step): dense packings load a node with several deep
    // contacts, which the nominal estimate does not know
    if (adaptive) dt = std::min(dt_cap, integrator_->safety() * stability_limit() / omega_now());
    if (trust && approach < 1e299) {
      double v2 = 0.0;
      for (std::size_t i = 0, n = nodes_.n_owned(); i < n; ++i)
        v2 = std::max(v2, nodes_.v[i].squaredNorm());
      if (v2 > 0.0) dt = std::min(dt, approach / std::sqrt(v2));
    }
    const double t_start = time;
    integrator_->step(*this);
    ++step;
    time += dt;
    if (interrupted() && stop_reason_.empty()) stop_reason_ = "interrupted by a signal";
    after_step(k, k == opt.steps || !stop_reason_.empty(), t_start);
    if (!stop_reason_.empty()) {
      if (verbose) std::printf("run stopped at step %ld: %s\n", step, stop_reason_.c_str());
      if (thermo_cadence().active() && !thermo_written_) write_thermo(false);
      break;
    }
    if (opt.callback && opt.every > 0 && k % opt.every == 0) {
      if (opt.callback(*this)) break;
    }
    if (verbose && (k & 255) == 0) {
      auto now = clock::now();
      double since = std::chrono::duration<double>(now - last_progress).count();
      if (since >= thermo.progress_seconds) {
        double el = std::chrono::duration<double>(now - t0).count();
        double rate = (step - first) / el;
        double eta = (opt.steps - k) / rate;
        std::string to = "the step count";
        if (goal) {
          std::string what;
          const double p = goal->stop_progress(&what);
          if (p > goal_start) {
            const double eta_goal = el * (1.0 - p) / (p - goal_start);
            if (eta_goal < eta) {
              eta = eta_goal;
              to = what;
            }
          }
        }
        std::printf(
            "  progress: step %ld of %ld (%.0f%%), %.3g steps/s, %.3g node-steps/s, ETA %.0f s "
            "(to %s)\n",
            k, opt.steps, 100.0 * k / opt.steps, rate, rate * nodes_.n_owned(), eta, to.c_str());
        std::fflush(stdout);
        last_progress = now;
      }
    }
  }
  last_stop_ = stop_reason_;
  stop_reason_.clear();
  for (auto& d : dumps_) d->flush();
  print_run_summary(step - first, std::chrono::duration<double>(clock::now() - t0).count());
  if (interrupted()) finish_interrupted();
}

void Simulation::finish_interrupted() {
  // The last step is complete and the guard has passed it (after_step ran with last =
  // true): a last frame of every dump that did not just write one, then the checkpoint.
  std::string where;
  bool checkpointed = false;
  for (auto& d : dumps_) {
    if (!d->cadence().due_at(step, time)) d->write(*this);
    d->flush();
    if (d->style_name() == "checkpoint") checkpointed = true;
  }
  if (checkpointed) {
    where = "the checkpoint dump's file";
  } else {
#ifdef SLENDER_HAVE_HDF5
    write_checkpoint(interrupt_file);
    where = interrupt_file;
#else
    where = "nowhere (built without HDF5: no checkpoints)";
#endif
  }
  const int sig = static_cast<int>(*interrupt_);
  throw InterruptedError(std::string("interrupted by ") +
                         (sig == SIGINT    ? "SIGINT"
                          : sig == SIGTERM ? "SIGTERM"
                                           : "a signal") +
                         " at step " + std::to_string(step) + " (time " + std::to_string(time) +
                         "); outputs flushed, last state written to " + where +
                         " (continue with sim:read_checkpoint)");
}

#ifndef SLENDER_HAVE_HDF5
void Simulation::write_checkpoint(const std::string& path) {
  throw InputError("cannot write checkpoint '" + path +
                   "': this slender was built with -DSLENDER_WITH_HDF5=OFF");
}
void Simulation::read_checkpoint(const std::string& path) {
  throw InputError("cannot read checkpoint '" + path +
                   "': this slender was built with -DSLENDER_WITH_HDF5=OFF");
}
#endif

}  // namespace slender
