#include "params.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

namespace slender {

const char* type_name(ParamType t) {
  switch (t) {
    case ParamType::Real:
      return "number";
    case ParamType::Int:
      return "integer";
    case ParamType::Bool:
      return "boolean";
    case ParamType::String:
      return "string";
    case ParamType::Vector:
      return "vector of numbers";
    case ParamType::RealOrAuto:
      return "number or \"auto\"";
    case ParamType::StringList:
      return "list of strings";
    case ParamType::IntList:
      return "list of integers";
    case ParamType::Function:
      return "function";
  }
  return "?";
}

namespace {

std::string fmt(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

const char* value_kind(const Value& v) {
  switch (v.index()) {
    case 0:
      return "nil";
    case 1:
      return "number";
    case 2:
      return "boolean";
    case 3:
      return "string";
    case 4:
      return "list of numbers";
    case 5:
      return "list of strings";
    case 6:
      return "function";
  }
  return "?";
}

std::string value_text(const Value& v) {
  if (auto d = std::get_if<double>(&v)) return fmt(*d);
  if (auto b = std::get_if<bool>(&v)) return *b ? "true" : "false";
  if (auto s = std::get_if<std::string>(&v)) return "\"" + *s + "\"";
  if (auto vv = std::get_if<std::vector<double>>(&v)) {
    std::string out = "{";
    for (size_t i = 0; i < vv->size(); ++i) out += (i ? ", " : "") + fmt((*vv)[i]);
    return out + "}";
  }
  if (auto vs = std::get_if<std::vector<std::string>>(&v)) {
    std::string out = "{";
    for (size_t i = 0; i < vs->size(); ++i) out += (i ? ", \"" : "\"") + (*vs)[i] + "\"";
    return out + "}";
  }
  if (std::holds_alternative<DeckFunction>(v)) return "function";
  return "nil";
}

}  // namespace

std::string ParamValues::exact_text(const Value& v) {
  if (auto d = std::get_if<double>(&v)) {
    // the shortest of 15 or 17 digits that reads back to the same number
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.15g", *d);
    if (std::strtod(buf, nullptr) != *d) std::snprintf(buf, sizeof buf, "%.17g", *d);
    return buf;
  }
  if (auto vv = std::get_if<std::vector<double>>(&v)) {
    std::string out = "{";
    for (size_t i = 0; i < vv->size(); ++i) out += (i ? ", " : "") + exact_text((*vv)[i]);
    return out + "}";
  }
  return value_text(v);
}

std::string ParamValues::text() const {
  std::string out;
  for (auto& [key, v] : values_) out += key + " = " + exact_text(v) + "\n";
  return out;
}

std::string ParamDecl::range_text() const {
  std::string r;
  if (std::isfinite(lo) || std::isfinite(hi)) {
    r += lo_open || !std::isfinite(lo) ? "(" : "[";
    r += std::isfinite(lo) ? fmt(lo) : "-inf";
    r += ", ";
    r += std::isfinite(hi) ? fmt(hi) : "inf";
    // values must be finite, so an unbounded side is open whatever the declaration says
    r += hi_open || !std::isfinite(hi) ? ")" : "]";
  }
  if (!allowed.empty()) {
    r += "one of";
    for (auto& a : allowed) r += " \"" + a + "\"";
  }
  return r;
}

std::string ParamDecl::default_text() const {
  if (is_required) return "required";
  if (std::holds_alternative<std::monostate>(default_value)) return "optional";
  return value_text(default_value);
}

ParamDecl& ParamSpec::add(const std::string& key, ParamType t, const std::string& help) {
  decls.push_back(ParamDecl{});
  decls.back().name = key;
  decls.back().type = t;
  decls.back().help = help;
  return decls.back();
}

const ParamDecl* ParamSpec::find(const std::string& key) const {
  for (auto& d : decls)
    if (d.name == key) return &d;
  return nullptr;
}

std::string ParamSpec::owner_text() const {
  return family == "command" ? "command '" + name + "'" : family + " style '" + name + "'";
}

ParamValues ParamSpec::validate(const RawParams& raw) const {
  const std::string who = owner_text();
  for (auto& [key, v] : raw) {
    if (!find(key)) {
      std::string known;
      for (auto& d : decls) known += (known.empty() ? "" : ", ") + d.name;
      throw InputError(who + ": unknown key '" + key +
                       "' (known keys: " + (known.empty() ? "none" : known) + ")");
    }
  }
  std::map<std::string, Value> out;
  for (auto& d : decls) {
    auto it = raw.find(d.name);
    if (it == raw.end() || std::holds_alternative<std::monostate>(it->second)) {
      if (d.is_required)
        throw InputError(who + ": missing required key '" + d.name + "' (" + d.help + ")");
      if (!std::holds_alternative<std::monostate>(d.default_value)) out[d.name] = d.default_value;
      continue;
    }
    Value v = it->second;
    auto mistyped = [&]() {
      return InputError(who + ": key '" + d.name + "' expects a " + type_name(d.type) + ", got " +
                        value_kind(v) + " " + value_text(v));
    };
    auto check_range = [&](double x) {
      if (!std::isfinite(x))
        throw InputError(who + ": key '" + d.name + "' = " + fmt(x) + " is not a finite number" +
                         (d.range_text().empty() ? "" : " (range " + d.range_text() + ")"));
      bool bad = x < d.lo || x > d.hi || (d.lo_open && x == d.lo) || (d.hi_open && x == d.hi);
      if (bad)
        throw InputError(who + ": key '" + d.name + "' = " + fmt(x) + " is out of range " +
                         d.range_text());
    };
    // integers travel as doubles (Lua numbers): beyond 2^53 they are no longer exact, and
    // beyond a long they would overflow (steps = 2^63 came out as a negative count)
    auto check_whole = [&](double x) {
      if (std::abs(x) > 9007199254740992.0)
        throw InputError(who + ": key '" + d.name + "' = " + fmt(x) +
                         " is too large for an integer (at most 2^53 = 9007199254740992)");
    };
    switch (d.type) {
      case ParamType::Real:
        if (!std::holds_alternative<double>(v)) throw mistyped();
        check_range(std::get<double>(v));
        break;
      case ParamType::Int: {
        if (!std::holds_alternative<double>(v)) throw mistyped();
        double x = std::get<double>(v);
        if (x != std::floor(x)) throw mistyped();
        check_whole(x);
        check_range(x);
        break;
      }
      case ParamType::Bool:
        if (!std::holds_alternative<bool>(v)) throw mistyped();
        break;
      case ParamType::String: {
        if (!std::holds_alternative<std::string>(v)) throw mistyped();
        auto& s = std::get<std::string>(v);
        if (!d.allowed.empty()) {
          bool ok = false;
          for (auto& a : d.allowed) ok = ok || a == s;
          if (!ok)
            throw InputError(who + ": key '" + d.name + "' = \"" + s + "\" is not " +
                             d.range_text());
        }
        break;
      }
      case ParamType::RealOrAuto:
        if (auto s = std::get_if<std::string>(&v)) {
          if (*s != "auto") throw mistyped();
        } else if (std::holds_alternative<double>(v)) {
          check_range(std::get<double>(v));
        } else {
          throw mistyped();
        }
        break;
      case ParamType::Vector:
      case ParamType::IntList: {
        if (std::holds_alternative<double>(v)) v = std::vector<double>{std::get<double>(v)};
        if (!std::holds_alternative<std::vector<double>>(v)) {
          // an empty Lua table arrives as an empty string list
          auto* vs = std::get_if<std::vector<std::string>>(&v);
          if (vs && vs->empty())
            v = std::vector<double>{};
          else
            throw mistyped();
        }
        auto& vv = std::get<std::vector<double>>(v);
        if (static_cast<int>(vv.size()) < d.min_len || static_cast<int>(vv.size()) > d.max_len)
          throw InputError(who + ": key '" + d.name + "' needs " + std::to_string(d.min_len) +
                           (d.max_len != d.min_len ? " to " + std::to_string(d.max_len) : "") +
                           " values, got " + std::to_string(vv.size()));
        for (double x : vv) {
          if (d.type == ParamType::IntList && x != std::floor(x)) throw mistyped();
          if (d.type == ParamType::IntList) check_whole(x);
          check_range(x);
        }
        break;
      }
      case ParamType::Function:
        if (!std::holds_alternative<DeckFunction>(v))
          throw InputError(who + ": key '" + d.name + "' must be a Lua function, got a " +
                           value_kind(v));
        break;
      case ParamType::StringList:
        if (std::holds_alternative<std::string>(v))
          v = std::vector<std::string>{std::get<std::string>(v)};
        if (auto* vd = std::get_if<std::vector<double>>(&v); vd && vd->empty())
          v = std::vector<std::string>{};
        if (!std::holds_alternative<std::vector<std::string>>(v)) throw mistyped();
        break;
    }
    out[d.name] = v;
  }
  return ParamValues(who, std::move(out));
}

std::string ParamSpec::help_text() const {
  std::ostringstream os;
  os << owner_text() << ": " << summary << "\n";
  if (decls.empty()) os << "  (no parameters)\n";
  for (auto& d : decls) {
    os << "  " << d.name << " (" << type_name(d.type) << ", ";
    if (d.is_required || std::holds_alternative<std::monostate>(d.default_value))
      os << d.default_text();
    else
      os << "default " << d.default_text();
    auto r = d.range_text();
    if (!r.empty()) os << ", " << r;
    os << "): " << d.help << "\n";
  }
  if (!outputs.empty()) {
    os << "  values for thermo columns (<id>.<key>):\n";
    for (auto& [key, help] : outputs) os << "    " << key << ": " << help << "\n";
  }
  return os.str();
}

const Value& ParamValues::get(const std::string& key) const {
  auto it = values_.find(key);
  if (it == values_.end()) throw InputError(owner_ + ": key '" + key + "' has no value");
  return it->second;
}
bool ParamValues::has(const std::string& key) const {
  return values_.count(key) > 0;
}
double ParamValues::real(const std::string& key) const {
  return std::get<double>(get(key));
}
long ParamValues::integer(const std::string& key) const {
  return static_cast<long>(std::get<double>(get(key)));
}
bool ParamValues::boolean(const std::string& key) const {
  return std::get<bool>(get(key));
}
const std::string& ParamValues::str(const std::string& key) const {
  return std::get<std::string>(get(key));
}
const std::vector<double>& ParamValues::vec(const std::string& key) const {
  return std::get<std::vector<double>>(get(key));
}
Eigen::Vector3d ParamValues::vec3(const std::string& key) const {
  auto& v = vec(key);
  Eigen::Vector3d out = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < v.size() && i < 3; ++i) out[i] = v[i];
  return out;
}
const std::vector<std::string>& ParamValues::strings(const std::string& key) const {
  return std::get<std::vector<std::string>>(get(key));
}
std::vector<long> ParamValues::integers(const std::string& key) const {
  std::vector<long> out;
  for (double x : vec(key)) out.push_back(static_cast<long>(x));
  return out;
}
bool ParamValues::is_auto(const std::string& key) const {
  auto& v = get(key);
  return std::holds_alternative<std::string>(v);
}

}  // namespace slender
