// Declared, validated style parameters. One declaration per style drives the
// validation of its Lua table, the error messages and `slender --help STYLE`.
#pragma once

#include <Eigen/Core>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace slender {

// A user mistake in a deck (bad key, type, range, unknown name). The Lua layer
// prefixes it with the deck's file:line.
struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

enum class ParamType { Real, Int, Bool, String, Vector, RealOrAuto, StringList, IntList, Function };

const char* type_name(ParamType t);

// A function given in a deck (a run callback, a growth law): validated like any other
// parameter (declared with ParamType::Function); the deck layer keeps the function itself.
struct DeckFunction {
  bool operator==(const DeckFunction&) const = default;
};

// A raw value as it comes from the deck, before validation.
using Value = std::variant<std::monostate, double, bool, std::string, std::vector<double>,
                           std::vector<std::string>, DeckFunction>;
using RawParams = std::map<std::string, Value>;

struct ParamDecl {
  std::string name;
  ParamType type = ParamType::Real;
  std::string help;
  bool is_required = false;
  Value default_value;
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false, hi_open = false;
  std::vector<std::string> allowed;    // for String
  int min_len = 0, max_len = 1 << 30;  // for Vector/lists

  ParamDecl& required() {
    is_required = true;
    return *this;
  }
  ParamDecl& def(Value v) {
    default_value = std::move(v);
    return *this;
  }
  ParamDecl& min(double v, bool open = false) {
    lo = v;
    lo_open = open;
    return *this;
  }
  ParamDecl& max(double v, bool open = false) {
    hi = v;
    hi_open = open;
    return *this;
  }
  ParamDecl& positive() { return min(0.0, true); }
  ParamDecl& nonnegative() { return min(0.0, false); }
  ParamDecl& choices(std::vector<std::string> c) {
    allowed = std::move(c);
    return *this;
  }
  ParamDecl& length(int lo_len, int hi_len) {
    min_len = lo_len;
    max_len = hi_len;
    return *this;
  }
  std::string range_text() const;
  // "required", "optional" or the default value as a deck would write it.
  std::string default_text() const;
};

class ParamValues;

struct ParamSpec {
  std::string family;
  std::string name;
  std::string summary;
  std::vector<ParamDecl> decls;
  // The values a style offers to thermo as "<id>.<key>": (key, meaning). They are the keys
  // Style::value_keys() reports, listed by --help, the style pages and the "unknown column"
  // error.
  std::vector<std::pair<std::string, std::string>> outputs;

  ParamSpec() = default;
  ParamSpec(std::string fam, std::string nm, std::string sum)
      : family(std::move(fam)), name(std::move(nm)), summary(std::move(sum)) {}

  ParamDecl& add(const std::string& key, ParamType t, const std::string& help);
  ParamDecl& real(const std::string& key, const std::string& help) {
    return add(key, ParamType::Real, help);
  }
  ParamDecl& integer(const std::string& key, const std::string& help) {
    return add(key, ParamType::Int, help);
  }
  ParamDecl& boolean(const std::string& key, const std::string& help) {
    return add(key, ParamType::Bool, help);
  }
  ParamDecl& string(const std::string& key, const std::string& help) {
    return add(key, ParamType::String, help);
  }
  ParamDecl& vector(const std::string& key, const std::string& help) {
    return add(key, ParamType::Vector, help);
  }
  const ParamDecl* find(const std::string& key) const;
  ParamSpec& output(const std::string& key, const std::string& help) {
    outputs.emplace_back(key, help);
    return *this;
  }

  // Checks keys, types and ranges; fills defaults. Throws InputError.
  ParamValues validate(const RawParams& raw) const;
  std::string help_text() const;
  // How messages name the owner: "bond style 'spring'" or "command 'wire'".
  std::string owner_text() const;
};

// Validated values of one style instance.
class ParamValues {
 public:
  ParamValues() = default;
  ParamValues(std::string owner, std::map<std::string, Value> v)
      : owner_(std::move(owner)), values_(std::move(v)) {}

  bool has(const std::string& key) const;
  double real(const std::string& key) const;
  long integer(const std::string& key) const;
  bool boolean(const std::string& key) const;
  const std::string& str(const std::string& key) const;
  const std::vector<double>& vec(const std::string& key) const;
  Eigen::Vector3d vec3(const std::string& key) const;  // 2-vectors get z = 0
  const std::vector<std::string>& strings(const std::string& key) const;
  std::vector<long> integers(const std::string& key) const;
  bool is_auto(const std::string& key) const;
  const std::map<std::string, Value>& all() const { return values_; }
  // Every value, "key = value" per line in key order, numbers to the last digit: what a
  // checkpoint records of the deck that wrote it.
  std::string text() const;
  // One value as text() writes it.
  static std::string exact_text(const Value& v);
  const std::string& owner() const { return owner_; }

 private:
  const Value& get(const std::string& key) const;
  std::string owner_;
  std::map<std::string, Value> values_;
};

}  // namespace slender
