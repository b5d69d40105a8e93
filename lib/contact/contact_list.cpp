#include "contact/contact_list.hpp"

#include <utility>

namespace dem {

void ContactList::resize(std::size_t n) {
  key_i.resize(n);
  key_j.resize(n);
  slot_i.resize(n, -1);
  slot_j.resize(n, -1);
  spring.resize(n, Vec3::Zero());
  bonded.resize(n, 0);
  active.resize(n, 0);
  normal.resize(n, Vec3::Zero());
  sum.resize(n);
}

void ContactList::push_back_from(const ContactList& from, std::size_t k) {
  key_i.push_back(from.key_i[k]);
  key_j.push_back(from.key_j[k]);
  slot_i.push_back(from.slot_i[k]);
  slot_j.push_back(from.slot_j[k]);
  spring.push_back(from.spring[k]);
  bonded.push_back(from.bonded[k]);
  active.push_back(from.active[k]);
  normal.push_back(from.normal[k]);
  sum.push_back(from.sum[k]);
}

void carry_history(ContactList& list, const std::vector<FoundContact>& found, ContactList& next) {
  // Merge-join of two key-sorted sequences, O(old + new); both lists keep their capacity, so a
  // run does not allocate here once warmed up.
  next.resize(found.size());
  std::size_t o = 0;
  for (std::size_t k = 0; k < found.size(); ++k) {
    const FoundContact& f = found[k];
    while (o < list.size() && (list.key_i[o] < f.key_i || (list.key_i[o] == f.key_i && list.key_j[o] < f.key_j))) ++o;
    const bool before = o < list.size() && list.key_i[o] == f.key_i && list.key_j[o] == f.key_j;
    next.key_i[k] = f.key_i;
    next.key_j[k] = f.key_j;
    next.slot_i[k] = f.slot_i;
    next.slot_j[k] = f.slot_j;
    next.spring[k] = before ? list.spring[o] : Vec3::Zero();
    next.bonded[k] = before ? list.bonded[o] : 0;
    // Whether it was a contact at the last step: the wall loop hands a lost contact's spring to a
    // new one of the same particle (a sphere rolling from one mesh element onto the next).
    next.active[k] = before ? list.active[o] : 0;
    next.sum[k] = ContactSum();
  }
  std::swap(list, next);
}

void active_contacts(const ContactList& list, ContactList& out) {
  out.clear();
  for (std::size_t k = 0; k < list.size(); ++k)
    if (list.active[k]) out.push_back_from(list, k);
}

}  // namespace dem
