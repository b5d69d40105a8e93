#pragma once
// The law on the wall contacts of one block of particles (block_forces.hpp, finish_block). Each
// particle's run of wall candidates is first sorted into contacts and not (their kinematics are
// gathered here, in WallContactsFound); the law then runs on all of the block's contacts together:
// eight at a time with AVX2 (the pair contacts' loop, pair_law_four_wide.hpp), or one at a time in
// the plain loops. The same source, so the same bits. One at a time, each contact's law (a chain
// of square roots and divisions) waited on itself, and the walls took a tenth of a settling
// box's step (bench/results/design.md).
#include <cstdint>
#include <vector>

#include "contact/contact_law.hpp"
#include "contact/contact_list.hpp"
#include "contact/kinematics.hpp"
#include "core/types.hpp"
#include "forces/pair_law_four_wide.hpp"
#include "state/materials.hpp"

namespace dem {

// The wall contacts found in a block, in the order their loads are added (each particle's run in
// order): what the law reads, as separate arrays. Per thread, cleared per block: its arrays keep
// their memory (no allocation per step once grown), and hold at least three entries past the last
// contact (the four-wide loads read them: pad()).
struct WallContactsFound {
  std::vector<int> k;                     // the wall candidate (index into the ContactList)
  std::vector<const PairParams*> params;  // the pair of the particle's material and the wall's
  std::vector<Vec3> n, v_rel, w_arm, w_rel, v_wall;  // ContactKinematics', and the wall's velocity there
  std::vector<double> overlap, m_eff, r_eff;

  int size() const { return count; }
  void clear() { count = 0; }
  // w_rel is read only where the model has a rolling law (ContactKinematics: unset otherwise).
  // Inlined into the force loop (called out of line, its calls cost 20 % of the walls' finding);
  // written by index behind one test of the room left (ten push_backs tested and moved ten ends).
  [[gnu::always_inline]] void add(int candidate, const PairParams& pair, const ContactKinematics& c, const Vec3& wall_velocity) {
    if (count + 4 > static_cast<int>(k.size())) [[unlikely]]
      grow(2 * count + 64);
    const int e = count++;
    k[e] = candidate, params[e] = &pair;
    n[e] = c.n, v_rel[e] = c.v_rel, w_arm[e] = c.w_arm, w_rel[e] = c.w_rel, v_wall[e] = wall_velocity;
    overlap[e] = c.overlap, m_eff[e] = c.m_eff, r_eff[e] = c.r_eff;
  }
  ContactKinematics kinematics(int e) const { return {n[e], overlap[e], v_rel[e], w_arm[e], m_eff[e], r_eff[e], w_rel[e]}; }
  // Three more entries repeating the last: the four-wide loads read past the last contact.
  void pad() {
    if (count == 0) return;
    const int e = count - 1;
    const Vec3 wall_velocity = v_wall[e];  // a copy: the arrays may grow below
    for (int q = 0; q < 3; ++q) add(k[e], *params[e], kinematics(e), wall_velocity);
    count -= 3;
  }

 private:
  int count = 0;  // contacts (the arrays are longer: room for more, and for the padding)
  void grow(int entries) {
    k.resize(entries), params.resize(entries);
    for (auto* v : {&n, &v_rel, &w_arm, &w_rel, &v_wall}) v->resize(entries);
    for (auto* v : {&overlap, &m_eff, &r_eff}) v->resize(entries);
  }
};

#ifdef DEM_SIMD_LOOPS
namespace four_wide {

// The law of Model on the wall contacts `found` (padded), eight at a time; `a` the wall
// ContactList's arrays (histories read and written by candidate, sums, normals and, with the
// energy log, each contact's work).
template <class Model, bool Bonds>
DEM_AVX2 void wall_law(const PairLawArrays a, const WallContactsFound& found, double dt) {
  const int m = found.size();
  if (m == 0) return;
  LawParams law[2]{};  // set by the first take (no lane's pair yet)
  const PairParams* law_of[2][4] = {};  // each lane's pair in law[half]: rebuilt only where one changes
  const auto take = [&](int e, FourContacts& g, int half) DEM_AVX2_LAMBDA {
    bool changed = false;
    for (int l = 0; l < 4; ++l) g.k[l] = found.k[e + l], changed = changed || found.params[e + l] != law_of[half][l];
    if (changed) {
      const PairParams* const pp[4] = {found.params[e], found.params[e + 1], found.params[e + 2], found.params[e + 3]};
      law[half] = law_params(pp);
      for (int l = 0; l < 4; ++l) law_of[half][l] = pp[l];
    }
    const int at[4] = {e, e + 1, e + 2, e + 3};
    LaneKinematics<Lanes4>& c = g.c;
    c.n = load_four(found.n.data(), at);
    c.overlap = simd::load(found.overlap.data() + e);
    c.v_rel = load_four(found.v_rel.data(), at);
    c.w_arm = load_four(found.w_arm.data(), at);
    c.m_eff = simd::load(found.m_eff.data() + e);
    c.r_eff = simd::load(found.r_eff.data() + e);
    if constexpr (Model::has_rolling) c.w_rel = load_four(found.w_rel.data(), at);
    take_histories<Model, Bonds>(a, g);
    return changed;
  };
  const auto keep = [&](const FourContacts& g, int count, const LaneForce<Lanes4>& f, const V3& spring, const Lanes4& mark,
                        const Mask4& bonded) DEM_AVX2_LAMBDA {
    if constexpr (Bonds) list_broken(a, g.k, count, g.bonded, bonded);
    keep_results<Model::has_rolling>(a, g.k, count, spring, g.c.n, f, mark, bonded, Bonds);
  };
  eight_at_a_time<Model>(m, dt, law, take, keep);
}

}  // namespace four_wide
#endif

// The law of Model on the wall contacts `found`, leaving in the wall ContactList `a` what a pair
// contact's law leaves (keep_pair_result, with the normal always kept): four-wide where `simd`
// and the model allows (found padded first), else one at a time.
template <class Model>
void wall_law(const PairLawArrays& a, WallContactsFound& found, double dt, bool simd, bool any_bonds) {
#ifdef DEM_SIMD_LOOPS
  if constexpr (Model::four_wide)
    if (simd) {
      found.pad();
      if (any_bonds) four_wide::wall_law<Model, true>(a, found, dt);
      else four_wide::wall_law<Model, false>(a, found, dt);
      return;
    }
#endif
  (void)simd, (void)any_bonds;
  for (int e = 0; e < found.size(); ++e) {
    const int k = found.k[e];
    const ContactKinematics c = found.kinematics(e);
    std::uint8_t bond = a.bonded[k];
    const ContactForce f = Model::evaluate(*found.params[e], c, dt, a.spring[k], bond, a.dashpot[k], a.rolling[k]);
    keep_bond(a, k, bond);
    keep_pair_result(a, k, c.n, f);
    if constexpr (Model::has_rolling) a.rolling[k] = f.couple;
  }
}

}  // namespace dem
