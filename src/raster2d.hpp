// A pixel image of 2D wires inside a circular cavity, shared by the loop count and
// the fractal dimension (docs/models.md §2.7): the wire is drawn as a thick line through
// its nodes, every wire pixel remembers which wire and arclength it belongs to, and
// pixels outside the cavity are marked as wall.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "simulation.hpp"

namespace slender {

class WireRaster {
 public:
  enum : std::uint8_t { kEmpty = 0, kWire = 1, kWall = 2 };

  // A square grid of pixel size `pixel` covering the disc of radius `radius`.
  WireRaster(const Vec3& center, double radius, double pixel);

  // Back to the empty cavity (wall only), keeping the memory: a compute evaluated at every
  // thermo row reuses one image instead of allocating and masking a new one (the fresh
  // pages and the circle test were ~15 % of a crumpling run, docs/performance.md).
  void clear() { state_ = empty_; }
  // The image kept in `img`, cleared, or made on first use.
  static WireRaster& reuse(std::optional<WireRaster>& img, const Vec3& center, double radius,
                           double pixel) {
    if (img)
      img->clear();
    else
      img.emplace(center, radius, pixel);
    return *img;
  }

  // Draws the polyline `pts` (consecutive points joined; `closed` joins the last to
  // the first) with half-width `half_width`; wire pixels store the arclength of the
  // nearest point of the nearest wire, offset by `s_offset` (so that separate
  // wires never share an arclength interval).
  void draw(const std::vector<Vec3>& pts, bool closed, double half_width, double s_offset);

  // Draws every chain of the scene; returns for each chain its [start, end)
  // arclength range in the image and whether it is closed.
  struct ChainRange {
    double s0, s1;
    bool closed;
  };
  std::vector<ChainRange> draw_chains(const Simulation& sim,
                                      const std::vector<const Chain*>& chains, double half_width);

  int size() const { return n_; }
  double pixel() const { return h_; }
  std::uint8_t state(int i, int j) const { return state_[index(i, j)]; }
  double arclength(int i, int j) const { return s_[index(i, j)]; }
  // centre of pixel (i, j)
  double px(int i) const { return x0_ + (i + 0.5) * h_; }
  double py(int j) const { return y0_ + (j + 0.5) * h_; }
  std::size_t index(int i, int j) const { return static_cast<std::size_t>(j) * n_ + i; }
  const std::vector<std::uint8_t>& states() const { return state_; }
  const std::vector<double>& arclengths() const { return s_; }

 private:
  double h_, x0_, y0_;
  int n_;
  std::vector<std::uint8_t> state_;
  std::vector<std::uint8_t> empty_;  // the cavity with nothing drawn: state_ after construction
  // Read only where state_ is kWire, i.e. written by a draw since the last clear(): left
  // as they were by clear()
  std::vector<double> s_;
  std::vector<float> d2_;  // squared distance to the nearest wire point drawn so far
};

}  // namespace slender
