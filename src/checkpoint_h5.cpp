// Checkpoints (restart files) in HDF5, written atomically: temp file + rename.
#include <fcntl.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <sstream>
#include <tuple>
#include <typeinfo>

#include "context.hpp"
#include "h5util.hpp"
#include "simulation.hpp"
#include "statics.hpp"

namespace slender {

namespace {
std::vector<double> flat3(const std::vector<Vec3>& v) {
  std::vector<double> out;
  out.reserve(v.size() * 3);
  for (auto& x : v) out.insert(out.end(), {x[0], x[1], x[2]});
  return out;
}
void unflat3(const std::vector<double>& d, std::vector<Vec3>& v) {
  v.resize(d.size() / 3);
  for (size_t i = 0; i < v.size(); ++i) v[i] = Vec3(d[3 * i], d[3 * i + 1], d[3 * i + 2]);
}
// Style ids such as "contact/node-edge" hold '/', which HDF5 reads as a path.
std::string group_name(const Style& s) {
  std::string n = s.id();
  for (char& c : n)
    if (c == '/') c = '|';
  return n;
}
void save_style(hid_t parent, const Style& s) {
  StateMap st;
  s.save_state(st);
  if (st.empty()) return;
  auto g = h5::create_group(parent, group_name(s));
  for (auto& [k, v] : st) h5::write_doubles(g, k, v, {v.size()});
}
// fsync of a file or a folder; a file system that cannot sync a folder is not an error.
void sync_path(const std::string& path, bool folder) {
  const int fd = ::open(path.c_str(), folder ? (O_RDONLY | O_DIRECTORY) : O_RDONLY);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

// The keys whose values differ between the parameters a checkpoint recorded for a style
// and the deck's ("key = value" lines): "radius 10 in the checkpoint, 12 here".
std::vector<std::string> changed_parameters(const std::string& saved, const std::string& now,
                                            const std::set<std::string>& deliberate) {
  auto parse = [](const std::string& text) {
    std::map<std::string, std::string> m;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) {
      const auto eq = line.find(" = ");
      if (eq != std::string::npos) m[line.substr(0, eq)] = line.substr(eq + 3);
    }
    return m;
  };
  const auto a = parse(saved), b = parse(now);
  std::vector<std::string> out;
  for (auto& [key, value] : b) {
    auto it = a.find(key);
    if (it != a.end() && it->second != value && !deliberate.count(key))
      out.push_back(key + " " + it->second + " in the checkpoint, " + value + " here");
  }
  return out;
}

void load_style(hid_t parent, Style& s, const std::string& path) {
  if (!h5::exists(parent, group_name(s))) return;
  auto g = h5::open_group(parent, group_name(s));
  const std::string who = "checkpoint '" + path + "': the state of " + s.family_name() + " '" +
                          s.id() + "' (" + s.style_name() + ")";
  StateMap st;
  for (auto& k : h5::children(g)) {
    st[k] = h5::read_doubles(g, k);
    for (double v : st[k])
      if (!std::isfinite(v)) throw InputError(who + ": array '" + k + "' holds NaN or inf");
  }
  try {
    s.load_state(st);
  } catch (const InputError& e) {
    throw InputError(who + ": " + e.what());
  }
}
}  // namespace

void Simulation::write_checkpoint(const std::string& path) {
  const std::string tmp = path + ".tmp";
  {
    // the file is written beside its final name and renamed when complete; a failure names
    // the file the deck asked for, not the temporary one
    h5::Handle f;
    try {
      f = h5::create_file(tmp);
    } catch (const std::runtime_error& e) {
      std::string why = e.what();
      for (auto at = why.find(tmp); at != std::string::npos; at = why.find(tmp, at + path.size()))
        why.replace(at, tmp.size(), path);
      throw std::runtime_error(why);
    }
    h5::attr_string(f, "creator", "slender checkpoint v1");
    auto st = h5::create_group(f, "state");
    std::ostringstream rng;
    rng << rng_;
    h5::write_string(st, "rng", rng.str());
    h5::write_doubles(st, "scalars",
                      {static_cast<double>(step), time, dt, forces_valid ? 1.0 : 0.0,
                       static_cast<double>(dim_), energy_scale_, static_cast<double>(state_epoch),
                       static_system_ ? static_system_->last_shift() : 0.0},
                      {8});
    auto en = h5::create_group(st, "energy");
    for (auto& [k, e] : energy_) h5::write_doubles(en, k, {e}, {1});
    auto nodes = h5::create_group(f, "nodes");
    const hsize_t n = nodes_.size();
    h5::write_doubles(nodes, "position", flat3(nodes_.x), {n, 3});
    h5::write_doubles(nodes, "velocity", flat3(nodes_.v), {n, 3});
    h5::write_doubles(nodes, "force", flat3(nodes_.f), {n, 3});
    h5::write_doubles(nodes, "mass", nodes_.mass, {n});
    auto props = h5::create_group(f, "properties");
    for (auto& [name, p] : nodes_.properties()) {
      if (!p->options().restart) continue;
      h5::write_doubles(props, name, p->to_flat(), {n, static_cast<hsize_t>(p->ncomp())});
    }
    auto chains = h5::create_group(f, "chains");
    for (auto& c : topo_.chains) {
      auto g = h5::create_group(chains, c.name);
      h5::write_doubles(g, "nodes", std::vector<double>(c.nodes.begin(), c.nodes.end()),
                        {c.nodes.size()});
      h5::write_doubles(g, "rest_length", c.rest_length, {c.rest_length.size()});
      h5::write_doubles(g, "closed", {c.closed ? 1.0 : 0.0}, {1});
    }
    auto styles = h5::create_group(f, "styles");
    for (Style* s : this->styles()) save_style(styles, *s);
    // the deck's parameters of every style, so that a restart under other values is noticed
    auto params = h5::create_group(f, "parameters");
    for (Style* s : this->styles())
      if (!s->parameters().empty()) h5::attr_string(params, group_name(*s), s->parameters());
    H5Fflush(f, H5F_SCOPE_GLOBAL);
  }
  // durable before it replaces the old one: the data on disk, then the rename in its folder
  // (a power loss leaves the old checkpoint or the new one, never a torn file)
  sync_path(tmp, false);
  if (std::rename(tmp.c_str(), path.c_str()) != 0)
    throw InputError("cannot move checkpoint " + tmp + " to " + path);
  const auto slash = path.find_last_of('/');
  sync_path(slash == std::string::npos ? "." : path.substr(0, slash + 1), true);
}

void Simulation::read_checkpoint(const std::string& path) {
  // Every failure names the file and what is wrong with it, in one line: a foreign or
  // damaged file must not crash the run or leave it with arrays it cannot index.
  try {
    read_checkpoint_checked(path);
  } catch (const InputError& e) {
    const std::string m = e.what();
    if (m.find(path) == std::string::npos) throw InputError("checkpoint '" + path + "': " + m);
    throw;
  } catch (const std::out_of_range&) {
    throw InputError("checkpoint '" + path +
                     "': a style's saved state lacks a dataset (written by another deck, or "
                     "damaged)");
  } catch (const std::exception& e) {
    throw InputError("checkpoint '" + path + "': " + e.what() +
                     " (not a slender checkpoint, or damaged)");
  }
}

namespace {
std::string num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.10g", v);
  return b;
}
}  // namespace

