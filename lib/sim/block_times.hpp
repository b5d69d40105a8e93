#pragma once
// How a loop over blocks of storage slots shares its work among threads: each thread takes one
// contiguous run of blocks (the particles stay in its core's cache from step to step), sized by
// the blocks' times at the last step (what a block costs depends on its contacts, on held
// particles, on the caches: counts balanced two threads within 30 % at best). Speed only: no
// result depends on the split.
#include <vector>

namespace dem {

struct BlockTimes {
  std::vector<long> ns;  // per block: its time at the last step [ns]
  long total = 0;        // their sum, as of the last fit()

  // Before a loop: `blocks` entries; when their count changed (first step, new particles), each
  // initial(b) (an estimate in any unit) until timed.
  template <class Initial>
  void fit(long blocks, Initial initial) {
    if (static_cast<long>(ns.size()) != blocks) {
      ns.resize(blocks);
      for (long b = 0; b < blocks; ++b) ns[b] = initial(b);
    }
    total = 0;
    for (long t : ns) total += t;
  }

  // The first block of the run of thread u of `threads` (u = threads: the end): each run ends at
  // the block boundary nearest its share of the total. Read before any thread times a block anew.
  long run_start(long u, long threads) const {
    const long blocks = static_cast<long>(ns.size());
    long b = 0;
    for (long before = 0; b < blocks && (u == threads || before + ns[b] / 2 < total * u / threads); ++b) before += ns[b];
    return b;
  }

  // After a block: its time, from seconds (omp_get_wtime) to nanoseconds, at least 1.
  void record(long b, double seconds) { ns[b] = 1 + static_cast<long>(1e9 * seconds); }
  // After more work on a block recorded this step: its time added.
  void add(long b, double seconds) { ns[b] += static_cast<long>(1e9 * seconds); }
};

}  // namespace dem
