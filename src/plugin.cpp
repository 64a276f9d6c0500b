// Style plugins: shared libraries built against this slender (slender_add_plugin)
// whose styles register exactly like built-in ones once their ABI string matches.
// Loaded libraries stay loaded for the life of the process, like the registry.
#include <dlfcn.h>

#include <filesystem>
#include <string>

#include "params.hpp"
#include "registry.hpp"

namespace slender {

int load_plugin(const std::string& path) {
  if (!std::filesystem::exists(path)) throw InputError("plugin '" + path + "': no such file");
  void* h = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!h) throw InputError(std::string("plugin '") + path + "': " + dlerror());
  using AbiFn = const char* (*)();
  using RegFn = int (*)();
  auto abi = reinterpret_cast<AbiFn>(dlsym(h, "slender_plugin_abi"));
  auto reg = reinterpret_cast<RegFn>(dlsym(h, "slender_plugin_register"));
  if (!abi || !reg) {
    dlclose(h);
    throw InputError("plugin '" + path +
                     "' is not a slender plugin (no SLENDER_PLUGIN_ENTRY(); build it with "
                     "slender_add_plugin)");
  }
  const std::string theirs = abi();
  if (theirs != SLENDER_ABI_STRING) {
    dlclose(h);
    throw InputError("plugin '" + path + "' was built for slender " + theirs +
                     ", this is slender " + SLENDER_ABI_STRING +
                     "; rebuild the plugin against this slender");
  }
  return reg();
}

void load_plugins_from_environment() {
  const char* env = std::getenv("SLENDER_PLUGIN_PATH");
  if (!env) return;
  std::string list = env;
  std::size_t start = 0;
  while (start <= list.size()) {
    const std::size_t end = list.find(':', start);
    const std::string item = list.substr(start, end == std::string::npos ? end : end - start);
    if (!item.empty()) {
      if (std::filesystem::is_directory(item)) {
        for (auto& e : std::filesystem::directory_iterator(item))
          if (e.path().extension() == ".so") load_plugin(e.path().string());
      } else {
        load_plugin(item);
      }
    }
    if (end == std::string::npos) break;
    start = end + 1;
  }
}

}  // namespace slender
