// A plugin that claims to be built for another slender: loading it must be refused
// with a clear message, before any of its styles register.
#include "context.hpp"
#include "registry.hpp"

namespace {
class OldFix : public slender::FixStyle {
 public:
  static slender::ParamSpec spec(const std::string& name) {
    return slender::ParamSpec("fix", name, "never registered");
  }
  OldFix(slender::Context&, const slender::ParamValues&) {}
  unsigned stages() const override { return 0; }
};
}  // namespace

SLENDER_REGISTER_STYLE(slender::FixStyle, "old_fix", OldFix)
#undef SLENDER_ABI_STRING
#define SLENDER_ABI_STRING "0.0.1/GNU-4.8/none"
SLENDER_PLUGIN_ENTRY()
