// Number of wings of a grown disc (docs/models.md §6.11): the height of the rim
// z(phi) - mean, resampled at `samples` equally spaced angles by linear
// interpolation, transformed with FFTW (real to complex); n is the mode >= 2 with
// the largest amplitude (n = 1 is a rigid tilt of a free disc).
#ifdef SLENDER_HAVE_FFTW
#include <fftw3.h>

#include <algorithm>
#include <cmath>

#include "registry.hpp"
#include "simulation.hpp"

namespace slender {

class RimModesCompute : public ComputeStyle {
 public:
  static ParamSpec spec(const std::string& name) {
    ParamSpec s("compute", name,
                "Fourier modes of the rim height of a disc (FFTW): the number of wings n");
    s.string("group", "rim nodes, e.g. disc.boundary").required();
    s.vector("center", "disc centre").def(std::vector<double>{0, 0, 0}).length(3, 3);
    s.integer("samples", "equally spaced angles of the resampled rim")
        .def(256.0)
        .min(8)
        .max(10000000);
    s.real("min_radius", "ignore group nodes closer to the axis (the inner edge of a ring)")
        .def(0.0)
        .nonnegative();
    s.output("n", "number of wings: the mode n >= 2 of largest amplitude");
    s.output("amplitude", "amplitude of mode n of the rim height");
    s.output("a1", "amplitude of mode 1 of the rim height (a rigid tilt)");
    s.output("a2", "amplitude of mode 2 of the rim height");
    s.output("a3", "amplitude of mode 3 of the rim height");
    s.output("a4", "amplitude of mode 4 of the rim height");
    return s;
  }
  RimModesCompute(Simulation& sim, const ParamValues& p)
      : group_(p.str("group")),
        c_(p.vec3("center")),
        m_(static_cast<int>(p.integer("samples"))),
        rmin_(p.real("min_radius")) {
    sim.group(group_);
  }
  void evaluate(Simulation& sim) override {
    std::vector<std::pair<double, double>> pts;  // (angle, height)
    for (int i : sim.group(group_)) {
      const Vec3 r = sim.nodes().x[i] - c_;
      if (std::hypot(r.x(), r.y()) < rmin_) continue;
      pts.push_back({std::atan2(r.y(), r.x()), r.z()});
    }
    if (pts.size() < 4)
      throw InputError("compute 'rim_modes': group '" + group_ + "' has < 4 nodes");
    std::sort(pts.begin(), pts.end());
    std::vector<double> z(m_);
    const std::size_t n = pts.size();
    for (int k = 0; k < m_; ++k) {
      const double a = -M_PI + 2 * M_PI * k / m_;
      std::size_t j =
          std::upper_bound(pts.begin(), pts.end(), std::make_pair(a, -1e300)) - pts.begin();
      const auto& hi = pts[j % n];
      const auto& lo = pts[(j + n - 1) % n];
      double a0 = lo.first, a1 = hi.first;
      if (j == 0) a0 -= 2 * M_PI;
      if (j == n) a1 += 2 * M_PI;
      const double s = a1 > a0 ? (a - a0) / (a1 - a0) : 0.0;
      z[k] = (1 - s) * lo.second + s * hi.second;
    }
    std::vector<fftw_complex> out(m_ / 2 + 1);
    fftw_plan plan = fftw_plan_dft_r2c_1d(m_, z.data(), out.data(), FFTW_ESTIMATE);
    fftw_execute(plan);
    fftw_destroy_plan(plan);
    amp_.assign(m_ / 2 + 1, 0.0);
    for (int k = 1; k <= m_ / 2; ++k) amp_[k] = 2.0 * std::hypot(out[k][0], out[k][1]) / m_;
    n_ = 0;
    for (int k = 2; k <= m_ / 2; ++k)
      if (n_ == 0 || amp_[k] > amp_[n_]) n_ = k;
  }
  double value(const std::string& key) const override {
    if (key == "n") return n_;
    if (key == "amplitude") return n_ ? amp_[n_] : 0.0;
    if (key.size() == 2 && key[0] == 'a' && key[1] >= '1' && key[1] <= '4') {
      const int k = key[1] - '0';
      return k < static_cast<int>(amp_.size()) ? amp_[k] : 0.0;
    }
    return ComputeStyle::value(key);
  }

 private:
  std::string group_;
  Vec3 c_;
  int m_;
  double rmin_;
  int n_ = 0;
  std::vector<double> amp_;
};

}  // namespace slender

SLENDER_REGISTER_STYLE(slender::ComputeStyle, "rim_modes", slender::RimModesCompute)
#endif
