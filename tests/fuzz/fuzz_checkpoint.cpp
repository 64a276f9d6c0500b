// Fuzz target: the checkpoint reader, structure-aware. Random bytes given to HDF5 would test
// the HDF5 library, not us; instead a valid checkpoint of a small scene (a 2D crumpling scene
// with plastic bending, friction and injection, or a 3D Cosserat rod with segment contact in
// a sphere) is made once, and each input is a list of edits of its datasets: an entry set to
// NaN, an infinity, a huge, negative or fractional value or to raw bytes, an index shifted by
// one, a dataset truncated, grown or dropped. The edited file is read into a fresh scene of
// the same deck, which then runs a few steps. Every input must either load and run, or be
// refused with an InputError (or stopped by the guard: InstabilityError); another exception,
// a crash or a sanitizer report is a finding.
#include <hdf5.h>
#include <unistd.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iterator>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "h5util.hpp"
#include "simulation.hpp"

namespace {

using slender::RawParams;
using slender::Simulation;
using slender::Vec3;

// The scene without its state: what a deck builds before sim:read_checkpoint.
std::unique_ptr<Simulation> make_scene(int kind) {
  auto sim = std::make_unique<Simulation>(kind == 0 ? 2 : 3, 7);
  sim->verbose = false;
  std::vector<Vec3> pts;
  if (kind == 0) {
    for (int i = 0; i < 25; ++i) pts.emplace_back(-12.0 + i, 0.05 * std::sin(i), 0);
    sim->add_chain("wire", pts, 1.0, false);
    sim->add_bond("spring", RawParams{{"k", 1000.0}});
    sim->add_bond("bend2d/hysteresis", RawParams{{"k", 60.0}, {"yield_curvature", 0.3}});
    sim->add_pair("contact/node-edge",
                  RawParams{{"stiffness", 2000.0}, {"mu_static", 0.3}, {"diameter", 1.0}});
    sim->add_fix("wall", "wall/circle",
                 RawParams{{"radius", 10.0}, {"stiffness", 2000.0}, {"mu_static", 0.3}});
    sim->add_fix("drag", "damping/viscous", RawParams{{"gamma", 0.5}});
    sim->add_fix("feed", "inject/wire",
                 RawParams{{"chain", std::string("wire")}, {"radius", 10.0}, {"speed", 0.5}});
    sim->set_integrator("verlet", RawParams{{"dt", 0.005}});
  } else {
    for (int i = 0; i < 16; ++i) pts.emplace_back(0.4 * i - 3.0, 0.3 * std::sin(i), 0.1 * i - 0.75);
    sim->add_chain("rod", pts, 1.0, false);
    sim->add_bond("spring", RawParams{{"k", 1000.0}});
    sim->add_bond("rod/cosserat",
                  RawParams{{"YI", 5.0}, {"GJ", 4.0}, {"coupling", 1000.0}, {"rot_inertia", 0.01}});
    sim->add_pair("contact/segment",
                  RawParams{{"stiffness", 1000.0}, {"mu_static", 0.2}, {"radius", 0.15}});
    sim->add_fix("wall", "wall/sphere", RawParams{{"radius", 4.0}, {"stiffness", 1000.0}});
    sim->set_integrator("verlet", RawParams{{"dt", 0.002}});
  }
  return sim;
}

// A checkpoint as its datasets: path -> (dimensions, values); all of them are doubles.
struct Dataset {
  std::vector<hsize_t> dims;
  std::vector<double> values;
};
using Checkpoint = std::map<std::string, Dataset>;

void collect(hid_t group, const std::string& prefix, Checkpoint& out) {
  for (const std::string& name : slender::h5::children(group)) {
    const hid_t ds = H5Dopen2(group, name.c_str(), H5P_DEFAULT);
    if (ds >= 0) {
      H5Dclose(ds);
      Dataset d;
      d.values = slender::h5::read_doubles(group, name, &d.dims);
      out[prefix + name] = std::move(d);
    } else {
      auto g = slender::h5::open_group(group, name);
      collect(g, prefix + name + "/", out);
    }
  }
}

void write(const Checkpoint& ck, const std::string& path) {
  auto f = slender::h5::create_file(path);
  slender::h5::attr_string(f, "creator", "slender checkpoint v1");
  std::map<std::string, slender::h5::Handle> groups;
  for (auto& [name, d] : ck) {
    hid_t parent = f;
    std::string rest = name, prefix;
    for (auto slash = rest.find('/'); slash != std::string::npos; slash = rest.find('/')) {
      prefix += rest.substr(0, slash) + "/";
      if (!groups.count(prefix))
        groups[prefix] = slender::h5::create_group(parent, rest.substr(0, slash));
      parent = groups[prefix];
      rest = rest.substr(slash + 1);
    }
    slender::h5::write_doubles(parent, rest, d.values, d.dims);
  }
}

struct Base {
  std::vector<Checkpoint> scenes;
  std::string file;
};

const Base& base() {
  static const Base b = [] {
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);  // probing for datasets is not an error
    Base b;
    const char* tmp = std::getenv("TMPDIR");
    const std::string dir = tmp ? tmp : "/tmp";
    b.file = dir + "/slender_fuzz_checkpoint_" + std::to_string(getpid()) + ".h5";
    for (int kind = 0; kind < 2; ++kind) {
      auto sim = make_scene(kind);
      sim->run(slender::RunOptions{kind == 0 ? 3000 : 1500, 0, {}});
      sim->write_checkpoint(b.file);
      auto f = slender::h5::open_file(b.file, false);
      Checkpoint ck;
      collect(f, "", ck);
      b.scenes.push_back(std::move(ck));
    }
    return b;
  }();
  return b;
}

