// The force loop's choice of model and the wall contacts' selection; the loop itself is
// block_forces.hpp, compiled per model by the force_loop_<law>.cpp units.
#include "forces/force_loop.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "forces/force_loop_units.hpp"

namespace dem {

LaggingThread lagging_thread;

void set_lagging_thread_for_tests(int thread, int microseconds) { lagging_thread = {thread, microseconds}; }

void counted_wall_touches(const Particles& p, const std::vector<WallGeometry>& geometry, const ContactList& wc, int first,
                          int n, Vec3* to_wall, std::uint8_t* touching, std::uint8_t* take, int* order, double gap) {
  const int i = wc.slot_i[first];
  const double reach = gap > 0 ? p.radius[i] * (1 + gap) : p.radius[i];
  const double r2 = reach * reach;
  for (int e = 0; e < n; ++e)
    touching[e] = wall_touches(p, geometry[wc.slot_j[first + e]], i, r2, wc.active[first + e], wc.bonded[first + e], to_wall[e]);
  select_wall_contacts(to_wall, touching, n, p.radius[i], take, order);
}

void select_wall_contacts(const Vec3* to_wall, const std::uint8_t* touching, int n, double radius, std::uint8_t* take,
                          int* order) {
  int m = 0;
  for (int e = 0; e < n; ++e) {
    take[e] = 0;
    if (touching[e]) order[m++] = e;
  }
  // Nearest first; ties (the same point seen by two elements) by element order: deterministic.
  std::sort(order, order + m, [&](int a, int b) {
    const double da = to_wall[a].squaredNorm(), db = to_wall[b].squaredNorm();
    return da != db ? da < db : a < b;
  });
  // Points within this distance of a tangent plane count as in it: round-off of the closest-point
  // computation is ~1e-16 of the coordinates; a real concave corner is ~radius in front.
  const double tol = 1e-9 * radius;
  for (int a = 0; a < m; ++a) {
    const int e = order[a];
    bool in_front = true;
    for (int b = 0; b < a && in_front; ++b) {
      const int t = order[b];
      if (!take[t]) continue;
      const double dist = to_wall[t].norm();
      // n_t points from the contact point to the centre: -to_wall / |to_wall|.
      in_front = dist == 0 || -(to_wall[e] - to_wall[t]).dot(to_wall[t]) > tol * dist;
    }
    take[e] = in_front;
  }
}

ForceVariant choose_force_variant(const MaterialTable& materials, bool any_bonds) {
  const std::optional<ModelChoice> m = materials.common_models(any_bonds);
  if (!m) return std::nullopt;
  return is_compiled(*m) ? m : std::nullopt;
}

std::string variant_name(ForceVariant v) {
  if (!v) return "mixed";
  std::string name(normal_law_name(v->normal));
  if (v->tangential != TangentialLaw::Coulomb) name += " + " + std::string(tangential_law_name(v->tangential));
  if (v->rolling != RollingLaw::None) name += " + " + std::string(rolling_law_name(v->rolling));
  if (v->explicit_dashpot) name += " (explicit dashpot)";
  return name;
}

double compute_contact_forces(const ForceLoopInput& in, ForceVariant variant, ContactList& pairs, ContactList& walls,
                              ForceBlocks& loads) {
  if (!variant) return mixed_force_loop()(in, pairs, walls, loads);
  for (const auto unit : kForceLoopUnits)
    if (const ForceLoopFn loop = unit(*variant)) return loop(in, pairs, walls, loads);
  // choose_force_variant gives compiled combinations only: kCompiled holds one no unit takes.
  throw std::logic_error("the force loop of " + variant_name(variant) + " is compiled by no unit (force_loop_units.hpp)");
}

}  // namespace dem
