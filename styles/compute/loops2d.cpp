// Loops of a 2D wire in a circular cavity (docs/models.md §2.7): a loop is an empty area
// enclosed by one stretch of wire whose two ends touch, "an area enclosed by a wire
// segment with only one inner contact". The wire is rastered with line width d (a
// little wider, so that touching wires close the gap between them); the connected
// empty regions that do not reach the cavity wall are labelled, and a region is a
// loop when the wire around it is one contiguous arclength interval [s_a, s_b]:
// then its only closure is the contact neck between s_a and s_b, an edge of the
// wire's contact graph. Regions bounded by several wire stretches (the voids of a
// packing, areas closed by two contacts) are holes but not loops; regions reaching
// the wall are neither.
#include <algorithm>
#include <cmath>
#include <numeric>

#include "chain_select.hpp"
#include "raster2d.hpp"
#include "registry.hpp"

namespace slender {

class Loops2dCompute : public ComputeStyle {
 public:
  static ParamSpec spec(const std::string& name) {
    ParamSpec s("compute", name,
                "loops of a 2D wire in a circular cavity: enclosed empty regions bounded by one "
                "contiguous stretch of wire closed by one contact neck (docs/models.md §2.7)");
    s.real("radius", "cavity radius r").required().positive();
    s.vector("center", "cavity centre").def(std::vector<double>{0, 0}).length(2, 3);
    s.real("diameter", "wire diameter d (line width of the image)").def(1.0).positive();
    s.real("pixel", "pixel size in units of d").def(0.25).positive();
    s.real("neck_tolerance",
           "wires closer than d (1 + tolerance) close a neck (the image's line width)")
        .def(0.1)
        .min(0.0);
    s.real("gap", "largest arclength gap within one boundary interval, in units of d")
        .def(1.0)
        .positive();
    s.real("min_area", "smallest loop area, in units of d^2 (smaller regions are voids)")
        .def(M_PI / 4)
        .min(0.0);
    s.add("chains", ParamType::StringList, "chains to analyse (default: all)")
        .def(std::vector<std::string>{});
    s.output("loops",
             "number of loops: enclosed regions bounded by one contiguous stretch of wire");
    s.output("holes",
             "number of enclosed empty regions off the wall of at least min_area (loops included)");
    s.output("loop_area", "total area of the loops");
    s.output("mean_loop_length", "mean wire arclength around a loop (0 without loops)");
    s.output("max_loop_length", "largest wire arclength around a loop");
    return s;
  }
  Loops2dCompute(Simulation& sim, const ParamValues& p)
      : r_(p.real("radius")),
        c_(p.vec3("center")),
        d_(p.real("diameter")),
        pixel_(p.real("pixel") * d_),
        half_width_(0.5 * d_ * (1.0 + p.real("neck_tolerance"))),
        gap_(p.real("gap") * d_),
        min_area_(p.real("min_area") * d_ * d_),
        names_(p.strings("chains")) {
    if (sim.dimension() != 2) throw InputError("compute style 'loops2d' needs a 2D simulation");
    if (pixel_ > 0.5 * d_) throw InputError("pixel must be at most d/2 to resolve the wire");
    select_chains(sim, names_);
  }

  void evaluate(Simulation& sim) override {
    if (sim.step == step_ && sim.state_epoch == epoch_ && sim.time == time_) return;
    step_ = sim.step;
    epoch_ = sim.state_epoch;
    time_ = sim.time;
    WireRaster& img = WireRaster::reuse(img_, c_, r_, pixel_);
    const auto ranges = img.draw_chains(sim, select_chains(sim, names_), half_width_);
    count(img, ranges);
  }

  double value(const std::string& key) const override {
    if (key == "loops") return loops_;
    if (key == "holes") return holes_;
    if (key == "loop_area") return area_;
    if (key == "mean_loop_length") return loops_ > 0 ? length_sum_ / loops_ : 0.0;
    if (key == "max_loop_length") return length_max_;
    return ComputeStyle::value(key);
  }

