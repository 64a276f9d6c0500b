// Fractal dimension of a 2D wire by the mass-radius (sandbox) method (docs/models.md
// §2.7): the wire is rastered with line width d; M(rho) is the number of wire
// pixels within rho of a centre on the wire; D is the slope of log <M> against
// log rho, <M> averaged over centres. Centres are wire nodes far enough inside the
// cavity that the largest circle stays off the wall; they are spread evenly along
// the wire. The spread of the per-centre slopes gives an uncertainty.
#include <algorithm>
#include <cmath>

#include "chain_select.hpp"
#include "raster2d.hpp"
#include "registry.hpp"

namespace slender {

namespace {
// least-squares slope of y against x
double slope(const std::vector<double>& x, const std::vector<double>& y) {
  const double n = static_cast<double>(x.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    sx += x[k];
    sy += y[k];
    sxx += x[k] * x[k];
    sxy += x[k] * y[k];
  }
  const double den = n * sxx - sx * sx;
  return den > 0 ? (n * sxy - sx * sy) / den : 0.0;
}
}  // namespace

class Fractal2dCompute : public ComputeStyle {
 public:
  static ParamSpec spec(const std::string& name) {
    ParamSpec s("compute", name,
                "fractal dimension of a 2D wire by the mass-radius (sandbox) method on a raster "
                "image of line width d (docs/models.md §2.7)");
    s.real("radius", "cavity radius r").required().positive();
    s.vector("center", "cavity centre").def(std::vector<double>{0, 0}).length(2, 3);
    s.real("diameter", "wire diameter d (line width of the image)").def(1.0).positive();
    s.real("pixel", "pixel size in units of d").def(0.25).positive();
    s.real("rho_min", "smallest sandbox radius, in units of d").def(2.0).positive();
    s.real("rho_max", "largest sandbox radius, as a fraction of r").def(0.3).positive().max(1.0);
    s.integer("radii", "number of log-spaced radii").def(12.0).min(3).max(1000);
    s.integer("centres", "largest number of centres").def(64.0).min(1).max(1000000);
    s.add("chains", ParamType::StringList, "chains to analyse (default: all)")
        .def(std::vector<std::string>{});
    s.output("D", "fractal dimension: slope of log <M> against log rho, M averaged over centres");
    s.output("D_err", "standard error of D from the spread of the per-centre slopes");
    s.output("centres", "number of centres used (0 when no node is far enough inside)");
    return s;
  }
  Fractal2dCompute(Simulation& sim, const ParamValues& p)
      : r_(p.real("radius")),
        c_(p.vec3("center")),
        d_(p.real("diameter")),
        pixel_(p.real("pixel") * d_),
        rho_min_(p.real("rho_min") * d_),
        rho_max_(p.real("rho_max") * r_),
        n_radii_(static_cast<int>(p.integer("radii"))),
        n_centres_(static_cast<int>(p.integer("centres"))),
        names_(p.strings("chains")) {
    if (sim.dimension() != 2) throw InputError("compute style 'fractal2d' needs a 2D simulation");
    if (pixel_ > 0.5 * d_) throw InputError("pixel must be at most d/2 to resolve the wire");
    if (rho_max_ <= rho_min_)
      throw InputError("rho_max * radius (" + std::to_string(rho_max_) +
                       ") must exceed rho_min * diameter (" + std::to_string(rho_min_) + ")");
    select_chains(sim, names_);
    for (int k = 0; k < n_radii_; ++k)
      rho_.push_back(rho_min_ * std::pow(rho_max_ / rho_min_, k / (n_radii_ - 1.0)));
    for (double r : rho_) rho2_.push_back(r * r);
  }

