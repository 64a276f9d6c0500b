// Self-registering style factories. Each style file ends with
// SLENDER_REGISTER_STYLE(Base, "name", Class); no central list to edit.
// The tables are function-local statics, so static-initialisation order does not
// matter; they are filled once at load time and never changed afterwards.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "params.hpp"

namespace slender {

class Simulation;

// Family-independent view of every registered style, for --list-styles/--help.
struct CatalogEntry {
  std::string family;
  std::string name;
  std::function<ParamSpec()> spec;
};

class Catalog {
 public:
  static std::vector<CatalogEntry>& entries() {
    static std::vector<CatalogEntry> table;
    return table;
  }
  static std::vector<const CatalogEntry*> lookup(const std::string& name) {
    std::vector<const CatalogEntry*> out;
    for (auto& e : entries())
      if (e.name == name || e.family + "/" + e.name == name) out.push_back(&e);
    return out;
  }
};

template <class Base>
class Registry {
 public:
  using Factory = std::function<std::unique_ptr<Base>(Simulation&, const ParamValues&)>;
  struct Entry {
    std::function<ParamSpec()> spec;
    Factory make;
  };

  static bool add(const std::string& name, std::function<ParamSpec()> spec, Factory make) {
    table()[name] = Entry{spec, std::move(make)};
    Catalog::entries().push_back(CatalogEntry{Base::family(), name, spec});
    return true;
  }
  static const Entry* find(const std::string& name) {
    auto it = table().find(name);
    return it == table().end() ? nullptr : &it->second;
  }
  static std::vector<std::string> names() {
    std::vector<std::string> out;
    for (auto& [k, v] : table()) out.push_back(k);
    return out;
  }
  // Validates the raw parameters with the style's declaration and builds it.
  static std::unique_ptr<Base> create(const std::string& name, Simulation& sim,
                                      const RawParams& raw) {
    const Entry* e = find(name);
    if (!e) {
      std::string known;
      for (auto& n : names()) known += (known.empty() ? "" : ", ") + n;
      throw InputError(std::string("unknown ") + Base::family() + " style '" + name +
                       "' (known: " + (known.empty() ? "none" : known) + ")");
    }
    ParamSpec spec = e->spec();
    ParamValues values = spec.validate(raw);
    auto obj = e->make(sim, values);
    obj->set_style_name(name);
    return obj;
  }

 private:
  static std::map<std::string, Entry>& table() {
    static std::map<std::string, Entry> t;
    return t;
  }
};

#define SLENDER_CONCAT_INNER(a, b) a##b
#define SLENDER_CONCAT(a, b) SLENDER_CONCAT_INNER(a, b)
#define SLENDER_REGISTER_STYLE(Base, NAME, Class)                                    \
  namespace {                                                                        \
  [[maybe_unused]] const bool SLENDER_CONCAT(slender_registered_, __LINE__) =        \
      ::slender::Registry<Base>::add(                                                \
          NAME, [] { return Class::spec(NAME); },                                    \
          [](::slender::Simulation& sim, const ::slender::ParamValues& p)            \
              -> std::unique_ptr<Base> { return std::make_unique<Class>(sim, p); }); \
  }

}  // namespace slender
