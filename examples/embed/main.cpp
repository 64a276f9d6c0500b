// slender as a library: a program builds a scene in C++ (no deck), runs it and reads
// the results. A clamped wire of 21 nodes under a small tip load relaxes by FIRE; the
// tip deflection is compared with Euler–Bernoulli, P L^3 / (3 EI), with L measured from
// the middle of the clamped first segment (the clamp holds nodes 0 and 1).
//   cmake -S . -B build -Dslender_DIR=<prefix>/lib/cmake/slender && cmake --build build
//   build/embed
#include <cmath>
#include <cstdio>

#include "scene_build.hpp"
#include "simulation.hpp"

int main() {
  using namespace slender;
  const int n = 21;
  const double L = 20.0, k_bend = 60.0, P = 1e-4;  // EI = k_bend * segment length
  Simulation sim(2, 1);
  sim.verbose = false;
  // the deck's sim:wire{...}, from the same parameter declarations (src/scene_build.hpp)
  add_wire(sim, RawParams{
                    {"name", std::string("wire")}, {"nodes", double(n)}, {"spacing", L / (n - 1)}});
  sim.add_bond("spring", RawParams{{"k", 1000.0}});
  sim.add_bond("bend2d", RawParams{{"k", k_bend}});
  sim.set_group("root", {0});
  sim.set_group("tip", {n - 1});
  sim.add_fix("clamp", "clamp", RawParams{{"group", std::string("root")}, {"rotation", true}});
  sim.add_fix("load", "force/constant",
              RawParams{{"group", std::string("tip")}, {"force", std::vector<double>{0, -P}}});
  sim.set_integrator("fire", RawParams{});
  const long steps = sim.minimize(1e-10, 1000000);
  const double tip = -sim.nodes().x[n - 1].y();
  const double EI = k_bend * L / (n - 1);
  const double Le = L - 0.5 * L / (n - 1);
  const double ref = P * Le * Le * Le / (3 * EI);
  std::printf("embed: %ld FIRE steps, tip deflection %.6e, Euler-Bernoulli %.6e, rel. error %.2e\n",
              steps, tip, ref, std::abs(tip / ref - 1));
  return std::abs(tip / ref - 1) < 0.01 ? 0 : 1;
}