  void evaluate(Simulation& sim) override {
    if (sim.step == step_ && sim.state_epoch == epoch_ && sim.time == time_) return;
    step_ = sim.step;
    epoch_ = sim.state_epoch;
    time_ = sim.time;
    D_ = D_err_ = 0.0;
    centres_ = 0;
    auto chains = select_chains(sim, names_);
    WireRaster& img = WireRaster::reuse(img_, c_, r_, pixel_);
    img.draw_chains(sim, chains, 0.5 * d_);

    // eligible centres: nodes whose largest circle stays inside the cavity
    std::vector<Vec3> eligible;
    for (auto* c : chains)
      for (int i : c->nodes) {
        const Vec3& x = sim.nodes().x[i];
        if ((x - c_).head<2>().norm() + rho_max_ <= r_) eligible.push_back(x);
      }
    if (eligible.empty()) return;
    const int nc = std::min<int>(n_centres_, static_cast<int>(eligible.size()));
    std::vector<double> mean(n_radii_, 0.0), logr(n_radii_), slopes;
    for (int k = 0; k < n_radii_; ++k) logr[k] = std::log(rho_[k]);
    std::vector<double> m(n_radii_), logm(n_radii_);
    const double h = img.pixel();
    const int n = img.size();
    // wire pixels counted by rows: row_count_[j (n + 1) + i] = wire pixels (0 .. i-1, j).
    // A disc's mass is then a sum over its rows of one difference each, instead of a test
    // of every pixel of its bounding square (that scan was most of the thermo rows' cost
    // in a crumpling run: 8 % of the run at f = 30, docs/performance.md)
    row_count_.resize(static_cast<std::size_t>(n) * (n + 1));
    for (int j = 0; j < n; ++j) {
      int* row = &row_count_[static_cast<std::size_t>(j) * (n + 1)];
      row[0] = 0;
      for (int i = 0; i < n; ++i) row[i + 1] = row[i] + (img.state(i, j) == WireRaster::kWire);
    }
    for (int q = 0; q < nc; ++q) {
      const Vec3& x = eligible[(static_cast<std::size_t>(q) * eligible.size()) / nc];
      std::fill(m.begin(), m.end(), 0.0);
      const int j0 = std::max(0, static_cast<int>(std::floor((x.y() - rho_max_ - img.py(0)) / h)));
      const int j1 =
          std::min(n - 1, static_cast<int>(std::ceil((x.y() + rho_max_ - img.py(0)) / h)));
      const double ic = (x.x() - img.px(0)) / h;  // the centre's column, fractional
      for (int j = j0; j <= j1; ++j) {
        const double dy = img.py(j) - x.y();
        const int* row = &row_count_[static_cast<std::size_t>(j) * (n + 1)];
        for (int k = 0; k < n_radii_; ++k) {
          // pixel (i, j) lies in the disc of radius rho_k when its squared distance, computed
          // as the pixel test always did, is at most rho_k^2; in a row that holds for one
          // interval of i, found from the root and then settled by the test itself
          auto inside = [&](int i) {
            const double dx = img.px(i) - x.x();
            return dx * dx + dy * dy <= rho2_[k];
          };
          if (dy * dy > rho2_[k]) continue;
          const double half = std::sqrt(rho2_[k] - dy * dy) / h;
          int lo = std::clamp(static_cast<int>(std::ceil(ic - half)), 0, n - 1);
          int hi = std::clamp(static_cast<int>(std::floor(ic + half)), 0, n - 1);
          while (lo > 0 && inside(lo - 1)) --lo;
          while (lo <= hi && !inside(lo)) ++lo;
          while (hi < n - 1 && inside(hi + 1)) ++hi;
          while (hi >= lo && !inside(hi)) --hi;
          if (lo <= hi) m[k] += row[hi + 1] - row[lo];
        }
      }
      for (int k = 0; k < n_radii_; ++k) {
        mean[k] += m[k] / nc;
        logm[k] = std::log(std::max(m[k], 1.0));
      }
      slopes.push_back(slope(logr, logm));
    }
    for (auto& v : mean) v = std::log(std::max(v, 1e-300));
    D_ = slope(logr, mean);
    centres_ = nc;
    double avg = 0, var = 0;
    for (double s : slopes) avg += s / nc;
    for (double s : slopes) var += (s - avg) * (s - avg);
    D_err_ = nc > 1 ? std::sqrt(var / (nc - 1) / nc) : 0.0;
  }

  double value(const std::string& key) const override {
    if (key == "D") return D_;
    if (key == "D_err") return D_err_;
    if (key == "centres") return centres_;
    return ComputeStyle::value(key);
  }

 private:
  double r_;
  Vec3 c_;
  double d_, pixel_, rho_min_, rho_max_;
  int n_radii_, n_centres_;
  std::vector<std::string> names_;
  std::vector<double> rho_, rho2_;
  std::optional<WireRaster> img_;  // one image, cleared and redrawn at each evaluation
  std::vector<int> row_count_;     // its wire pixels counted along each row (kept: no fresh pages)
  long step_ = -1, epoch_ = -1;
  double time_ = -1.0;
  double D_ = 0, D_err_ = 0, centres_ = 0;
};

}  // namespace slender

SLENDER_REGISTER_STYLE(slender::ComputeStyle, "fractal2d", slender::Fractal2dCompute)
