// Periodic checkpoints: the full restartable state every N steps or T time units, written
// atomically. "%d" in the file name is replaced by the step number.
#include <string>

#include "registry.hpp"
#include "simulation.hpp"

namespace slender {

class CheckpointDump : public DumpStyle {
 public:
  static ParamSpec spec(const std::string& name) {
    ParamSpec s(
        "dump", name,
        "restart file (HDF5) every N steps or T time units, written atomically (temp + rename)");
    s.string("file", "checkpoint file; %d is replaced by the step").required();
    Cadence::declare(s, "checkpoints");
    return s;
  }
  CheckpointDump(Simulation&, const ParamValues& p) : file_(p.str("file")) {
    set_cadence(Cadence::from(p, "dump style 'checkpoint'", true));
  }
  void write(Simulation& sim) override {
    if (sim.step == 0 && sim.time == 0.0) return;  // nothing to restart from yet
    std::string path = file_;
    auto pos = path.find("%d");
    if (pos != std::string::npos) path.replace(pos, 2, std::to_string(sim.step));
    sim.write_checkpoint(path);
  }

 private:
  std::string file_;
};

}  // namespace slender

SLENDER_REGISTER_STYLE(slender::DumpStyle, "checkpoint", slender::CheckpointDump)
