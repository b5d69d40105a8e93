#include "contact/contact_list.hpp"

namespace dem {

void ContactList::clear() { resize(0); }

void ContactList::resize(std::size_t n) {
  key_i.resize(n);
  key_j.resize(n);
  slot_i.resize(n);
  slot_j.resize(n);
  spring.resize(n, Vec3::Zero());
  bonded.resize(n, 0);
  normal.resize(n, Vec3::Zero());
  force.resize(n, Vec3::Zero());
  tangential.resize(n, Vec3::Zero());
}

void update_contacts(ContactList& list, const std::vector<FoundContact>& found) {
  // Merge-join of two key-sorted sequences: O(old + new).
  std::vector<Vec3> spring;
  std::vector<std::uint8_t> bonded;
  std::vector<const FoundContact*> kept;
  spring.reserve(found.size());
  bonded.reserve(found.size());
  kept.reserve(found.size());
  std::size_t o = 0;
  for (const FoundContact& f : found) {
    while (o < list.size() && (list.key_i[o] < f.key_i || (list.key_i[o] == f.key_i && list.key_j[o] < f.key_j))) ++o;
    const bool before = o < list.size() && list.key_i[o] == f.key_i && list.key_j[o] == f.key_j;
    const std::uint8_t b = before ? list.bonded[o] : 0;
    if (!f.touching && !b) continue;
    spring.push_back(before ? list.spring[o] : Vec3::Zero());
    bonded.push_back(b);
    kept.push_back(&f);
  }
  list.resize(kept.size());
  for (std::size_t k = 0; k < kept.size(); ++k) {
    list.key_i[k] = kept[k]->key_i;
    list.key_j[k] = kept[k]->key_j;
    list.slot_i[k] = kept[k]->slot_i;
    list.slot_j[k] = kept[k]->slot_j;
  }
  list.spring.swap(spring);
  list.bonded.swap(bonded);
}

}  // namespace dem
