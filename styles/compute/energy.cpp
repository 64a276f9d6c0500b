// Energies by category: kinetic, stretch, bend, contact, external, potential, total.
// Potential terms are those of the last force evaluation.
#include "registry.hpp"
#include "simulation.hpp"

namespace slender {

class EnergyCompute : public ComputeStyle {
 public:
  static ParamSpec spec(const std::string& name) {
    ParamSpec s("compute", name,
                "energies: kinetic, stretch, bend, contact, external, potential, total");
    s.output("kinetic", "kinetic energy");
    s.output("stretch", "stretching energy of the last force evaluation (0 without such a style)");
    s.output("bend", "bending energy of the last force evaluation (0 without such a style)");
    s.output("contact", "contact energy of the pair styles at the last force evaluation");
    s.output("external", "energy of the fixes (loads, walls) at the last force evaluation");
    s.output("potential", "potential energy: all categories of the last force evaluation");
    s.output("total", "kinetic plus potential energy");
    return s;
  }
  EnergyCompute(Simulation&, const ParamValues&) {}
  void evaluate(Simulation& sim) override {
    vals_ = sim.energies();
    vals_["kinetic"] = sim.kinetic_energy();
    vals_["potential"] = sim.potential_energy();
    vals_["total"] = vals_["kinetic"] + vals_["potential"];
  }
  double value(const std::string& key) const override {
    auto it = vals_.find(key);
    if (it != vals_.end()) return it->second;
    for (auto& k : value_keys())
      if (k == key) return 0.0;  // no style of this category in the scene
    return ComputeStyle::value(key);
  }

 private:
  std::map<std::string, double> vals_;
};

}  // namespace slender

SLENDER_REGISTER_STYLE(slender::ComputeStyle, "energy", slender::EnergyCompute)
