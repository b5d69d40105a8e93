#pragma once
// Contacts as structure-of-arrays, with their history (the tangential spring, the bond and the
// dashpot's mark) keyed by
// stable ids so that it survives neighbour rebuilds, re-sorting and restarts (DESIGN.md).
//
// During a run the list holds every candidate pair of the neighbour list; `active` marks those
// that touch (or hold by a bond) this step. History lives on the candidates, so nothing is merged,
// copied or compacted per step: only a rebuild of the neighbour list carries it over, by key.
// A candidate that is no contact holds zero springs and a zero sum (the force loop and the loads
// rely on it: they skip such candidates).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/keep_items.hpp"
#include "core/types.hpp"

namespace dem {

// What the per-particle sums read of one contact, together in memory: the force on i and its
// torque per unit radius n x f_t (eq. 2.33-2.34: the torque on i is a_i n x f_t, on j a_j n x f_t).
struct ContactSum {
  Vec3 force = Vec3::Zero();   // total force on i [N]; j receives the opposite (eq. 2.31-2.32)
  Vec3 torque_per_radius = Vec3::Zero();  // n x f_t [N]: times a particle's radius, its torque
};

struct ContactList {
  // Keys: particle ids (key_i < key_j) for particle pairs; (particle id, wall index) for walls.
  std::vector<Index> key_i, key_j;
  std::vector<int> slot_i, slot_j;  // storage slots (slot_j = wall index for walls); -1 until found
  std::vector<Vec3> spring;         // tangential spring force on i [N] (history)
  std::vector<Vec3> rolling;        // rolling spring couple on i [N m] (history of epsd2; zero for other laws)
  std::vector<std::uint8_t> bonded; // bond flag Φ (history), SPEC §6
  std::vector<double> dashpot;      // the normal dashpot's overlap mark [m] (history; 0: none),
                                    // docs/contact-laws.md "The dashpot in time"
  std::vector<std::uint8_t> active; // touching or bonded this step: a contact, not just a candidate
  std::vector<Vec3> normal;         // unit normal from i to j (or to the wall) this step
  std::vector<ContactSum> sum;      // force on i and n x f_t this step; zero for a mere candidate

  std::size_t size() const { return key_i.size(); }
  const Vec3& force(std::size_t k) const { return sum[k].force; }  // on i [N]
  // The tangential part f_t of force(k): (n x f_t) x n, since f_t lies in the tangent plane.
  Vec3 tangential(std::size_t k) const { return sum[k].torque_per_radius.cross(normal[k]); }
  void clear() { resize(0); }
  void resize(std::size_t n);  // with an eighth more room when it grows
  void reserve(std::size_t n);
  // Appends entry k of `from` (all fields).
  void push_back_from(const ContactList& from, std::size_t k);
  // Keeps the entries whose `keep` flag is set (all fields), in their order.
  void keep_only(const Kept& keep);
};

// A pair found by the search (particle ids or particle id and wall index), ordered by key.
struct FoundContact {
  Index key_i, key_j;
  int slot_i, slot_j;
  bool operator<(const FoundContact& o) const { return key_i != o.key_i ? key_i < o.key_i : key_j < o.key_j; }
};

// Where a list's entries are stored, in key order: by_key[r] is the position of the entry with the
// r-th smallest key. Empty: the list is stored in key order (a list read from a checkpoint).
// Candidate lists are stored along the particles' storage order instead (place_by_storage,
// place_walls_by_storage), so that the force loop reads its lists in the order it visits the
// particles; every sum walks them in key order, so no result depends on where an entry is stored.
using KeyOrder = std::vector<int>;

// Positions for the candidates in `found` (sorted by key) along the particles' storage order:
// grouped by the smaller of their two slots, in key order within a group. `count` is working
// storage kept by the caller; `particles` the number of storage slots.
void place_by_storage(const std::vector<FoundContact>& found, std::size_t particles, std::vector<int>& count,
                      KeyOrder& place);
// The same for wall candidates (slot_j a wall's index): grouped by the particle's slot, so that
// each particle's wall candidates form one run, in key order (the wall index).
void place_walls_by_storage(const std::vector<FoundContact>& found, std::size_t particles, std::vector<int>& count,
                            KeyOrder& place);

// Makes `list` hold exactly the candidates in `found` (sorted by key), the r-th stored at position
// place[r] (empty `place`: at r), each carrying its history (spring, bond) from the entry of `list`
// with the same key when there is one, else zero history. `by_key` tells where `list` holds its
// entries in key order; afterwards it holds `place`, and `place` the old order (swapped: no copy,
// no allocation). `from` is working storage kept by the caller.
void carry_history(ContactList& list, KeyOrder& by_key, const std::vector<FoundContact>& found, KeyOrder& place,
                   std::vector<int>& from);

// carry_history without sorting anything, for a list whose slots still hold the same particles
// (`id_of_slot`: the particles' ids by slot) and which is stored as place_by_storage puts it, as is
// `found` (LinkedCells::find_near_pairs), `groups` telling where each slot's group starts (+ the
// end): each slot's old and new groups are merged by key, slot by slot in parallel, and `list`
// ends up holding `found` in its order, each with its history. Returns false, with `list`
// untouched, where the slots no longer fit (the storage was re-sorted, particles were added or
// removed, the list was read from a checkpoint): carry by key then. `from` is working storage.
bool carry_history_in_groups(ContactList& list, const std::vector<FoundContact>& found, const std::vector<int>& groups,
                             const std::vector<Index>& id_of_slot, std::vector<int>& from);

// Whether entry a of `list` comes before entry b in key order.
inline bool key_before(const ContactList& list, std::size_t a, std::size_t b) {
  return list.key_i[a] != list.key_i[b] ? list.key_i[a] < list.key_i[b] : list.key_j[a] < list.key_j[b];
}

// Where `list` holds its entries in key order (a KeyOrder for it), by sorting.
void sort_by_key(const ContactList& list, KeyOrder& by_key);

// The position of the r-th entry in key order.
inline int key_rank_to_position(const KeyOrder& by_key, std::size_t r) {
  return by_key.empty() ? static_cast<int>(r) : by_key[r];
}

// How many entries of `list` are active.
std::size_t active_count(const ContactList& list);

// The active entries of `list`, in key order.
void active_contacts(const ContactList& list, const KeyOrder& by_key, ContactList& out);

}  // namespace dem
