// Shared-memory threads for the force kernels and the integrators (OpenMP).
//
// Determinism: the work [0, n) is cut into one contiguous range per thread, always the
// same for the same thread count, and every sum across threads (forces, energies, counts)
// is taken in thread order. A run is therefore bit-identical to itself for a given thread
// count, and with one thread the kernels write straight into the force array in the
// serial order (bit-identical to the code before threads).
//
// No atomics on the hot path: a kernel that adds forces to nodes other than its own
// (bonds, pairs) writes them, on threads 1..T-1, into per-thread buffers that are added
// into the force array after the kernel (and zeroed in the same pass for the next one).
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <limits>
#include <utility>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "nodes.hpp"

namespace slender {

// Below this many work items per thread a kernel runs serially: the cost of waking the
// threads (a few microseconds) would exceed the work.
inline constexpr std::size_t kMinItemsPerThread = 256;
// The same for light passes over the nodes (a few flops per node: the integrator's
// updates, zeroing, the drag, the wall, the guard's scan). A parallel region costs
// 0.6 us on the 2-core development machine, a pass over 1 000 nodes about as much. (At
// 4096, with the hysteresis hinges' false sharing removed, two threads ran a crumpling
// stretch at 2 500-2 800 nodes 15 % slower than at 1024: docs/performance.md, "Threads
// that pay at 2 000-4 000 nodes".)
inline constexpr std::size_t kMinLightItemsPerThread = 1024;
// A scene smaller than this runs on one thread (Simulation::threads_min_nodes; measured,
// docs/performance.md "Threads"). SLENDER_THREADS_MIN_NODES overrides it.
inline constexpr std::size_t kThreadsMinNodes = 2000;
// The most threads a simulation takes.
inline constexpr int kMaxThreads = 64;

// The range of work items thread `tid` of `threads` takes out of [0, n).
inline void thread_range(std::size_t n, int threads, int tid, std::size_t& begin,
                         std::size_t& end) {
  const std::size_t T = static_cast<std::size_t>(threads), t = static_cast<std::size_t>(tid);
  begin = n * t / T;
  end = n * (t + 1) / T;
}

// How many threads a kernel of n items uses out of the simulation's `threads`, at least
// `grain` items each.
inline int threads_for(std::size_t n, int threads, std::size_t grain = kMinItemsPerThread) {
#ifdef _OPENMP
  const std::size_t most = std::max<std::size_t>(1, n / grain);
  return static_cast<int>(
      std::min<std::size_t>(static_cast<std::size_t>(std::min(threads, kMaxThreads)), most));
#else
  (void)n;
  (void)threads;
  (void)grain;
  return 1;
#endif
}

// Per-thread force buffers, owned by the Simulation and reused by every kernel in turn.
class ForceScratch {
 public:
  // Buffers for threads 1..threads-1, each n_nodes long and zero.
  void prepare(int threads, std::size_t n_nodes) {
    const std::size_t want = static_cast<std::size_t>(std::max(threads - 1, 0));
    if (buf_.size() < want) buf_.resize(want);
    for (std::size_t t = 0; t < want; ++t)
      if (buf_[t].size() != n_nodes) buf_[t].assign(n_nodes, Vec3::Zero());
  }
  // Where thread tid adds its forces: the force array itself for thread 0.
  Vec3* forces(int tid, std::vector<Vec3>& f) {
    return tid == 0 ? f.data() : buf_[static_cast<std::size_t>(tid - 1)].data();
  }
  // f[i] += the buffers of threads 1..threads-1 for i in [begin, end); zeroes them.
  void reduce(int threads, std::vector<Vec3>& f, std::size_t begin, std::size_t end) {
    for (int t = 1; t < threads; ++t) {
      auto& b = buf_[static_cast<std::size_t>(t - 1)];
      for (std::size_t i = begin; i < end; ++i) {
        f[i] += b[i];
        b[i].setZero();
      }
    }
  }

