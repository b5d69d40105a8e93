#pragma once
// Contacts of one step as structure-of-arrays, with their history (the tangential spring) keyed by
// stable ids so that it survives neighbour rebuilds, re-sorting and restarts (DESIGN.md).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/types.hpp"

namespace dem {

struct ContactList {
  // Keys: particle ids (key_i < key_j) for particle pairs; (particle id, wall index) for walls.
  std::vector<Index> key_i, key_j;
  std::vector<int> slot_i, slot_j;  // storage slots this step (slot_j = wall index for walls)
  std::vector<Vec3> spring;         // tangential spring force on i [N] (history)
  std::vector<std::uint8_t> bonded; // bond flag Φ (history), SPEC §6
  std::vector<Vec3> normal;         // unit normal from i to j (or to the wall) this step
  std::vector<Vec3> force;          // force on i this step [N]
  std::vector<Vec3> tangential;     // tangential part of force on i [N]

  std::size_t size() const { return key_i.size(); }
  void clear();
  void resize(std::size_t n);
};

// A pair found by the search (particle ids or particle id and wall index), ordered by key.
struct FoundContact {
  Index key_i, key_j;
  int slot_i, slot_j;
  bool touching = true;
  bool operator<(const FoundContact& o) const { return key_i != o.key_i ? key_i < o.key_i : key_j < o.key_j; }
};

// Replace `list` with the contacts in `found` (sorted by key), carrying each contact's history
// (spring, bond) from `list` when the same key was in contact before, else starting from zero.
// A found pair that does not touch is kept only while it is bonded (a bond holds in tension).
// `scratch` is working storage kept by the caller between steps.
void update_contacts(ContactList& list, const std::vector<FoundContact>& found, ContactList& scratch);

}  // namespace dem
