#include "schedule.hpp"

#include <algorithm>
#include <chrono>

#include "context.hpp"

namespace slender {

void Schedule::build(const std::vector<ShellStyle*>& shells, const std::vector<BondStyle*>& bonds,
                     const std::vector<PairStyle*>& pairs, const std::vector<FixStyle*>& fixes,
                     Constraints constraints) {
  std::vector<Call> old;
  old.swap(calls_);
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
  for (Call& c : calls_)
    for (const Call& o : old)
      if (o.stage == c.stage && o.style() == c.style()) c.seconds = o.seconds;
  constraints_ = std::move(constraints);
}

namespace {
double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
}  // namespace

void Schedule::forces(Simulation& sim, std::map<std::string, double>& energy) const {
  double ext = 0.0;
  Context& ctx = sim.context();
  for (const Call& c : calls_) {
    if (c.stage != Stage::kForce && c.stage != Stage::kPostForce) continue;
    const auto t0 = std::chrono::steady_clock::now();
    if (c.stage == Stage::kForce) {
      if (c.shell) c.shell->compute(ctx);
      if (c.bond) energy[c.bond->energy_category()] += c.bond->compute(ctx);
      if (c.pair) energy["contact"] += c.pair->compute(ctx);
    } else {
      ext += c.fix->post_force(ctx);
    }
    c.seconds += seconds_since(t0);
  }
  energy["external"] += ext;
}

void Schedule::end_of_step(Simulation& sim) const {
  for (const Call& c : calls_)
    if (c.stage == Stage::kEndOfStep) {
      const auto t0 = std::chrono::steady_clock::now();
      c.fix->end_of_step(sim.context());
      c.seconds += seconds_since(t0);
    }
}

std::vector<std::pair<std::string, double>> Schedule::timings() const {
  std::vector<std::pair<std::string, double>> out;
  for (const Call& c : calls_) {
    std::string name = c.label();
    name = name.substr(0, name.rfind(" ["));
    if (c.stage == Stage::kEndOfStep) name += " (end of step)";
    out.emplace_back(name, c.seconds);
  }
  return out;
}

void Schedule::reset_timings() {
  for (Call& c : calls_) c.seconds = 0.0;
}

std::vector<const FixStyle*> Schedule::post_force_fixes() const {
  std::vector<const FixStyle*> out;
  for (const Call& c : calls_)
    if (c.stage == Stage::kPostForce) out.push_back(c.fix);
  return out;
}

const Style* Schedule::Call::style() const {
  return shell  ? static_cast<const Style*>(shell)
         : bond ? static_cast<const Style*>(bond)
         : pair ? static_cast<const Style*>(pair)
                : static_cast<const Style*>(fix);
}

std::string Schedule::Call::label() const {
  const Style* s = style();
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
