#include "schedule.hpp"

#include <algorithm>

#include "context.hpp"

namespace slender {

void Schedule::build(const std::vector<ShellStyle*>& shells, const std::vector<BondStyle*>& bonds,
                     const std::vector<PairStyle*>& pairs, const std::vector<FixStyle*>& fixes,
                     Constraints constraints) {
  calls_.clear();
  for (auto* s : shells) calls_.push_back(Call{Stage::kForce, s->priority(), s});
  for (auto* b : bonds) calls_.push_back(Call{Stage::kForce, b->priority(), nullptr, b});
  for (auto* p : pairs) calls_.push_back(Call{Stage::kForce, p->priority(), nullptr, nullptr, p});
  for (auto* f : fixes) {
    if (f->stages() & kPostForce)
      calls_.push_back(Call{Stage::kPostForce, f->priority(), nullptr, nullptr, nullptr, f});
    if (f->stages() & kEndOfStep)
      calls_.push_back(Call{Stage::kEndOfStep, f->priority(), nullptr, nullptr, nullptr, f});
  }
  // stable: equal priorities keep the deck's order within a family, and the families'
  // order (shells, bonds, pairs) where priorities tie across them
  std::stable_sort(calls_.begin(), calls_.end(), [](const Call& a, const Call& b) {
    if (a.stage != b.stage) return a.stage < b.stage;
    return a.priority < b.priority;
  });
  constraints_ = std::move(constraints);
}

void Schedule::forces(Simulation& sim, std::map<std::string, double>& energy) const {
  double ext = 0.0;
  Context& ctx = sim.context();
  for (const Call& c : calls_) {
    if (c.stage == Stage::kForce) {
      if (c.shell) c.shell->compute(ctx);
      if (c.bond) energy[c.bond->energy_category()] += c.bond->compute(ctx);
      if (c.pair) energy["contact"] += c.pair->compute(ctx);
    } else if (c.stage == Stage::kPostForce) {
      ext += c.fix->post_force(ctx);
    }
  }
  energy["external"] += ext;
}

void Schedule::end_of_step(Simulation& sim) const {
  for (const Call& c : calls_)
    if (c.stage == Stage::kEndOfStep) c.fix->end_of_step(sim.context());
}

std::vector<const FixStyle*> Schedule::post_force_fixes() const {
  std::vector<const FixStyle*> out;
  for (const Call& c : calls_)
    if (c.stage == Stage::kPostForce) out.push_back(c.fix);
  return out;
}

std::string Schedule::Call::label() const {
  const Style* s = shell  ? static_cast<const Style*>(shell)
                   : bond ? static_cast<const Style*>(bond)
                   : pair ? static_cast<const Style*>(pair)
                          : static_cast<const Style*>(fix);
  const char* family = shell ? "shell" : bond ? "bond" : pair ? "pair" : "fix";
  std::string name = std::string(family) + " " + s->id();
  if (s->style_name() != s->id()) name += " (" + s->style_name() + ")";
  return name + " [" + std::to_string(priority) + "]";
}

std::string Schedule::describe() const {
  std::string out;
  auto stage = [&](Stage st, const char* title, std::vector<std::string> extra) {
    out += title;
    out += ":";
    bool any = false;
    for (const Call& c : calls_)
      if (c.stage == st) {
        out += (any ? "; " : " ") + c.label();
        any = true;
      }
    for (auto& e : extra) {
      out += (any ? "; " : " ") + e;
      any = true;
    }
    if (!any) out += " (none)";
    out += "\n";
  };
  stage(Stage::kForce, "force", {});
  stage(Stage::kPostForce, "post-force", {});
  std::vector<std::string> core;
  if (constraints_.dof_mask) core.push_back("clamped components (dof_mask)");
  if (constraints_.plane) core.push_back("2D plane");
  for (auto& c : constraints_.unit_coordinates) core.push_back("unit quaternions " + c);
  stage(Stage::kConstrain, "constrain", core);
  stage(Stage::kEndOfStep, "end of step", {});
  return out;
}

}  // namespace slender
