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

class Context;
// The scene's Context (defined in src/simulation.cpp): what force styles are built with.
Context& context_of(Simulation& sim);
// What a style of family Base is constructed with: the Context for force styles, the
// Simulation for integrators, computes and dumps (src/style.hpp, kSeesContext).
template <class Base>
decltype(auto) host_for(Simulation& sim) {
  if constexpr (Base::kSeesContext)
    return context_of(sim);
  else
    return (sim);
}

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
    obj->set_parameters(values.text());
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
#ifndef SLENDER_PLUGIN
#define SLENDER_REGISTER_STYLE(Base, NAME, Class)                              \
  namespace {                                                                  \
  [[maybe_unused]] const bool SLENDER_CONCAT(slender_registered_, __LINE__) =  \
      ::slender::Registry<Base>::add(                                          \
          NAME, [] { return Class::spec(NAME); },                              \
          [](::slender::Simulation& sim,                                       \
             const ::slender::ParamValues& p) -> std::unique_ptr<Base> {       \
            return std::make_unique<Class>(::slender::host_for<Base>(sim), p); \
          });                                                                  \
  }
#define SLENDER_PLUGIN_ENTRY()
#else
// In a plugin (compiled with -DSLENDER_PLUGIN, see slender_add_plugin) registration
// waits until slender has loaded the library and checked that it was built for the
// same slender: a mismatched plugin is refused before any of its code touches the
// registry. SLENDER_PLUGIN_ENTRY() (once per plugin) defines the two entry points.
inline std::vector<std::function<void()> >& plugin_pending() {
  static std::vector<std::function<void()> > v;
  return v;
}
#define SLENDER_REGISTER_STYLE(Base, NAME, Class)                                                  \
  namespace {                                                                                      \
  [[maybe_unused]] const bool SLENDER_CONCAT(                                                      \
      slender_registered_, __LINE__) = (::slender::plugin_pending().push_back([] {                 \
    ::slender::Registry<Base>::add(                                                                \
        NAME, [] { return Class::spec(NAME); },                                                    \
        [](::slender::Simulation& sim, const ::slender::ParamValues& p) -> std::unique_ptr<Base> { \
          return std::make_unique<Class>(::slender::host_for<Base>(sim), p);                       \
        });                                                                                        \
  }),                                                                                              \
                                        true);                                                     \
  }
#define SLENDER_PLUGIN_ENTRY()                                                         \
  extern "C" __attribute__((visibility("default"))) const char* slender_plugin_abi() { \
    return SLENDER_ABI_STRING;                                                         \
  }                                                                                    \
  extern "C" __attribute__((visibility("default"))) int slender_plugin_register() {    \
    for (auto& f : ::slender::plugin_pending()) f();                                   \
    return static_cast<int>(::slender::plugin_pending().size());                       \
  }
#endif

// Loads a style plugin (a shared library built with slender_add_plugin): checks its
// ABI string, then registers its styles; returns how many. Throws InputError with
// the reason (file missing, not a plugin, built for another slender).
int load_plugin(const std::string& path);
// Loads every plugin named in SLENDER_PLUGIN_PATH (colon-separated files or folders).
void load_plugins_from_environment();

}  // namespace slender
