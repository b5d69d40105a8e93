#pragma once
// Verlet neighbour list with a skin (DESIGN.md "Choices that decide speed"): candidate pairs closer
// than touching + margin + skin, found with linked cells, rebuilt only when a particle (or wall)
// may have moved far enough to create a contact the list does not hold, or when the particles or
// their fixed flags changed (pairs of two fixed particles are no candidates). Which steps rebuild
// never changes the contacts found, so results do not depend on it (restart-exact).
#include <cstdint>
#include <vector>

#include "contact/contact_list.hpp"
#include "search/linked_cells.hpp"
#include "state/particles.hpp"
#include "walls/wall.hpp"

namespace dem {

class NeighbourList {
 public:
  // Rebuilds if needed for the current positions; returns true when it did. `margin` is how far
  // apart a bonded pair can still hold (0 without bonds); `skin` the extra distance listed: a
  // value > 0 is the scene's (a new value rebuilds the list), 0 the automatic skin, worked out at
  // each build (automatic_skin) and kept with the list until the next: a removal through
  // keep_only, which changes the mean radius, keeps the list and its skin.
  bool update(const Particles& p, const PeriodicBox& box, const std::vector<WallGeometry>& walls, double margin, double skin);
  // The automatic skin: 0.2 x the particles' mean radius.
  static double automatic_skin(const Particles& p);
  // Forget the list (particle storage was reordered): the next update rebuilds it.
  void invalidate() { valid_ = false; }
  // Whether the list is built for these `particles` as stored now (no reorder, insertion or
  // removal since, other than through keep_only).
  bool valid_for(std::size_t particles) const { return valid_ && x_build_.size() == particles; }
  // The particles whose `keep` flag is set stay, in their order, the others are removed: the list
  // stays valid (each pair of those left that it held stays within its reach), its reference
  // positions those of the particles left. The caller filters its candidates alike.
  void keep_only(const Kept& keep);

  // Pair candidates with the storage slots of the last build, grouped by the smaller slot (key order
  // within a group; LinkedCells::find_near_pairs), and where each slot's group starts (+ the end).
  const std::vector<FoundContact>& pairs() const { return pairs_; }
  const std::vector<int>& pair_groups() const { return pair_groups_; }
  // Puts pairs() in key order (pair_groups() then means nothing).
  void sort_pairs_by_key();
  // Wall candidates, sorted by key.
  const std::vector<FoundContact>& wall_pairs() const { return wall_pairs_; }
  // Frees pairs() and wall_pairs() once the caller has taken what it needs from them (their
  // history carried over): at 10^6 particles they are tens of MB, needed only at a rebuild.
  void release_found() {
    std::vector<FoundContact>().swap(pairs_);
    std::vector<FoundContact>().swap(wall_pairs_);
    std::vector<int>().swap(pair_groups_);
  }
  std::int64_t builds() const { return builds_; }

 private:
  bool needs_rebuild(const Particles& p, const PeriodicBox& box, const std::vector<WallGeometry>& walls, double margin,
                     double skin) const;
  void build(const Particles& p, const PeriodicBox& box, const std::vector<WallGeometry>& walls, double margin, double skin);

  LinkedCells cells_;
  std::vector<FoundContact> pairs_, wall_pairs_;
  std::vector<int> pair_groups_;
  std::vector<Vec3> x_build_;
  std::vector<Index> id_build_;
  std::vector<std::uint8_t> fixed_build_;  // the fixed flags at the last build
  std::vector<Vec3> wall_build_;  // every element's vertices at the last build, 4 per element
  double margin_build_ = -1, skin_build_ = -1;
  PeriodicBox box_build_;
  bool valid_ = false;
  std::int64_t builds_ = 0;
};

}  // namespace dem
