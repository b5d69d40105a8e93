#include "contact/contact_list.hpp"

namespace dem {

void ContactList::clear() { resize(0); }

void ContactList::resize(std::size_t n) {
  key_i.resize(n);
  key_j.resize(n);
  slot_i.resize(n);
  slot_j.resize(n);
  spring.resize(n, Vec3::Zero());
  normal.resize(n, Vec3::Zero());
  force.resize(n, Vec3::Zero());
  tangential.resize(n, Vec3::Zero());
}

void update_contacts(ContactList& list, const std::vector<FoundContact>& found) {
  // Merge-join of two key-sorted sequences: O(old + new).
  std::vector<Vec3> spring(found.size(), Vec3::Zero());
  std::size_t o = 0;
  for (std::size_t k = 0; k < found.size(); ++k) {
    const FoundContact& f = found[k];
    while (o < list.size() && (list.key_i[o] < f.key_i || (list.key_i[o] == f.key_i && list.key_j[o] < f.key_j))) ++o;
    if (o < list.size() && list.key_i[o] == f.key_i && list.key_j[o] == f.key_j) spring[k] = list.spring[o];
  }
  list.resize(found.size());
  for (std::size_t k = 0; k < found.size(); ++k) {
    list.key_i[k] = found[k].key_i;
    list.key_j[k] = found[k].key_j;
    list.slot_i[k] = found[k].slot_i;
    list.slot_j[k] = found[k].slot_j;
  }
  list.spring.swap(spring);
}

}  // namespace dem
