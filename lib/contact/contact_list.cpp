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

void update_contacts(ContactList& list, const std::vector<FoundContact>& found, ContactList& next) {
  // Merge-join of two key-sorted sequences, O(old + new), written into `next`, which then becomes
  // the list; both keep their capacity, so a run does not allocate here once warmed up.
  next.key_i.clear();
  next.key_j.clear();
  next.slot_i.clear();
  next.slot_j.clear();
  next.spring.clear();
  next.bonded.clear();
  std::size_t o = 0;
  for (const FoundContact& f : found) {
    while (o < list.size() && (list.key_i[o] < f.key_i || (list.key_i[o] == f.key_i && list.key_j[o] < f.key_j))) ++o;
    const bool before = o < list.size() && list.key_i[o] == f.key_i && list.key_j[o] == f.key_j;
    const std::uint8_t b = before ? list.bonded[o] : 0;
    if (!f.touching && !b) continue;
    next.key_i.push_back(f.key_i);
    next.key_j.push_back(f.key_j);
    next.slot_i.push_back(f.slot_i);
    next.slot_j.push_back(f.slot_j);
    next.spring.push_back(before ? list.spring[o] : Vec3::Zero());
    next.bonded.push_back(b);
  }
  const std::size_t n = next.key_i.size();
  next.normal.resize(n);
  next.force.resize(n);
  next.tangential.resize(n);
  std::swap(list, next);
}

}  // namespace dem