 private:
  void count(const WireRaster& img, const std::vector<WireRaster::ChainRange>& ranges) {
    loops_ = holes_ = area_ = length_sum_ = length_max_ = 0.0;
    const int n = img.size();
    const auto& state = img.states();
    const auto& sval = img.arclengths();
    // the regions' pixels seen so far (kept between evaluations: no fresh pages per row)
    std::vector<std::uint8_t>& seen = seen_;
    seen.assign(state.size(), 0);
    std::vector<int>& stack = stack_;
    std::vector<double>& boundary = boundary_;
    const double pixel_area = pixel_ * pixel_;
    for (std::size_t seed = 0; seed < state.size(); ++seed) {
      if (state[seed] != WireRaster::kEmpty || seen[seed]) continue;
      // flood fill one empty region (4-connected: a diagonal step cannot slip
      // through a neck)
      bool wall = false;
      long npix = 0;
      boundary.clear();
      stack.assign(1, static_cast<int>(seed));
      seen[seed] = 1;
      while (!stack.empty()) {
        const int idx = stack.back();
        stack.pop_back();
        ++npix;
        const int i = idx % n, j = idx / n;
        const int nb[4][2] = {{i - 1, j}, {i + 1, j}, {i, j - 1}, {i, j + 1}};
        for (auto& q : nb) {
          if (q[0] < 0 || q[1] < 0 || q[0] >= n || q[1] >= n) {
            wall = true;
            continue;
          }
          const int k = q[1] * n + q[0];
          if (state[k] == WireRaster::kWall) {
            wall = true;
          } else if (state[k] == WireRaster::kWire) {
            boundary.push_back(sval[k]);
          } else if (!seen[k]) {
            seen[k] = 1;
            stack.push_back(k);
          }
        }
      }
      const double area = npix * pixel_area;
      if (wall || area < min_area_ || boundary.empty()) continue;
      holes_ += 1;
      double length = 0.0;
      if (one_interval(boundary, ranges, length)) {
        loops_ += 1;
        area_ += area;
        length_sum_ += length;
        length_max_ = std::max(length_max_, length);
      }
    }
  }

  // Whether the arclengths `s` of the wire around a region form one interval with
  // no gap larger than gap_ (on a closed chain the interval may wrap round);
  // `length` is its extent.
  bool one_interval(std::vector<double>& s, const std::vector<WireRaster::ChainRange>& ranges,
                    double& length) const {
    std::sort(s.begin(), s.end());
    int gaps = 0;
    double largest = 0.0;
    for (std::size_t k = 1; k < s.size(); ++k) {
      const double g = s[k] - s[k - 1];
      if (g > gap_) ++gaps;
      largest = std::max(largest, g);
    }
    if (gaps == 0) {
      length = s.back() - s.front();
      return true;
    }
    // a closed chain: the boundary may run through its start; one gap then splits
    // the ring into the boundary and the rest
    if (gaps == 1)
      for (auto& r : ranges)
        if (r.closed && s.front() >= r.s0 && s.back() <= r.s1 &&
            (s.front() - r.s0) + (r.s1 - s.back()) <= gap_) {
          length = (r.s1 - r.s0) - largest;
          return true;
        }
    return false;
  }

  double r_;
  Vec3 c_;
  double d_, pixel_, half_width_, gap_, min_area_;
  std::vector<std::string> names_;
  std::optional<WireRaster> img_;  // one image, cleared and redrawn at each evaluation
  std::vector<std::uint8_t> seen_;
  std::vector<int> stack_;
  std::vector<double> boundary_;
  long step_ = -1, epoch_ = -1;
  double time_ = -1.0;
  double loops_ = 0, holes_ = 0, area_ = 0, length_sum_ = 0, length_max_ = 0;
};

}  // namespace slender

SLENDER_REGISTER_STYLE(slender::ComputeStyle, "loops2d", slender::Loops2dCompute)
