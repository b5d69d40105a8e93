#include "contact/contact_list.hpp"

#include <algorithm>
#include <parallel/algorithm>
#include <utility>

#include "core/keep_items.hpp"

namespace dem {

namespace {
// std::vector::resize at least doubles the capacity whenever it grows: the candidate list, the
// largest thing in memory of a dense run, grows by a few entries at many rebuilds and would keep
// up to twice the room it needs. Grown by an eighth instead: to exactly n, each of those rebuilds
// moved the list to new memory, page by page faulted in (bench/results/design.md). Room
// never written is address space only, not resident memory.
template <class T>
void resize_with_headroom(std::vector<T>& v, std::size_t n, const T& value) {
  if (n > v.capacity()) v.reserve(n + n / 8);
  v.resize(n, value);
}
}  // namespace

void ContactList::resize(std::size_t n) {
  resize_with_headroom(key_i, n, Index{0});
  resize_with_headroom(key_j, n, Index{0});
  resize_with_headroom(slot_i, n, -1);
  resize_with_headroom(slot_j, n, -1);
  resize_with_headroom(spring, n, Vec3(Vec3::Zero()));
  resize_with_headroom(rolling, n, Vec3(Vec3::Zero()));
  resize_with_headroom(bonded, n, std::uint8_t{0});
  resize_with_headroom(dashpot, n, 0.0);
  resize_with_headroom(active, n, std::uint8_t{0});
  resize_with_headroom(normal, n, Vec3(Vec3::Zero()));
  resize_with_headroom(sum, n, ContactSum());
}

void ContactList::reserve(std::size_t n) {
  key_i.reserve(n);
  key_j.reserve(n);
  slot_i.reserve(n);
  slot_j.reserve(n);
  spring.reserve(n);
  rolling.reserve(n);
  bonded.reserve(n);
  dashpot.reserve(n);
  active.reserve(n);
  normal.reserve(n);
  sum.reserve(n);
}

void ContactList::push_back_from(const ContactList& from, std::size_t k) {
  key_i.push_back(from.key_i[k]);
  key_j.push_back(from.key_j[k]);
  slot_i.push_back(from.slot_i[k]);
  slot_j.push_back(from.slot_j[k]);
  spring.push_back(from.spring[k]);
  rolling.push_back(from.rolling[k]);
  bonded.push_back(from.bonded[k]);
  dashpot.push_back(from.dashpot[k]);
  active.push_back(from.active[k]);
  normal.push_back(from.normal[k]);
  sum.push_back(from.sum[k]);
}

void ContactList::keep_only(const Kept& keep) {
  keep_items(key_i, keep), keep_items(key_j, keep), keep_items(slot_i, keep), keep_items(slot_j, keep);
  keep_items(spring, keep), keep_items(rolling, keep), keep_items(bonded, keep), keep_items(dashpot, keep);
  keep_items(active, keep), keep_items(normal, keep), keep_items(sum, keep);
}

namespace {

// A counting sort of `found` by group(f), a storage slot: O(candidates + particles), and stable
// (key order within a group), so the places depend on the storage order only, never on the
// thread count.
template <class Group>
void place_by_group(const std::vector<FoundContact>& found, std::size_t particles, std::vector<int>& count, KeyOrder& place,
                    Group group) {
  count.assign(particles + 1, 0);
  for (const FoundContact& f : found) ++count[group(f) + 1];
  for (std::size_t s = 0; s < particles; ++s) count[s + 1] += count[s];
  place.resize(found.size());
  for (std::size_t r = 0; r < found.size(); ++r) place[r] = count[group(found[r])]++;
}

}  // namespace

void place_by_storage(const std::vector<FoundContact>& found, std::size_t particles, std::vector<int>& count,
                      KeyOrder& place) {
  place_by_group(found, particles, count, place, [](const FoundContact& f) { return std::min(f.slot_i, f.slot_j); });
}

void place_walls_by_storage(const std::vector<FoundContact>& found, std::size_t particles, std::vector<int>& count,
                            KeyOrder& place) {
  place_by_group(found, particles, count, place, [](const FoundContact& f) { return f.slot_i; });
}

namespace {

// new[place(r)] = field[from[r]] (zero for a new candidate), then swapped in. One field's worth of
// working memory at a time, freed again: at 10^6 particles the candidate list is the largest thing
// in memory, and a second copy of it would set the peak (the allocation happens once per rebuild).
template <class T>
void carry_field(std::vector<T>& field, const std::vector<int>& from, const KeyOrder& place, const T& zero) {
  std::vector<T> next(from.size());
  const long n = static_cast<long>(from.size());
#pragma omp parallel for schedule(static)
  for (long r = 0; r < n; ++r) next[key_rank_to_position(place, r)] = from[r] >= 0 ? field[from[r]] : zero;
  field.swap(next);
}

// `list` becomes `found`, the r-th stored at place[r], each with the history of entry from[r] of
// `list` (-1: none).
void take_found(ContactList& list, const std::vector<FoundContact>& found, const KeyOrder& place, const std::vector<int>& from) {
  carry_field(list.spring, from, place, Vec3(Vec3::Zero()));
  carry_field(list.rolling, from, place, Vec3(Vec3::Zero()));
  carry_field(list.bonded, from, place, std::uint8_t{0});
  carry_field(list.dashpot, from, place, 0.0);
  // Whether it was a contact at the last step: the wall loop hands a lost contact's spring to a
  // new one of the same particle (a sphere rolling from one mesh element onto the next).
  carry_field(list.active, from, place, std::uint8_t{0});
  // The rest belongs to the new candidates: keys and slots from the search; the force loop writes
  // every normal and sum before anything reads them.
  list.resize(found.size());
  const long n = static_cast<long>(found.size());
#pragma omp parallel for schedule(static)
  for (long r = 0; r < n; ++r) {
    const std::size_t k = key_rank_to_position(place, r);
    list.key_i[k] = found[r].key_i;
    list.key_j[k] = found[r].key_j;
    list.slot_i[k] = found[r].slot_i;
    list.slot_j[k] = found[r].slot_j;
    list.sum[k] = ContactSum();
  }
}

bool key_less(const ContactList& list, std::size_t a, const FoundContact& f) {
  return list.key_i[a] < f.key_i || (list.key_i[a] == f.key_i && list.key_j[a] < f.key_j);
}

}  // namespace

void carry_history(ContactList& list, KeyOrder& by_key, const std::vector<FoundContact>& found, KeyOrder& place,
                   std::vector<int>& from) {
  // Which old entry each candidate continues (-1: none): a merge-join of two key-sorted
  // sequences, O(old + new).
  from.resize(found.size());
  std::size_t r_old = 0;
  for (std::size_t r = 0; r < found.size(); ++r) {
    const FoundContact& f = found[r];
    from[r] = -1;
    for (; r_old < list.size(); ++r_old) {
      const int at = key_rank_to_position(by_key, r_old);
      if (!key_less(list, at, f)) {
        if (list.key_i[at] == f.key_i && list.key_j[at] == f.key_j) from[r] = at;
        break;
      }
    }
  }
  take_found(list, found, place, from);
  by_key.swap(place);
}

bool carry_history_in_groups(ContactList& list, const std::vector<FoundContact>& found, const std::vector<int>& groups,
                             const std::vector<Index>& id_of_slot, std::vector<int>& from) {
  const long old_n = static_cast<long>(list.size());
  const long slots = static_cast<long>(groups.size()) - 1;
  auto lower = [&](long k) { return std::min(list.slot_i[k], list.slot_j[k]); };
  // The old entries' slots hold the particles of their keys, and the groups rise along the list.
  int fits = 1;
#pragma omp parallel for schedule(static) reduction(min : fits)
  for (long k = 0; k < old_n; ++k) {
    const int i = list.slot_i[k], j = list.slot_j[k];
    const bool ok = i >= 0 && j >= 0 && i < slots && j < slots && id_of_slot[i] == list.key_i[k] &&
                    id_of_slot[j] == list.key_j[k] && (k == 0 || lower(k - 1) <= lower(k));
    fits = std::min(fits, static_cast<int>(ok));
  }
  if (!fits) return false;
  // Where each slot's old group starts: entry k starts the groups of the slots after entry k - 1's
  // slot, up to its own (empty groups start where the next one does).
  std::vector<int> old_start(slots + 1);
#pragma omp parallel for schedule(static)
  for (long k = 0; k <= old_n; ++k) {
    const long first = k == 0 ? 0 : lower(k - 1) + 1, last = k == old_n ? slots : lower(k);
    for (long s = first; s <= last; ++s) old_start[s] = static_cast<int>(k);
  }
  from.resize(found.size());
#pragma omp parallel for schedule(static, 256)
  for (long s = 0; s < slots; ++s) {
    int o = old_start[s];
    for (int q = groups[s]; q < groups[s + 1]; ++q) {
      const FoundContact& f = found[q];
      while (o < old_start[s + 1] && key_less(list, o, f)) ++o;
      from[q] = o < old_start[s + 1] && list.key_i[o] == f.key_i && list.key_j[o] == f.key_j ? o : -1;
    }
  }
  take_found(list, found, {}, from);
  return true;
}

void sort_by_key(const ContactList& list, KeyOrder& by_key) {
  by_key.resize(list.size());
  for (std::size_t k = 0; k < list.size(); ++k) by_key[k] = static_cast<int>(k);
  __gnu_parallel::sort(by_key.begin(), by_key.end(), [&](int a, int b) { return key_before(list, a, b); });
}

std::size_t active_count(const ContactList& list) {
  return static_cast<std::size_t>(std::count_if(list.active.begin(), list.active.end(), [](std::uint8_t a) { return a != 0; }));
}

void active_contacts(const ContactList& list, const KeyOrder& by_key, ContactList& out) {
  out.clear();
  out.reserve(active_count(list));
  for (std::size_t r = 0; r < list.size(); ++r) {
    const int k = key_rank_to_position(by_key, r);
    if (list.active[k]) out.push_back_from(list, k);
  }
}

}  // namespace dem