void Simulation::read_checkpoint_checked(const std::string& path) {
  auto bad = [&](const std::string& what) {
    return InputError("checkpoint '" + path + "': " + what);
  };
  auto all_finite = [](const std::vector<double>& v) {
    for (double x : v)
      if (!std::isfinite(x)) return false;
    return true;
  };
  h5::Handle f;
  try {
    f = h5::open_file(path, false);
  } catch (const std::exception& e) {
    throw InputError(e.what());
  }
  auto st = h5::open_group(f, "state");
  auto sc = h5::read_doubles(st, "scalars");
  if (sc.size() < 7 || !all_finite(sc))
    throw bad("dataset state/scalars must hold 7 finite numbers (step, time, dt, ...)");
  // the 8th (since 2026-12-07): the Levenberg shift a minimiser's preconditioner settled on
  const double statics_shift = sc.size() > 7 ? sc[7] : 0.0;
  if (statics_shift < 0) throw bad("dataset state/scalars holds a negative Levenberg shift");
  if (sc[0] < 0 || sc[0] != std::floor(sc[0]) || sc[0] > 9.007199254740992e15 || sc[2] < 0 ||
      sc[6] != std::floor(sc[6]) || std::abs(sc[6]) > 9.007199254740992e15)
    throw bad("dataset state/scalars holds an impossible step " + num(sc[0]) + " or time step " +
              num(sc[2]));
  if (sc[4] != static_cast<double>(dim_))
    throw InputError("checkpoint '" + path + "' is " + num(sc[4]) + "D, the scene is " +
                     std::to_string(dim_) + "D");
  // the chains must match both ways (checked before anything is read into the scene): a
  // chain of the file that the scene lacks would leave its nodes in the arrays without a
  // chain, orphans that no bond holds
  {
    auto file_chains = h5::open_group(f, "chains");
    for (auto& name : h5::children(file_chains))
      if (!topo_.find(name))
        throw InputError("checkpoint '" + path + "' has chain '" + name +
                         "' that this scene does not define: the deck differs from the one "
                         "that wrote it");
    for (auto& c : topo_.chains)
      if (!h5::exists(file_chains, c.name))
        throw InputError("checkpoint '" + path + "' has no chain '" + c.name + "'");
  }
  // the node arrays: shapes, finite values, positive masses (read before the scene changes)
  auto nodes = h5::open_group(f, "nodes");
  std::vector<hsize_t> dims;
  auto pos = h5::read_doubles(nodes, "position", &dims);
  if (dims.size() != 2 || dims[1] != 3) throw bad("dataset nodes/position is not n x 3");
  const std::size_t n = dims[0];
  auto vel = h5::read_doubles(nodes, "velocity");
  auto force = h5::read_doubles(nodes, "force");
  auto mass = h5::read_doubles(nodes, "mass");
  for (auto& [name, v, size] :
       {std::tuple<const char*, const std::vector<double>*, std::size_t>{"position", &pos, 3 * n},
        {"velocity", &vel, 3 * n},
        {"force", &force, 3 * n},
        {"mass", &mass, n}}) {
    if (v->size() != size)
      throw bad("dataset nodes/" + std::string(name) + " has " + std::to_string(v->size()) +
                " values, " + std::to_string(size) + " expected for " + std::to_string(n) +
                " nodes");
    if (!all_finite(*v)) throw bad("dataset nodes/" + std::string(name) + " holds NaN or inf");
  }
  for (std::size_t i = 0; i < n; ++i)
    if (!(mass[i] > 0))
      throw bad("dataset nodes/mass: node " + std::to_string(i + 1) + " has mass " + num(mass[i]));
  // chains: node indices within the arrays, each node in one chain, one rest length per edge
  auto chains = h5::open_group(f, "chains");
  std::vector<std::pair<std::vector<int>, std::vector<double>>> chain_data;
  {
    std::vector<char> seen(n, 0);
    for (auto& c : topo_.chains) {
      auto g = h5::open_group(chains, c.name);
      auto idx = h5::read_doubles(g, "nodes");
      auto rest = h5::read_doubles(g, "rest_length");
      const std::string where = "chain '" + c.name + "': ";
      std::vector<int> ids;
      for (double d : idx) {
        if (!(d >= 0 && d < static_cast<double>(n) && d == std::floor(d)))
          throw bad(where + "node index " + num(d) + " is not one of the " + std::to_string(n) +
                    " nodes");
        const int i = static_cast<int>(d);
        if (seen[static_cast<std::size_t>(i)]++)
          throw bad(where + "node " + std::to_string(i + 1) + " belongs to two chains");
        ids.push_back(i);
      }
      const std::size_t edges = ids.size() < 2 ? 0 : (c.closed ? ids.size() : ids.size() - 1);
      if (ids.size() < 2 || rest.size() != edges)
        throw bad(where + std::to_string(ids.size()) + " nodes and " + std::to_string(rest.size()) +
                  " rest lengths (one per edge expected)");
      for (double r : rest)
        if (!(std::isfinite(r) && r > 0)) throw bad(where + "a rest length is not positive");
      chain_data.emplace_back(std::move(ids), std::move(rest));
    }
  }
  // styles create some node properties when they first bind (e.g. the shell's
  // dof_mask for its ghosts): bind them now, so a fresh scene that has not run yet
  // holds the same properties as the run that wrote the checkpoint
  if (nodes_.size() > 0) build_schedule();
  auto props = h5::open_group(f, "properties");
  auto names = h5::children(props);
  std::vector<std::pair<PropertyBase*, std::vector<double>>> prop_data;
  for (auto& name : names) {
    PropertyBase* p = nodes_.find_any(name);
    if (!p)
      throw InputError(
          "checkpoint '" + path + "' has node property '" + name +
          "' that this scene does not use: the deck differs from the one that wrote it");
    auto v = h5::read_doubles(props, name);
    if (v.size() != n * static_cast<std::size_t>(p->ncomp()))
      throw bad("node property '" + name + "' has " + std::to_string(v.size()) + " values, " +
                std::to_string(n * static_cast<std::size_t>(p->ncomp())) + " expected");
    if (!all_finite(v)) throw bad("node property '" + name + "' holds NaN or inf");
    if (p->type() == typeid(int))  // flags and counters: a double past int would be UB to cast
      for (double x : v)
        if (x != std::trunc(x) || x < -2147483648.0 || x > 2147483647.0)
          throw bad("node property '" + name + "' holds " + std::to_string(x) +
                    " where integers are stored");
    prop_data.emplace_back(p, std::move(v));
  }
  for (auto& [name, p] : nodes_.properties())
    if (p->options().restart && !h5::exists(props, name))
      throw InputError("checkpoint '" + path + "' lacks node property '" + name +
                       "' that this scene uses: the deck differs from the one that wrote it");
  std::map<std::string, double> energy;
  auto en = h5::open_group(st, "energy");
  for (auto& k : h5::children(en)) {
    auto v = h5::read_doubles(en, k);
    if (v.size() != 1 || !std::isfinite(v[0]))
      throw bad("dataset state/energy/" + k + " must hold one finite number");
    energy[k] = v[0];
  }
  std::mt19937_64 rng_read;
  {
    std::istringstream rng(h5::read_string(st, "rng"));
    if (!(rng >> rng_read)) throw bad("dataset state/rng is not a random-stream state");
  }
  // a deck that differs from the one that wrote the file (another cavity radius, friction):
  // legitimate for some keys (a jamming threshold, the time step), so said, not refused;
  // keys that sim:modify changed in this run are deliberate and not said
  if (h5::exists(f, "parameters")) {
    auto pg = h5::open_group(f, "parameters");
    for (Style* s : this->styles()) {
      if (s->parameters().empty() || H5Aexists(pg, group_name(*s).c_str()) <= 0) continue;
      for (auto& change : changed_parameters(h5::read_attr_string(pg, group_name(*s)),
                                             s->parameters(), modified_keys_[s->id()]))
        std::fprintf(stderr,
                     "slender: warning: checkpoint '%s' was written with other parameters: %s "
                     "'%s' (%s): %s\n",
                     path.c_str(), s->family_name(), s->id().c_str(), s->style_name().c_str(),
                     change.c_str());
    }
  }

  // everything the core reads is checked: into the scene
  nodes_.resize(n);
  unflat3(pos, nodes_.x);
  unflat3(vel, nodes_.v);
  unflat3(force, nodes_.f);
  nodes_.mass = mass;
  for (auto& [p, v] : prop_data) p->from_flat(v);
  {
    std::size_t k = 0;
    for (auto& c : topo_.chains) {
      c.nodes = std::move(chain_data[k].first);
      c.rest_length = std::move(chain_data[k].second);
      ++k;
    }
  }
  auto styles = h5::open_group(f, "styles");
  for (Style* s : this->styles()) load_style(styles, *s, path);
  // the styles' own state refers to nodes and edges: each checks its indices
  for (Style* s : this->styles()) {
    const std::string problem = s->check_loaded(*context_);
    if (!problem.empty())
      throw bad("the saved state of '" + s->id() + "' (" + s->style_name() + "): " + problem);
  }
  rng_ = rng_read;
  step = static_cast<long>(sc[0]);
  time = sc[1];
  dt = sc[2];
  forces_valid = sc[3] != 0.0;
  energy_scale_ = sc[5];
  state_epoch = static_cast<long>(sc[6]);
  // a minimisation after the restart starts its shift ladder where the saved run would have
  if (statics_shift > 0 || static_system_) static_system().set_last_shift(statics_shift);
  energy_ = std::move(energy);
  for (auto& c : topo_.chains) groups_[c.name] = c.nodes;
}

}  // namespace slender
