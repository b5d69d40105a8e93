#include "search/linked_cells.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/error.hpp"
#include "simd/lanes_avx2.hpp"
#include "simd/memory.hpp"
#include "simd/simd.hpp"

namespace dem {

namespace {
// Appends the parts to `out`, in order, and frees them: kept, they would double the memory of the
// found pairs at every rebuild.
void join_and_release(std::vector<SearchPart>& parts, std::vector<FoundContact>& out) {
  const long count = static_cast<long>(parts.size());
  std::vector<std::size_t> at(count + 1, out.size());
  for (long c = 0; c < count; ++c) at[c + 1] = at[c] + parts[c].found.size();
  out.resize(at[count]);
#pragma omp parallel for schedule(static)
  for (long c = 0; c < count; ++c) {
    std::copy(parts[c].found.begin(), parts[c].found.end(), out.begin() + at[c]);
    std::vector<FoundContact>().swap(parts[c].found);
  }
}

// [first, last) in order: an insertion sort where there are a few (a group holds a handful of
// candidates, for which std::sort's setup took longer than the sorting: a fifth of the search's
// time on a settled bed), std::sort beyond.
// Indices, not pointers: an empty range may be (nullptr, nullptr), where first + 1 is undefined.
void sort_small(FoundContact* first, FoundContact* last) {
  const std::ptrdiff_t n = last - first;
  if (n > 32) return std::sort(first, last);
  for (std::ptrdiff_t q = 1; q < n; ++q) {
    const FoundContact f = first[q];
    std::ptrdiff_t r = q;
    for (; r > 0 && f < first[r - 1]; --r) first[r] = first[r - 1];
    first[r] = f;
  }
}

#ifdef DEM_SIMD_LOOPS
// Which of the particles at slots[0..3] may lie within reach of particle a: a bit per lane where
// |x_a - x_b|^2 < (r_a + r_b + margin)^2, with a margin far above round-off (the plain test then
// decides each of those, so that both loops find exactly the same pairs).
DEM_AVX2 inline int maybe_near_four(const Vec3* x, const double* radius, int a, const int* slots, double margin) {
  using lanes::Lanes4;
  const lanes::Triple<Lanes4> b = simd::load_four(x, slots[0], slots[1], slots[2], slots[3]);
  const Lanes4 dx = simd::broadcast(x[a].x()) - b.x, dy = simd::broadcast(x[a].y()) - b.y, dz = simd::broadcast(x[a].z()) - b.z;
  const Lanes4 d2 = (dx * dx + dy * dy) + dz * dz;
  const Lanes4 reach = (simd::broadcast(radius[a]) + simd::gather(radius, simd::load(slots))) + simd::broadcast(margin);
  return simd::bits(lanes::less(d2, reach * reach * simd::broadcast(1 + 1e-12)));
}
#endif

}  // namespace

long LinkedCells::cell_coord(double x, int d) const {
  return std::clamp(static_cast<long>(std::floor((x - lo_[d]) / edge_[d])), 0L, dims_[d] - 1);
}

long LinkedCells::particle_cell_coord(double x, int d) const {
  return std::clamp(static_cast<long>(std::floor((x - lo_[d]) / edge_[d])), pad_[d], dims_[d] - 1 - pad_[d]);
}

void LinkedCells::bin(const Particles& p, const PeriodicBox& box, double margin) {
  const int n = static_cast<int>(p.size());
  Vec3 lo = n ? p.x[0] : Vec3::Zero(), hi = lo;
  double rmax = 0;
  for (int k = 0; k < n; ++k) {
    lo = lo.cwiseMin(p.x[k]);
    hi = hi.cwiseMax(p.x[k]);
    rmax = std::max(rmax, p.radius[k]);
  }
  // Cell edge >= 2 Rmax (+ margin) (eq. 3.1); widened if needed so the grid has at most ~2N + 27 cells,
  // which bounds memory when a particle flies far away. A period holds a whole number of cells.
  double edge = std::max(2 * rmax + margin, 1e-300);
  long* dims = dims_;
  for (;;) {
    long total = 1;
    for (int d = 0; d < 3; ++d) {
      if (box.axis[d]) {
        dims[d] = std::max(1L, static_cast<long>(std::floor(box.length(d) / edge)));
        lo_[d] = box.lo[d];
        edge_[d] = box.length(d) / dims[d];
      } else {
        dims[d] = std::max(1L, static_cast<long>(std::floor((hi[d] - lo[d]) / edge)) + 1);
        lo_[d] = lo[d];
        edge_[d] = edge;
      }
      total *= dims[d];
    }
    if (total <= 2L * n + 27) break;
    edge *= 1.26;
  }
  // Along an axis that is not periodic, one empty cell more at each end: every particle's cell then
  // has all 26 neighbours on the grid, found by a fixed offset of its index (find_near_pairs).
  for (int d = 0; d < 3; ++d) {
    pad_[d] = box.axis[d] ? 0 : 1;
    lo_[d] -= pad_[d] * edge_[d];
    dims[d] += 2 * pad_[d];
  }
  for (int d = 0; d < 3; ++d)
    if (box.axis[d] && dims[d] < 3) {
      std::ostringstream m;
      m << "periodic boundaries: the period along " << "xyz"[d] << " (" << box.length(d) << " m) must hold at least 3 search cells of "
        << 2 * rmax + margin << " m (the largest diameter plus the neighbour-list skin and bond reach): widen the period";
      throw InputError(m.str());
    }
  rmax_ = rmax;
  // Each cell's slots as one run (a counting sort by cell, stable: slot order within a cell).
  const long ncell = dims[0] * dims[1] * dims[2];
  cell_of_.resize(n);
#pragma omp parallel for schedule(static)
  for (int k = 0; k < n; ++k)
    cell_of_[k] = static_cast<int>((particle_cell_coord(p.x[k][2], 2) * dims[1] + particle_cell_coord(p.x[k][1], 1)) * dims[0] +
                                   particle_cell_coord(p.x[k][0], 0));
  cell_first_.assign(ncell + 1, 0);
  for (int k = 0; k < n; ++k) ++cell_first_[cell_of_[k] + 1];
  for (long c = 0; c < ncell; ++c) cell_first_[c + 1] += cell_first_[c];
  cell_slots_.resize(n);
  std::vector<int> fill(cell_first_.begin(), cell_first_.end() - 1);
  for (int k = 0; k < n; ++k) cell_slots_[fill[cell_of_[k]]++] = k;
}

void LinkedCells::find_near_pairs(const Particles& p, const PeriodicBox& box, std::vector<FoundContact>& out, std::vector<int>& group_start,
                                  double margin, bool fixed_pairs) {
  bin(p, box, margin);
  const long* dims = dims_;
  const long ncell = dims[0] * dims[1] * dims[2];
  const bool periodic = box.any();
  // Half of the neighbour shell: the 13 cells "after" the current one, plus the cell itself. With
  // at least 3 cells along a periodic axis, each pair of cells is still visited once.
  static constexpr int kHalf[13][3] = {{1, 0, 0},  {-1, 1, 0}, {0, 1, 0},  {1, 1, 0},   {-1, -1, 1},
                                       {0, -1, 1}, {1, -1, 1}, {-1, 0, 1}, {0, 0, 1},   {1, 0, 1},
                                       {-1, 1, 1}, {0, 1, 1},  {1, 1, 1}};
  // Cells are searched in parallel, each thread into its own part.
  const int threads = omp_get_max_threads();
  parts_.resize(threads);
  // The arrays' addresses in locals: a store into `mine` could change the vectors' own fields for
  // the compiler, which then reloaded them for every pair tested.
  const Vec3* const x = p.x.data();
  const double* const radius = p.radius.data();
  const std::uint8_t* const fixed = p.fixed.data();
  const Index* const id = p.id.data();
#pragma omp parallel num_threads(threads)
  {
    SearchPart& part = parts_[omp_get_thread_num()];
    std::vector<FoundContact>& mine = part.found;
    mine.clear();
    mine.reserve(part.last_pairs + part.last_pairs / 8);
    auto test = [&, x, radius, fixed, id, fixed_pairs](int a, int b) {
      if (!fixed_pairs && both_fixed(fixed[a], fixed[b])) return;
      const double r = radius[a] + radius[b];
      const double d2 = (periodic ? box.nearest(x[a] - x[b]) : Vec3(x[a] - x[b])).squaredNorm();
      if (d2 < (r + margin) * (r + margin)) {
        if (id[a] < id[b]) mine.push_back({id[a], id[b], a, b});
        else mine.push_back({id[b], id[a], b, a});
      }
    };
    // A neighbour cell's coordinate along axis d, wrapped around a period; -1 when off the grid.
    auto along = [&](long c, int d) {
      if (c >= 0 && c < dims[d]) return c;
      return box.axis[d] ? (c + dims[d]) % dims[d] : -1L;
    };
    // Without periodic axes every particle's cell lies inside the padding (bin): its neighbours are
    // at fixed offsets of its index. (Their coordinates, checked against the grid per neighbour,
    // were most of the search's time where cells hold a particle or two.)
    long offset[13];
    for (int h = 0; h < 13; ++h) offset[h] = (kHalf[h][2] * dims[1] + kHalf[h][1]) * dims[0] + kHalf[h][0];
    // There, the half shell is five runs of consecutive cells (along x, a row's cells are
    // consecutive indices): (1, 0, 0), then x - 1 to x + 1 in the rows (y + 1, z), (y - 1, z + 1),
    // (y, z + 1), (y + 1, z + 1); each run's slots are one range of cell_slots (faster than cell by
    // cell with one or two particles per cell: bench/results/design.md).
    const long row[5] = {offset[0], offset[1], offset[4], offset[7], offset[10]};
    const long row_cells[5] = {1, 3, 3, 3, 3};
    const int* const cell_first = cell_first_.data();
    const int* const cell_slots = cell_slots_.data();
    // The slots of those five runs, one after the other (each thread's own, kept across cells).
    std::vector<int> around;
    const bool simd = simd_loops_on();
#pragma omp for schedule(dynamic, 64)
    for (long c = 0; c < ncell; ++c) {
      const int first = cell_first[c], last = cell_first[c + 1];
      if (first == last) continue;
      for (int m = first; m < last; ++m)
        for (int o = m + 1; o < last; ++o) test(cell_slots[m], cell_slots[o]);
      if (!periodic) {
        around.clear();
        for (int r = 0; r < 5; ++r)
          around.insert(around.end(), cell_slots + cell_first[c + row[r]], cell_slots + cell_first[c + row[r] + row_cells[r]]);
        const int count = static_cast<int>(around.size());
#ifdef DEM_SIMD_LOOPS
        // Four at a time: a pre-test of the distances (maybe_near_four), the plain test on those
        // that pass it. (The settle of 10^4 rebuilds its list every 40 steps: its searches took
        // 0.77 s of 10 s on one thread one at a time, 0.70-0.73 s so.)
        if (simd && count >= 4) {
          const int any = around[0];
          around.insert(around.end(), 3, any);  // lanes past the end: masked out
          for (int m = first; m < last; ++m) {
            const int a = cell_slots[m];
            for (int o = 0; o < count; o += 4) {
              int hits = maybe_near_four(x, radius, a, around.data() + o, margin) & ((1 << std::min(4, count - o)) - 1);
              for (; hits; hits &= hits - 1) test(a, around[o + __builtin_ctz(hits)]);
            }
          }
          continue;
        }
#endif
        for (int m = first; m < last; ++m)
          for (int o = 0; o < count; ++o) test(cell_slots[m], around[o]);
        continue;
      }
      // The cell's coordinates, to wrap its neighbours around the periods.
      const long cx = c % dims[0], cy = (c / dims[0]) % dims[1], cz = c / (dims[0] * dims[1]);
      for (int h = 0; h < 13; ++h) {
        // Wrapped around the periods; off the grid along an axis that is not periodic.
        const long x = along(cx + kHalf[h][0], 0), y = along(cy + kHalf[h][1], 1), z = along(cz + kHalf[h][2], 2);
        if (x < 0 || y < 0 || z < 0) continue;
        const long cell = (z * dims[1] + y) * dims[0] + x;
        for (int m = first; m < last; ++m)
          for (int o = cell_first[cell]; o < cell_first[cell + 1]; ++o) test(cell_slots[m], cell_slots[o]);
      }
    }
    part.last_pairs = mine.size();
  }
  // Grouped by the smaller slot (a counting sort: in any order within a group), then each group put
  // in key order: an order that depends on neither the threads nor the cells. Each part is counted
  // and placed by one thread: part c's pairs of slot s go after those of the parts before c.
  // (Owners of slot ranges that each read every part, and atomic counters, were slower on two
  // threads: bench/results/design.md.)
  const long n = static_cast<long>(p.size());
  const long part_count = static_cast<long>(parts_.size());
  auto lower = [](const FoundContact& f) { return std::min(f.slot_i, f.slot_j); };
  // Per part and slot: its count, then its first place (a count per slot and thread for the time of
  // the grouping: 4 MB a thread at 10^6 particles).
  std::vector<std::vector<int>> place(part_count);
#pragma omp parallel for schedule(static, 1)
  for (long c = 0; c < part_count; ++c) {
    std::vector<int> count(n, 0);
    for (const FoundContact& f : parts_[c].found) ++count[lower(f)];
    place[c].swap(count);
  }
  group_start.assign(n + 1, 0);
  for (long s = 0; s < n; ++s) {
    int at = group_start[s];
    for (std::vector<int>& part : place) {
      const int count = part[s];
      part[s] = at;
      at += count;
    }
    group_start[s + 1] = at;
  }
  out.resize(group_start[n]);
#pragma omp parallel for schedule(static, 1)
  for (long c = 0; c < part_count; ++c)
    for (const FoundContact& f : parts_[c].found) out[place[c][lower(f)]++] = f;
  for (SearchPart& part : parts_) std::vector<FoundContact>().swap(part.found);  // kept, they would double the memory
#pragma omp parallel for schedule(static, 1024)
  for (long s = 0; s < n; ++s) sort_small(out.data() + group_start[s], out.data() + group_start[s + 1]);
}

void LinkedCells::find_near_walls(const Particles& p, const std::vector<WallGeometry>& walls, std::vector<FoundContact>& out,
                                  double margin) {
  if (p.size() == 0) return;
  const int threads = omp_get_max_threads();
  parts_.resize(threads);
  const long nw = static_cast<long>(walls.size());
  const double grow = rmax_ + margin;
#pragma omp parallel num_threads(threads)
  {
    SearchPart& part = parts_[omp_get_thread_num()];
    std::vector<FoundContact>& mine = part.found;
    mine.clear();
    mine.reserve(part.last_walls + part.last_walls / 8);
    // One element at a time: a box has six walls, each covering thousands of cells.
#pragma omp for schedule(dynamic, 1)
    for (long w = 0; w < nw; ++w) {
      const WallGeometry& g = walls[w];
      Vec3 blo = g.vertices[0], bhi = g.vertices[0];
      for (int v = 1; v < g.count; ++v) blo = blo.cwiseMin(g.vertices[v]), bhi = bhi.cwiseMax(g.vertices[v]);
      blo.array() -= grow;
      bhi.array() += grow;
      long c0[3], c1[3];
      bool outside = false;
      for (int d = 0; d < 3; ++d) {
        // Cells past the grid's last one hold nothing beyond it: an element far away is skipped.
        outside = outside || bhi[d] < lo_[d] || blo[d] > lo_[d] + dims_[d] * edge_[d];
        c0[d] = cell_coord(blo[d], d);
        c1[d] = cell_coord(bhi[d], d);
      }
      if (outside) continue;
      for (long z = c0[2]; z <= c1[2]; ++z)
        for (long y = c0[1]; y <= c1[1]; ++y)
          for (long x = c0[0]; x <= c1[0]; ++x) {
            const long cell = (z * dims_[1] + y) * dims_[0] + x;
            for (int m = cell_first_[cell]; m < cell_first_[cell + 1]; ++m) {
              const int k = cell_slots_[m];
              const double reach = p.radius[k] + margin;
              if ((closest_point(g, p.x[k]) - p.x[k]).squaredNorm() < reach * reach)
                mine.push_back({p.id[k], static_cast<Index>(w), k, static_cast<int>(w)});
            }
          }
    }
    part.last_walls = mine.size();
  }
  join_and_release(parts_, out);
}

}  // namespace dem
