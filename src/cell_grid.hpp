// Linked cells shared by the contact pair styles (docs/models.md §2.3, §5.1): items
// (nodes, edge midpoints) are binned by a counting sort into a uniform grid over
// a bounding box, and a query visits the items of the 3^dim cells around a point.
// The same grid serves 2D (one layer of cells) and 3D.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "context.hpp"
#include "nodes.hpp"
#include "params.hpp"

namespace slender {

// When a contact pair list (pairs within the cut-off plus a skin) must be rebuilt:
// every N steps if asked, else as soon as some node moved more than skin/2 since
// the last build, so no pair can come into contact unlisted (docs/models.md §2.3, §5.1).
class RebuildSchedule {
 public:
  static void declare(ParamSpec& s, const std::string& skin_help) {
    s.real("skin", skin_help).def(1.0).positive();
    s.integer("rebuild_every", "rebuild the pair list every N steps (0: when a node moved skin/2)")
        .def(0.0)
        .min(0);
  }
  explicit RebuildSchedule(const ParamValues& p)
      : skin_(p.real("skin")), every_(p.integer("rebuild_every")) {}
  double skin() const { return skin_; }
  // Whether the list must be rebuilt now; the scene's neighbour service decides for all
  // lists at once (src/neighbors.hpp). `force`: this list must be rebuilt (its chains were
  // re-bound, a rollback): every list is.
  bool due(Context& sim, bool force) {
    auto& service = sim.neighbors();
    // rebuild_every replaces the displacement criterion (the skin still sizes the list)
    if (handle_ < 0) handle_ = service.request(this, every_ > 0 ? 0.0 : skin_, every_);
    if (force) service.invalidate();
    return service.due(handle_, sim.nodes().x, sim.step());
  }
  void built(Context& sim) {
    sim.neighbors().built(handle_, sim.step());
    builds_ += 1;
  }
  double builds() const { return builds_; }
  void save(StateMap& st) const { st["counters"] = {builds_, 0.0}; }
  void load(const StateMap& st) { builds_ = saved_array(st, "counters", 1)[0]; }

 private:
  double skin_;
  long every_;
  int handle_ = -1;
  double builds_ = 0;
};

class CellGrid {
 public:
  // Bins the items at `pos` into cells of size `cell` over the box [lo, hi]
  // (points outside fall into the border cells); `dim` is 2 or 3.
  void build(const Vec3& lo, const Vec3& hi, double cell, int dim, const std::vector<Vec3>& pos) {
    lo_ = lo;
    cs_ = cell;
    dim_ = dim;
    // at most a few cells per item: one node flung far away (a divergence the guard has yet
    // to see) must not make the grid allocate gigabytes (found by fuzzing). A scene wider
    // than that gets larger cells; an infinite extent, the cells a cube root of the cap
    // allows (items beyond the last cell fall into it: points within a cell size of each
    // other still lie in neighbouring cells, so the search stays correct)
    const double cap = std::max(1048576.0, 8.0 * static_cast<double>(pos.size()));
    const int per_axis = std::max(1, static_cast<int>(std::pow(cap, 1.0 / dim)));
    auto count = [&](int a, int top) {
      const double e = (hi[a] - lo[a]) / cs_;
      return std::isfinite(e) ? clamped_cell(e, top - 1) + 1 : per_axis;
    };
    auto cells = [&](int top) {
      for (int a = 0; a < 3; ++a) n_[a] = a < dim ? count(a, top) : 1;
      return static_cast<double>(n_[0]) * n_[1] * n_[2];
    };
    const double total = cells(1 << 14);
    if (total > cap) {
      cs_ *= 1.0001 * std::pow(total / cap, 1.0 / dim);
      if (cells(1 << 14) > cap) cells(per_axis);
    }
    const std::size_t ncell = static_cast<std::size_t>(n_[0]) * n_[1] * n_[2];
    start_.assign(ncell + 1, 0);
    item_cell_.resize(pos.size());
    for (std::size_t k = 0; k < pos.size(); ++k) {
      item_cell_[k] = cell_index(pos[k]);
      ++start_[static_cast<std::size_t>(item_cell_[k]) + 1];
    }
    for (std::size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
    items_.resize(pos.size());
    fill_ = start_;
    for (std::size_t k = 0; k < pos.size(); ++k)
      items_[static_cast<std::size_t>(fill_[static_cast<std::size_t>(item_cell_[k])]++)] =
          static_cast<int>(k);
  }

  // Calls f(item) for every item above `first` in the cells around p: each pair of items
  // once when item `first` searches around itself. The items of a cell are stored in
  // ascending order (build), so the ones at or below `first` are skipped by one binary
  // search per cell.
  template <class F>
  void for_each_near_above(const Vec3& p, int first, F&& f) const {
    int c[3];
    coords(p, c);
    const int zr = dim_ == 3 ? 1 : 0;
    for (int dz = -zr; dz <= zr; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int gx = c[0] + dx, gy = c[1] + dy, gz = c[2] + dz;
          if (gx < 0 || gy < 0 || gz < 0 || gx >= n_[0] || gy >= n_[1] || gz >= n_[2]) continue;
          const std::size_t cell = (static_cast<std::size_t>(gz) * n_[1] + gy) * n_[0] + gx;
          const int* begin = items_.data() + start_[cell];
          const int* end = items_.data() + start_[cell + 1];
          for (const int* k = std::upper_bound(begin, end, first); k < end; ++k) f(*k);
        }
  }

  // Calls f(item) for every item in the cells around p (z outermost, then y, x).
  template <class F>
  void for_each_near(const Vec3& p, F&& f) const {
    int c[3];
    coords(p, c);
    const int zr = dim_ == 3 ? 1 : 0;
    for (int dz = -zr; dz <= zr; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int gx = c[0] + dx, gy = c[1] + dy, gz = c[2] + dz;
          if (gx < 0 || gy < 0 || gz < 0 || gx >= n_[0] || gy >= n_[1] || gz >= n_[2]) continue;
          const std::size_t cell = (static_cast<std::size_t>(gz) * n_[1] + gy) * n_[0] + gx;
          for (int k = start_[cell]; k < start_[cell + 1]; ++k)
            f(items_[static_cast<std::size_t>(k)]);
        }
  }

 private:
  // floor(v) within [0, top], clamped before the cast: a node flung far away (or a NaN the
  // guard has yet to see, found by fuzzing) lands in a border cell, never in undefined
  // behaviour
  static int clamped_cell(double v, int top) {
    if (!(v >= 0.0)) return 0;
    return v >= static_cast<double>(top) ? top : static_cast<int>(v);
  }
  void coords(const Vec3& p, int c[3]) const {
    for (int a = 0; a < 3; ++a)
      c[a] = a < dim_ ? clamped_cell((p[a] - lo_[a]) / cs_, n_[a] - 1) : 0;
  }
  int cell_index(const Vec3& p) const {
    int c[3];
    coords(p, c);
    return (c[2] * n_[1] + c[1]) * n_[0] + c[0];
  }

  Vec3 lo_ = Vec3::Zero();
  double cs_ = 1.0;
  int dim_ = 2;
  int n_[3] = {1, 1, 1};
  std::vector<int> start_, fill_, items_, item_cell_;
};

}  // namespace slender
