// When the contact pair lists must be rebuilt, decided once per force evaluation for every
// list of the scene (the role of LAMMPS's Neighbor). A pair style registers a request (the
// skin of its list, or a fixed interval); the service keeps one copy of the positions at
// the last common build and scans the displacements once per evaluation for all requests.
// When one list is due, all are rebuilt together, so that one copy serves them all and no
// pair can come into contact unlisted (docs/models.md §2.3, §5.1): a list is valid while no node
// has moved more than half its skin since it was built.
//
// A scene without contact styles makes no request, holds no copy and scans nothing.
#pragma once

#include <algorithm>
#include <array>
#include <limits>
#include <vector>

#include "nodes.hpp"
#include "threads.hpp"

namespace slender {

class NeighborService {
 public:
  // Registers a list (once per owner; a later call updates its skin and interval). `skin`
  // > 0: rebuilt when a node moved more than skin/2; `every` > 0: rebuilt at least every that
  // many steps (either or both). Returns its handle.
  int request(const void* owner, double skin, long every) {
    for (std::size_t h = 0; h < req_.size(); ++h)
      if (req_[h].owner == owner) {
        req_[h].skin = skin;
        req_[h].every = every;
        return static_cast<int>(h);
      }
    req_.push_back(Request{owner, skin, every});
    return static_cast<int>(req_.size()) - 1;
  }
  // A new force evaluation on `threads` threads begins (Simulation::compute_forces): the
  // next query decides anew.
  void begin_evaluation(int threads = 1) {
    decided_ = false;
    threads_ = threads;
  }
  // Every list is rebuilt at the next query (a style re-bound its chains at a run's start
  // or after a chain grew, a guard rollback, a checkpoint read).
  void invalidate() {
    if (decided_ && rebuilt_now_) return;  // every list is rebuilt at these positions already
    force_ = true;
    decided_ = false;
  }
  // Whether list `handle` must be rebuilt before this evaluation, at positions `x` and clock
  // `step`.
  bool due(int handle, const std::vector<Vec3>& x, long step) {
    if (!decided_) decide(x, step);
    return req_[static_cast<std::size_t>(handle)].generation < generation_;
  }
  // List `handle` was rebuilt now.
  void built(int handle, long step) {
    auto& r = req_[static_cast<std::size_t>(handle)];
    r.generation = generation_;
    r.last = step;
  }
  std::size_t requests() const { return req_.size(); }
  // Common rebuilds decided so far, and displacement scans (at most one per evaluation).
  long rebuilds() const { return generation_; }
  long scans() const { return scans_; }

 private:
  struct Request {
    const void* owner;
    double skin;
    long every;
    long last = 0;         // step of its last build
    long generation = -1;  // the common build it was last rebuilt at
  };
  void decide(const std::vector<Vec3>& x, long step) {
    decided_ = true;
    rebuilt_now_ = false;
    bool all = force_ || x_.size() != x.size();
    double half_skin2 = std::numeric_limits<double>::infinity();
    for (auto& r : req_) {
      if (r.every > 0) all = all || step - r.last >= r.every;
      if (r.skin > 0) half_skin2 = std::min(half_skin2, 0.25 * r.skin * r.skin);
    }
    if (!all && half_skin2 < std::numeric_limits<double>::infinity()) {
      ++scans_;
      // on the threads' node ranges, as the kernels take them (threads.hpp)
      std::array<char, kMaxThreads> moved{};
      const int T = parallel_ranges(
          threads_, x.size(),
          [&](int tid, std::size_t b, std::size_t e) {
            bool any = false;
            for (std::size_t i = b; i < e && !any; ++i)
              any = (x[i] - x_[i]).squaredNorm() > half_skin2;
            moved[static_cast<std::size_t>(tid)] = any;
          },
          kMinLightItemsPerThread);
      for (int t = 0; t < T; ++t) all = all || moved[static_cast<std::size_t>(t)];
    }
    if (!all) return;
    ++generation_;
    x_ = x;
    force_ = false;
    rebuilt_now_ = true;
  }

  std::vector<Request> req_;
  std::vector<Vec3> x_;  // positions at the last common build
  long generation_ = 0;
  long scans_ = 0;
  bool decided_ = false, force_ = false, rebuilt_now_ = false;
  int threads_ = 1;
};

}  // namespace slender
