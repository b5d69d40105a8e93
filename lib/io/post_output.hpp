#pragma once
// post-macro's outputs (docs/post.md describes every field): particles with stress and
// displacement (.vtu), coarse-grained grid fields (.vti), force chains (.vtp), and CSV tables of
// box averages and profiles. Every file is written atomically (temporary name, then rename).
#include <string>
#include <vector>

#include "post/coarse_grain.hpp"
#include "post/contact_forces.hpp"
#include "post/displacement.hpp"
#include "post/fragments.hpp"
#include "post/stress.hpp"
#include "state/particles.hpp"

namespace dem {

// Particles (write_particles_vtu's arrays) plus: stress (9 components: the contact part, plus the
// kinetic part when `kinetic` is given), kinetic_stress (when given), pressure, coordination, and
// with `fragments`: fragment (its rank, 0 the largest by mass) and fragment_particles.
// `u`: per-particle displacement or null.
void write_particle_fields_vtu(const std::string& path, const Particles& p, const std::vector<std::string>& material_names,
                               const std::vector<Mat3>& stress, const std::vector<Mat3>* kinetic, const std::vector<int>& coordination,
                               const std::vector<Vec3>* u, const FragmentSet* fragments = nullptr);

// Grid fields: density, solid_fraction, velocity, stress (contact + kinetic when `kinetic`),
// pressure, kinetic_stress (when `kinetic`), and with a displacement: displacement,
// displacement_gradient, strain, volumetric_strain.
void write_grid_fields_vti(const std::string& path, const GridFields& g, bool kinetic);

// One line per contact: pairs from centre to centre, wall contacts from the centre to the contact
// point on the wall. Cell data: force_magnitude, normal_force (positive in compression),
// tangential_force (magnitude), force (on the first end), wall (-1 for pairs, else the wall
// index), bonded.
void write_force_chains_vtp(const std::string& path, const Particles& p, const ContactForceSet& c);

// `title`: the one comment line above the header. Stress columns: stress = contact (+ kinetic).
void write_average_csv(const std::string& path, const std::string& title, const std::vector<BoxAverage>& rows, bool kinetic,
                       bool displacement);
void write_stress_profile_csv(const std::string& path, const std::string& title, const std::vector<BoxAverage>& rows, int axis,
                              bool kinetic);
// One row per fragment, largest mass first: rank, first_id, particles, mass, equivalent_diameter,
// centre x, y, z, and mass_passing: the fraction of all mass in fragments of equivalent diameter at
// most this one's (a grading curve).
void write_fragments_csv(const std::string& path, const std::string& title, const FragmentSet& f);
void write_displacement_profile_csv(const std::string& path, const std::string& title, const std::vector<ProfileRow>& rows, int axis);

}  // namespace dem
