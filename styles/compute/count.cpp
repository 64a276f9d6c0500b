// Node, edge and chain counts (they change when chains grow).
#include "registry.hpp"
#include "simulation.hpp"

namespace slender {

class CountCompute : public ComputeStyle {
 public:
  static ParamSpec spec(const std::string& name) {
    ParamSpec s("compute", name, "counts: nodes, edges, chains, ghosts; or the nodes of one group");
    s.string("group", "count only this group's nodes for key 'group'").def(std::string("all"));
    s.output("nodes", "number of owned nodes (ghosts not counted)");
    s.output("edges", "number of edges");
    s.output("chains", "number of chains");
    s.output("ghosts", "number of ghost nodes");
    s.output("group", "number of nodes in the group named by 'group'");
    return s;
  }
  CountCompute(Simulation& sim, const ParamValues& p) : group_(p.str("group")) {
    sim.group(group_);
  }
  void evaluate(Simulation& sim) override {
    nodes_ = static_cast<double>(sim.nodes().n_owned());
    ghosts_ = static_cast<double>(sim.nodes().n_ghost());
    edges_ = sim.topology().n_edges();
    chains_ = static_cast<double>(sim.topology().chains.size());
    group_count_ = static_cast<double>(sim.group(group_).size());
  }
  double value(const std::string& key) const override {
    if (key == "nodes") return nodes_;
    if (key == "edges") return edges_;
    if (key == "chains") return chains_;
    if (key == "ghosts") return ghosts_;
    if (key == "group") return group_count_;
    return ComputeStyle::value(key);
  }

 private:
  std::string group_;
  double nodes_ = 0, edges_ = 0, chains_ = 0, ghosts_ = 0, group_count_ = 0;
};

}  // namespace slender

SLENDER_REGISTER_STYLE(slender::ComputeStyle, "count", slender::CountCompute)
