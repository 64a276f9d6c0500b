// The limit-surface position (Loop's limit mask, docs/models.md §6.6) of the control
// node nearest to a reference point, and its displacement: the deflection a plate
// or shell test compares with theory (a control node itself is not on the surface).
#include <limits>

#include "registry.hpp"
#include "shell/loop_patch.hpp"
#include "simulation.hpp"

namespace slender {

class LimitPointCompute : public ComputeStyle {
 public:
  static ParamSpec spec(const std::string& name) {
    ParamSpec s("compute", name,
                "limit-surface position and displacement at the control node nearest to a "
                "reference point of a shell mesh");
    s.string("mesh", "surface created by sim:mesh").required();
    s.vector("point", "reference position").required().length(3, 3);
    s.output("x", "x of the limit-surface point of the nearest control node");
    s.output("y", "y of the limit-surface point of the nearest control node");
    s.output("z", "z of the limit-surface point of the nearest control node");
    s.output("ux", "x displacement of that limit-surface point from its reference position");
    s.output("uy", "y displacement of that limit-surface point from its reference position");
    s.output("uz", "z displacement of that limit-surface point from its reference position");
    return s;
  }
  LimitPointCompute(Simulation& sim, const ParamValues& p) {
    const Surface* s = sim.topology().find_surface(p.str("mesh"));
    if (!s) throw InputError("compute 'limit_point': no mesh named '" + p.str("mesh") + "'");
    const Vec3 X = p.vec3("point");
    int best = 0;
    double d = std::numeric_limits<double>::max();
    for (int i = 0; i < s->mesh->n_real_nodes; ++i)
      if ((s->mesh->mesh.x[i] - X).norm() < d) {
        d = (s->mesh->mesh.x[i] - X).norm();
        best = i;
      }
    base_ = s->first_node;
    mask_ = shell::limit_mask(*s->mesh, best);
    for (auto& r : mask_) ref_ += r.N * s->mesh->mesh.x[r.node];
  }
  void evaluate(Simulation& sim) override {
    x_.setZero();
    for (auto& r : mask_) x_ += r.N * sim.nodes().x[base_ + r.node];
  }
  double value(const std::string& key) const override {
    if (key.size() == 1 && key[0] >= 'x' && key[0] <= 'z') return x_[key[0] - 'x'];
    if (key.size() == 2 && key[0] == 'u' && key[1] >= 'x' && key[1] <= 'z')
      return x_[key[1] - 'x'] - ref_[key[1] - 'x'];
    return ComputeStyle::value(key);
  }

 private:
  int base_ = 0;
  shell::Stencil mask_;
  Vec3 ref_ = Vec3::Zero(), x_ = Vec3::Zero();
};

}  // namespace slender

SLENDER_REGISTER_STYLE(slender::ComputeStyle, "limit_point", slender::LimitPointCompute)