 private:
  std::vector<std::vector<Vec3>> buf_;
};

// Runs kernel(tid, begin, end, Vec3* f) over [0, n) on up to `threads` threads, where f
// is where that thread adds forces (indexed by node), and returns the sum of the
// kernel's return values in thread order. With one thread: kernel(0, 0, n, f.data()).
template <class Kernel>
double parallel_forces(int threads, ForceScratch& scratch, std::vector<Vec3>& f, std::size_t n,
                       Kernel&& kernel) {
  const int T = threads_for(n, threads);
  if (T <= 1) return kernel(0, std::size_t{0}, n, f.data());
  scratch.prepare(T, f.size());
  std::array<double, kMaxThreads> part{};
#ifdef _OPENMP
#pragma omp parallel num_threads(T)
  {
    const int tid = omp_get_thread_num();
    std::size_t b, e;
    thread_range(n, T, tid, b, e);
    part[static_cast<std::size_t>(tid)] = kernel(tid, b, e, scratch.forces(tid, f));
#pragma omp barrier
    thread_range(f.size(), T, tid, b, e);
    scratch.reduce(T, f, b, e);
  }
#endif
  double sum = 0.0;
  for (int t = 0; t < T; ++t) sum += part[static_cast<std::size_t>(t)];
  return sum;
}

// Runs body(tid, begin, end) over [0, n) on up to `threads` threads, at least `grain` items
// each (work on distinct items, nothing to reduce: integrators, per-node fixes; light
// passes over the nodes take kMinLightItemsPerThread). Returns the thread count used.
template <class Body>
int parallel_ranges(int threads, std::size_t n, Body&& body,
                    std::size_t grain = kMinItemsPerThread) {
  const int T = threads_for(n, threads, grain);
  if (T <= 1) {
    body(0, std::size_t{0}, n);
    return 1;
  }
#ifdef _OPENMP
#pragma omp parallel num_threads(T)
  {
    const int tid = omp_get_thread_num();
    std::size_t b, e;
    thread_range(n, T, tid, b, e);
    body(tid, b, e);
  }
#endif
  return T;
}

// Builds a list on up to `threads` threads: body(begin, end, out) appends what the work
// items [begin, end) contribute to `out`, in order; the threads' lists are joined in thread
// order, so `list` (appended to) is the one a serial loop gives. `parts` keeps the
// per-thread lists' memory from one call to the next.
template <class Item, class Body>
void parallel_list(int threads, std::size_t n, std::vector<Item>& list,
                   std::vector<std::vector<Item>>& parts, Body&& body) {
  const int T = threads_for(n, threads);
  if (T <= 1) {
    body(std::size_t{0}, n, list);
    return;
  }
  if (parts.size() < static_cast<std::size_t>(T)) parts.resize(static_cast<std::size_t>(T));
  parallel_ranges(T, n, [&](int tid, std::size_t begin, std::size_t end) {
    auto& out = parts[static_cast<std::size_t>(tid)];
    out.clear();
    body(begin, end, out);
  });
  for (int t = 0; t < T; ++t) {
    const auto& part = parts[static_cast<std::size_t>(t)];
    list.insert(list.end(), part.begin(), part.end());
  }
}

// Where a kernel over the items of one chain (edges, hinges) adds forces. Item i touches
// the nodes at chain positions i + lo ... i + hi ("unwrapped": on a closed chain they may
// run past the end). A thread writes straight into the force array, except at positions
// that an earlier thread also touches (the first hi positions of its range, and, on the
// last thread of a closed chain, the positions thread 0 reaches across the seam): those
// contributions are kept, one entry each, and added after the kernel in thread order.
// Every node thus receives its contributions in the serial order — the result is
// bit-identical to one thread — and no O(N) pass over per-thread buffers is needed.
class ChainForces {
 public:
  ChainForces(Vec3* f, std::vector<std::pair<int, Vec3>>* halo, long redirect_below,
              long redirect_from)
      : f_(f), halo_(halo), below_(redirect_below), from_(redirect_from) {}
  // The force of `node` at unwrapped chain position p, to add one contribution to.
  Vec3& at(long p, int node) {
    if (p < below_ || p >= from_) {
      halo_->emplace_back(node, Vec3::Zero());
      return halo_->back().second;
    }
    return f_[node];
  }

 private:
  Vec3* f_;
  std::vector<std::pair<int, Vec3>>* halo_;
  long below_, from_;
};

// Per-thread lists of ChainForces' deferred contributions (owned by the Simulation).
using ChainHalos = std::array<std::vector<std::pair<int, Vec3>>, kMaxThreads>;

// Runs kernel(tid, begin, end, ChainForces& f) over the n items of a chain of n_positions
// nodes (closed: positions wrap), whose item i touches positions i + lo ... i + hi, and
// returns the sum of the kernel's return values in thread order.
template <class Kernel>
double parallel_chain_forces(int threads, ChainHalos& halos, std::vector<Vec3>& f, std::size_t n,
                             bool closed, long n_positions, long lo, long hi, Kernel&& kernel) {
  const int T = threads_for(n, threads);
  const long none_below = std::numeric_limits<long>::min();
  const long none_from = std::numeric_limits<long>::max();
  if (T <= 1) {
    ChainForces direct(f.data(), nullptr, none_below, none_from);
    return kernel(0, std::size_t{0}, n, direct);
  }
  std::array<double, kMaxThreads> part{};
#ifdef _OPENMP
#pragma omp parallel num_threads(T)
  {
    const int tid = omp_get_thread_num();
    std::size_t b, e;
    thread_range(n, T, tid, b, e);
    auto& halo = halos[static_cast<std::size_t>(tid)];
    halo.clear();
    const long below = tid == 0 ? none_below : static_cast<long>(b) + hi;
    const long from = closed && tid == T - 1 ? n_positions + lo : none_from;
    ChainForces sink(f.data(), &halo, below, from);
    part[static_cast<std::size_t>(tid)] = kernel(tid, b, e, sink);
  }
#else
  (void)closed;
  (void)n_positions;
  (void)lo;
  (void)hi;
#endif
  double sum = 0.0;
  for (int t = 0; t < T; ++t) {
    for (const auto& [node, F] : halos[static_cast<std::size_t>(t)])
      f[static_cast<std::size_t>(node)] += F;
    sum += part[static_cast<std::size_t>(t)];
  }
  return sum;
}

}  // namespace slender
