// Checkpoints (restart files) in HDF5, written atomically: temp file + rename.
#include <cstdio>
#include <sstream>

#include "h5util.hpp"
#include "simulation.hpp"

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
void load_style(hid_t parent, Style& s) {
  if (!h5::exists(parent, group_name(s))) return;
  auto g = h5::open_group(parent, group_name(s));
  StateMap st;
  for (auto& k : h5::children(g)) st[k] = h5::read_doubles(g, k);
  s.load_state(st);
}
}  // namespace

void Simulation::write_checkpoint(const std::string& path) {
  const std::string tmp = path + ".tmp";
  {
    auto f = h5::create_file(tmp);
    h5::attr_string(f, "creator", "slender checkpoint v1");
    auto st = h5::create_group(f, "state");
    std::ostringstream rng;
    rng << rng_;
    h5::write_string(st, "rng", rng.str());
    h5::write_doubles(st, "scalars",
                      {static_cast<double>(step), time, dt, forces_valid ? 1.0 : 0.0,
                       static_cast<double>(dim_), energy_scale_, static_cast<double>(state_epoch)},
                      {7});
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
    H5Fflush(f, H5F_SCOPE_GLOBAL);
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0)
    throw InputError("cannot move checkpoint " + tmp + " to " + path);
}

void Simulation::read_checkpoint(const std::string& path) {
  h5::Handle f;
  try {
    f = h5::open_file(path, false);
  } catch (const std::exception&) {
    throw InputError("cannot open checkpoint '" + path + "'");
  }
  auto st = h5::open_group(f, "state");
  auto sc = h5::read_doubles(st, "scalars");
  if (static_cast<int>(sc[4]) != dim_)
    throw InputError("checkpoint '" + path + "' is " + std::to_string(int(sc[4])) +
                     "D, the scene is " + std::to_string(dim_) + "D");
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
  // styles create some node properties when they first bind (e.g. the shell's
  // dof_mask for its ghosts): bind them now, so a fresh scene that has not run yet
  // holds the same properties as the run that wrote the checkpoint
  if (nodes_.size() > 0) build_schedule();
  auto nodes = h5::open_group(f, "nodes");
  std::vector<hsize_t> dims;
  auto pos = h5::read_doubles(nodes, "position", &dims);
  nodes_.resize(dims[0]);
  unflat3(pos, nodes_.x);
  unflat3(h5::read_doubles(nodes, "velocity"), nodes_.v);
  unflat3(h5::read_doubles(nodes, "force"), nodes_.f);
  nodes_.mass = h5::read_doubles(nodes, "mass");
  auto props = h5::open_group(f, "properties");
  auto names = h5::children(props);
  for (auto& name : names) {
    PropertyBase* p = nodes_.find_any(name);
    if (!p)
      throw InputError(
          "checkpoint '" + path + "' has node property '" + name +
          "' that this scene does not use: the deck differs from the one that wrote it");
    p->from_flat(h5::read_doubles(props, name));
  }
  for (auto& [name, p] : nodes_.properties())
    if (p->options().restart && !h5::exists(props, name))
      throw InputError("checkpoint '" + path + "' lacks node property '" + name +
                       "' that this scene uses: the deck differs from the one that wrote it");
  auto chains = h5::open_group(f, "chains");
  for (auto& c : topo_.chains) {
    if (!h5::exists(chains, c.name))
      throw InputError("checkpoint '" + path + "' has no chain '" + c.name + "'");
    auto g = h5::open_group(chains, c.name);
    auto idx = h5::read_doubles(g, "nodes");
    c.nodes.assign(idx.begin(), idx.end());
    c.rest_length = h5::read_doubles(g, "rest_length");
  }
  auto styles = h5::open_group(f, "styles");
  for (Style* s : this->styles()) load_style(styles, *s);
  std::istringstream rng(h5::read_string(st, "rng"));
  rng >> rng_;
  step = static_cast<long>(sc[0]);
  time = sc[1];
  dt = sc[2];
  forces_valid = sc[3] != 0.0;
  energy_scale_ = sc[5];
  state_epoch = static_cast<long>(sc[6]);
  energy_.clear();
  auto en = h5::open_group(st, "energy");
  for (auto& k : h5::children(en)) energy_[k] = h5::read_doubles(en, k)[0];
  for (auto& c : topo_.chains) groups_[c.name] = c.nodes;
}

}  // namespace slender
