// slender: run a Lua deck, list styles, or describe one.
#include <cstdio>
#include <cstring>
#include <string>

#include "lua_binding.hpp"
#include "registry.hpp"

namespace {

void usage() {
  std::printf(
      "usage: slender DECK.lua [-v name=value ...] [-q]\n"
      "       slender --list-styles\n"
      "       slender --help STYLE     (e.g. spring, bond/spring, gear)\n"
      "       slender --version\n"
      "A deck reads overrides with slender.var(\"name\", default).\n");
}

int list_styles() {
  std::string last;
  for (auto& fam : {"bond", "pair", "fix", "compute", "dump", "integrator", "region"}) {
    std::printf("%s:\n", fam);
    bool any = false;
    for (auto& e : slender::Catalog::entries()) {
      if (e.family != fam) continue;
      std::printf("  %-18s %s\n", e.name.c_str(), e.spec().summary.c_str());
      any = true;
    }
    if (!any) std::printf("  (none registered yet)\n");
  }
  return 0;
}

int help_style(const std::string& name) {
  auto found = slender::Catalog::lookup(name);
  if (found.empty()) {
    std::fprintf(stderr, "slender: no style named '%s' (see slender --list-styles)\n", name.c_str());
    return 1;
  }
  for (auto* e : found) std::printf("%s\n", e->spec().help_text().c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  slender::DeckOptions opt;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    if (a == "--list-styles") return list_styles();
    if (a == "--help" || a == "-h") {
      if (i + 1 < argc) return help_style(argv[i + 1]);
      usage();
      return 0;
    }
    if (a == "--version") {
      std::printf("slender 0.1.0\n");
      return 0;
    }
    if (a == "-q") {
      opt.quiet = true;
    } else if (a == "-v") {
      if (i + 1 >= argc || !std::strchr(argv[i + 1], '=')) {
        std::fprintf(stderr, "slender: -v needs name=value\n");
        return 2;
      }
      std::string kv = argv[++i];
      auto eq = kv.find('=');
      opt.vars[kv.substr(0, eq)] = kv.substr(eq + 1);
    } else if (!a.empty() && a[0] == '-') {
      std::fprintf(stderr, "slender: unknown option %s\n", a.c_str());
      usage();
      return 2;
    } else if (opt.path.empty()) {
      opt.path = a;
    } else {
      std::fprintf(stderr, "slender: only one deck per run (got %s and %s)\n", opt.path.c_str(), a.c_str());
      return 2;
    }
  }
  if (opt.path.empty()) {
    usage();
    return 2;
  }
  return slender::run_deck(opt);
}
