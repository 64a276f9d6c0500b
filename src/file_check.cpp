#include "file_check.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "params.hpp"

namespace slender {

std::string why_not_writable(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path p(path);
  const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
  // (appending to a named string: g++ 12 warns falsely on "literal" + std::string&&)
  std::string d = dir.string();
  if (!fs::exists(dir, ec)) return std::string("the folder '").append(d).append("' does not exist");
  if (!fs::is_directory(dir, ec)) return std::string("'").append(d).append("' is not a folder");
  if (fs::is_directory(p, ec)) return "a folder of that name exists";
  if (::access(dir.c_str(), W_OK) != 0)
    return std::string("the folder '")
        .append(d)
        .append("' is not writable (")
        .append(std::strerror(errno))
        .append(")");
  if (fs::exists(p, ec) && ::access(path.c_str(), W_OK) != 0)
    return std::string("the file exists and is not writable (") + std::strerror(errno) + ")";
  return {};
}

void require_writable(const std::string& what, const std::string& path) {
  const std::string why = why_not_writable(path);
  if (!why.empty()) throw InputError(what + " '" + path + "' cannot be written: " + why);
}

}  // namespace slender
