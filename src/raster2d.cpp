#include "raster2d.hpp"

#include <algorithm>
#include <cmath>

#include "params.hpp"

namespace slender {

WireRaster::WireRaster(const Vec3& center, double radius, double pixel) : h_(pixel) {
  if (!(pixel > 0) || !(radius > 0)) throw InputError("raster: pixel and radius must be > 0");
  // one spare pixel of wall on each side, so every region inside sees the wall
  n_ = static_cast<int>(std::ceil(2 * radius / pixel)) + 2;
  if (n_ > 20000)
    throw InputError("raster: " + std::to_string(n_) + "^2 pixels; use a larger pixel size");
  x0_ = center.x() - 0.5 * n_ * h_;
  y0_ = center.y() - 0.5 * n_ * h_;
  const std::size_t np = static_cast<std::size_t>(n_) * n_;
  state_.assign(np, kEmpty);
  s_.assign(np, 0.0);
  d2_.assign(np, 0.0f);
  const double r2 = radius * radius;
  for (int j = 0; j < n_; ++j)
    for (int i = 0; i < n_; ++i) {
      const double dx = px(i) - center.x(), dy = py(j) - center.y();
      if (dx * dx + dy * dy >= r2) state_[index(i, j)] = kWall;
    }
  empty_ = state_;
}

void WireRaster::draw(const std::vector<Vec3>& pts, bool closed, double half_width,
                      double s_offset) {
  const std::size_t np = pts.size();
  const std::size_t ns = closed ? np : (np ? np - 1 : 0);
  const double w2 = half_width * half_width;
  double s = s_offset;
  for (std::size_t k = 0; k < ns; ++k) {
    const Vec3& a = pts[k];
    const Vec3& b = pts[(k + 1) % np];
    const double ex = b.x() - a.x(), ey = b.y() - a.y();
    const double len2 = ex * ex + ey * ey, len = std::sqrt(len2);
    const int i0 =
        std::max(0, static_cast<int>(std::floor((std::min(a.x(), b.x()) - half_width - x0_) / h_)));
    const int i1 = std::min(
        n_ - 1, static_cast<int>(std::floor((std::max(a.x(), b.x()) + half_width - x0_) / h_)));
    const int j0 =
        std::max(0, static_cast<int>(std::floor((std::min(a.y(), b.y()) - half_width - y0_) / h_)));
    const int j1 = std::min(
        n_ - 1, static_cast<int>(std::floor((std::max(a.y(), b.y()) + half_width - y0_) / h_)));
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        const std::size_t idx = index(i, j);
        if (state_[idx] == kWall) continue;  // the wall is never wire
        const double qx = px(i) - a.x(), qy = py(j) - a.y();
        const double t = len2 > 0 ? std::clamp((qx * ex + qy * ey) / len2, 0.0, 1.0) : 0.0;
        const double dx = qx - t * ex, dy = qy - t * ey;
        const double d2 = dx * dx + dy * dy;
        if (d2 >= w2) continue;
        if (state_[idx] == kWire && d2 >= d2_[idx]) continue;
        state_[idx] = kWire;
        d2_[idx] = static_cast<float>(d2);
        s_[idx] = s + t * len;
      }
    s += len;
  }
}

std::vector<WireRaster::ChainRange> WireRaster::draw_chains(const Simulation& sim,
                                                            const std::vector<const Chain*>& chains,
                                                            double half_width) {
  std::vector<ChainRange> out;
  double offset = 0.0;
  std::vector<Vec3> pts;
  for (auto* c : chains) {
    pts.clear();
    for (int i : c->nodes) pts.push_back(sim.nodes().x[i]);
    double len = 0.0;
    const std::size_t ns = c->closed ? pts.size() : (pts.empty() ? 0 : pts.size() - 1);
    for (std::size_t k = 0; k < ns; ++k) len += (pts[(k + 1) % pts.size()] - pts[k]).norm();
    draw(pts, c->closed, half_width, offset);
    out.push_back({offset, offset + len, c->closed});
    // a gap far larger than any tolerance keeps chains apart in arclength
    offset += len + 1e6 * (1.0 + half_width);
  }
  return out;
}

}  // namespace slender
