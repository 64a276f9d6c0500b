// Simulation: the inventory of a scene (what it allocated, built and ran), as JSON.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "registry.hpp"
#include "simulation.hpp"

namespace slender {

// ---------------------------------------------------------------- inventory

std::string Simulation::inventory_json() const {
  std::ostringstream o;
  auto q = [](const std::string& t) {
    std::string r = "\"";
    for (char c : t) {
      if (c == '"' || c == '\\') r += '\\';
      r += c;
    }
    return r + "\"";
  };
  const std::size_t n = nodes_.size();
  std::size_t total = n * (3 * sizeof(Vec3) + sizeof(double));
  o << "{\"dimension\": " << dim_ << ", \"nodes\": " << n << ", \"node_properties\": [";
  o << "{\"name\": \"position\", \"bytes\": " << n * sizeof(Vec3) << "}, "
    << "{\"name\": \"velocity\", \"bytes\": " << n * sizeof(Vec3) << "}, "
    << "{\"name\": \"force\", \"bytes\": " << n * sizeof(Vec3) << "}, "
    << "{\"name\": \"mass\", \"bytes\": " << n * sizeof(double) << "}";
  for (const auto& [name, prop] : nodes_.properties()) {
    o << ", {\"name\": " << q(name) << ", \"type\": " << q(prop->type_name())
      << ", \"bytes\": " << prop->bytes() << "}";
    total += prop->bytes();
  }
  o << "], \"coordinates\": [";
  for (std::size_t i = 0; i < coords_.size(); ++i) o << (i ? ", " : "") << q(coords_[i]->name);
  o << "], \"styles\": [";
  bool first = true;
  auto style = [&](const char* family, const Style& s) {
    o << (first ? "" : ", ") << "{\"family\": " << q(family) << ", \"style\": " << q(s.style_name())
      << ", \"id\": " << q(s.id()) << "}";
    first = false;
  };
  for (auto& s : shells_) style("shell", *s);
  for (auto& [id, g] : growths_) style("growth", *g);
  for (auto& s : bonds_) style("bond", *s);
  for (auto& s : pairs_) style("pair", *s);
  for (auto& s : fixes_) style("fix", *s);
  for (auto& s : computes_) style("compute", *s);
  for (auto& s : dumps_) style("dump", *s);
  for (auto& [id, r] : regions_) style("region", *r);
  if (integrator_) style("integrator", *integrator_);
  o << "], \"neighbor\": [";
  for (std::size_t i = 0; i < pairs_.size(); ++i) {
    const auto keys = pairs_[i]->value_keys();
    o << (i ? ", " : "") << "{\"pair\": " << q(pairs_[i]->id())
      << ", \"structure\": " << q(pairs_[i]->neighbor_structure());
    if (std::find(keys.begin(), keys.end(), "pairs") != keys.end())
      o << ", \"pairs\": " << pairs_[i]->value("pairs");
    o << "}";
  }
  // the one rebuild decision for all lists (none in a scene without contacts)
  o << "], \"neighbor_service\": {\"requests\": " << neighbors_.requests()
    << ", \"rebuilds\": " << neighbors_.rebuilds() << ", \"scans\": " << neighbors_.scans()
    << "}, \"chains\": " << topo_.chains.size() << ", \"surfaces\": " << topo_.surfaces.size()
    << ", \"node_bytes\": " << total << "}";
  return o.str();
}

// ---------------------------------------------------------------- running

}  // namespace slender
