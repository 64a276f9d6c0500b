// Fuzz target: the OBJ/OFF mesh reader and the surface it builds (ghost layer, Loop patch
// checks). The first byte chooses the format, the rest is the file. Every input must either
// give a surface or be refused with an InputError; anything else (another exception, a
// crash, a sanitizer report) is a finding.
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include "params.hpp"
#include "shell/surface.hpp"
#include "shell/trimesh.hpp"
#include "simulation.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1 || size > 1 << 16) return 0;
  const std::string format = (data[0] & 1) ? "off" : "obj";
  std::istringstream in(std::string(reinterpret_cast<const char*>(data) + 1, size - 1));
  try {
    slender::shell::TriMesh m = slender::shell::parse_mesh(in, format, "fuzz." + format);
    if (m.n_nodes() > 4096) return 0;  // the reader is the target, not the size of the scene
    slender::Simulation sim(3, 1);
    slender::shell::add_surface(sim, "s", m, 0.0);
  } catch (const slender::InputError&) {
  }
  return 0;
}