double special(std::uint8_t k, double old, std::size_t n) {
  const double table[] = {std::numeric_limits<double>::quiet_NaN(),
                          std::numeric_limits<double>::infinity(),
                          -std::numeric_limits<double>::infinity(),
                          -1.0,
                          0.0,
                          1e20,
                          -1e20,
                          2147483648.0,
                          9007199254740993.0,
                          1e-300,
                          old + 0.5,
                          static_cast<double>(n),
                          static_cast<double>(n) - 1.0,
                          old + 1.0,
                          old - 1.0,
                          -old};
  return table[k % (sizeof table / sizeof table[0])];
}

// Applies the edits the input spells: 4 bytes each (dataset, operation, index), plus 8 for a
// raw value.
void edit(Checkpoint& ck, const std::uint8_t* data, std::size_t size) {
  std::size_t at = 0;
  while (at + 4 <= size && !ck.empty()) {
    auto it = ck.begin();
    std::advance(it, data[at] % ck.size());
    Dataset& d = it->second;
    const std::uint8_t op = data[at + 1];
    const std::size_t index = static_cast<std::size_t>(data[at + 2]) | (data[at + 3] << 8);
    at += 4;
    const std::size_t n = d.values.size();
    const std::size_t row = d.dims.empty() ? 1 : n / std::max<hsize_t>(d.dims[0], 1);
    switch (op % 6) {
      case 0:
      case 1:  // one entry set to a value that has broken readers
        if (n > 0) d.values[index % n] = special(op / 6, d.values[index % n], n);
        break;
      case 2:  // one entry set to raw bytes
        if (at + 8 <= size && n > 0) {
          double v;
          std::memcpy(&v, data + at, 8);
          d.values[index % n] = v;
        }
        at += 8;
        break;
      case 3:  // rows cut off
        if (!d.dims.empty() && d.dims[0] > 0) {
          d.dims[0] = index % d.dims[0];
          d.values.resize(d.dims[0] * row);
        }
        break;
      case 4:  // rows added (copies of the last)
        if (!d.dims.empty() && n > 0 && row > 0) {
          const std::size_t extra = 1 + index % 8;
          for (std::size_t r = 0; r < extra; ++r)
            d.values.insert(d.values.end(), d.values.end() - static_cast<long>(row),
                            d.values.end());
          d.dims[0] += extra;
        }
        break;
      case 5:  // the dataset dropped
        ck.erase(it);
        break;
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1 || size > 512) return 0;
  const Base& b = base();
  const int kind = data[0] & 1;
  Checkpoint ck = b.scenes[static_cast<std::size_t>(kind)];
  edit(ck, data + 1, size - 1);
  write(ck, b.file);
  auto sim = make_scene(kind);
  std::string what = "ok";
  try {
    sim->read_checkpoint(b.file);
    sim->run(slender::RunOptions{3, 0, {}});
  } catch (const slender::InputError& e) {
    what = e.what();
  } catch (const slender::InstabilityError& e) {
    what = std::string("guard: ") + e.what();
  }
  // SLENDER_FUZZ_VERBOSE=1: what each input gave (to check that the seeds reach the reader)
  if (std::getenv("SLENDER_FUZZ_VERBOSE"))
    std::fprintf(stderr, "scene %d: %s\n", kind, what.substr(0, 300).c_str());
  return 0;
}
