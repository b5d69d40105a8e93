#pragma once
// How a loop over blocks of storage slots shares its work among threads: each thread takes one
// contiguous run of blocks (the particles stay in its core's cache from step to step), sized by
// the blocks' times at the last steps (what a block costs depends on its contacts, on fixed
// particles, on the caches: counts balanced two threads poorly, design.md). Speed only: no
// result depends on the split.
#include <algorithm>
#include <chrono>
#include <vector>

#if defined(__x86_64__)
#include <x86intrin.h>
#endif

namespace dem {

struct BlockTimes {
  std::vector<long> ticks;  // per block: its latest time [ticks of now()], written as blocks end
  std::vector<long> fitted; // the times the runs are cut from, as of the last fit() (so no thread
                            // need wait for the others to cut theirs before timing a block): each
                            // block's times smoothed over the last few steps, so that one step's
                            // noise does not move a run's end back and forth (design.md)
  long total = 0;           // their sum
  bool estimated = false;   // fitted holds initial() estimates, not yet a step's times

  // The clock of block times, in ticks of some fixed unit (only their ratios are used): the
  // processor's time-stamp counter where there is one, else steady_clock's nanoseconds.
  // (omp_get_wtime, through clock_gettime, took 50-75 ns a call: a tenth of the integration's
  // time on the settle of 10^4, whose blocks of 256 particles take about a microsecond.)
  static long now() {
#if defined(__x86_64__)
    return static_cast<long>(__rdtsc());
#else
    return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch()).count();
#endif
  }

  // Before a loop: `blocks` entries; when their count changed (first step, new particles), each
  // initial(b) (an estimate in any unit) until timed.
  template <class Initial>
  void fit(long blocks, Initial initial) {
    if (static_cast<long>(ticks.size()) != blocks) {
      ticks.resize(blocks);
      for (long b = 0; b < blocks; ++b) ticks[b] = initial(b);
      fitted = ticks, estimated = true;
    } else if (estimated || fitted.size() != ticks.size()) {
      fitted = ticks, estimated = false;  // the first step's times replace the estimates
    } else {
      for (long b = 0; b < blocks; ++b) fitted[b] += (ticks[b] - fitted[b]) / 4;  // a quarter of the way to the latest
    }
    total = 0;
    for (long t : fitted) total += t;
  }

  // The first block of the run of thread u of `threads` (u = threads: the end): each run ends at
  // the block boundary nearest its share of the total.
  long run_start(long u, long threads) const {
    const long blocks = static_cast<long>(fitted.size());
    long b = 0;
    for (long before = 0; b < blocks && (u == threads || before + fitted[b] / 2 < total * u / threads); ++b) before += fitted[b];
    return b;
  }

  // After a block begun at `start` (now()): its time, at least 1 (a thread moved to another core
  // may read a counter a little behind).
  void record(long b, long start) { ticks[b] = std::max(1L, now() - start + 1); }
  // After more work on a block recorded this step, begun at `start`: its time added.
  void add(long b, long start) { ticks[b] += std::max(0L, now() - start); }
};

}  // namespace dem
