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
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "nodes.hpp"

namespace slender {

// Below this many work items per thread a kernel runs serially: the cost of waking the
// threads (a few microseconds) would exceed the work.
inline constexpr std::size_t kMinItemsPerThread = 256;
// The most threads a simulation takes.
inline constexpr int kMaxThreads = 64;

// The range of work items thread `tid` of `threads` takes out of [0, n).
inline void thread_range(std::size_t n, int threads, int tid, std::size_t& begin,
                         std::size_t& end) {
  const std::size_t T = static_cast<std::size_t>(threads), t = static_cast<std::size_t>(tid);
  begin = n * t / T;
  end = n * (t + 1) / T;
}

// How many threads a kernel of n items uses out of the simulation's `threads`.
inline int threads_for(std::size_t n, int threads) {
#ifdef _OPENMP
  const std::size_t most = std::max<std::size_t>(1, n / kMinItemsPerThread);
  return static_cast<int>(
      std::min<std::size_t>(static_cast<std::size_t>(std::min(threads, kMaxThreads)), most));
#else
  (void)n;
  (void)threads;
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

// Runs body(tid, begin, end) over [0, n) on up to `threads` threads (work on distinct
// items, nothing to reduce: integrators, per-node fixes). Returns the thread count used.
template <class Body>
int parallel_ranges(int threads, std::size_t n, Body&& body) {
  const int T = threads_for(n, threads);
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

}  // namespace slender
