#pragma once
// The force loop's body (force_loop.hpp), a template over the contact model, for the units that
// compile it: force_loop_<law>.cpp each instantiates its share of the combinations, so that a
// parallel build compiles them side by side (one unit took over 10 minutes under the sanitizers).
// In an unnamed namespace: each unit's instantiations are its own, inlined as in one file.
// Include it only from those units.
#include <omp.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <thread>
#include <type_traits>

#include "contact/contact_law.hpp"
#include "contact/model_table.hpp"
#include "forces/find_contacts.hpp"
#include "forces/force_loop.hpp"
#include "forces/force_loop_units.hpp"
#include "forces/pair_law_four_wide.hpp"
#include "forces/wall_law.hpp"
#include "simd/lanes_avx2.hpp"
#include "simd/memory.hpp"
#include "simd/simd.hpp"

namespace dem {

namespace {

// Each contact and each block of particles is written by one thread only; no force is added
// atomically (DESIGN.md). Each thread takes a contiguous run of blocks, as in the integration:
// candidates are stored along the particles' order, so a thread mostly reads particles that stay
// in its own core's cache (chunks dealt in turn made the cores trade cache lines: design.md).
// Each loop also returns the largest overlap relative to the smaller radius (a stability check).
constexpr long kChunk = 256;  // candidates per pass-1/pass-2 chunk

// The four-wide law pays where a chunk holds several groups of four contacts; in a sparse chunk
// (falling spheres) each group's gathers wait for all four lanes, some of them padding, and the
// plain loops are faster (bench/results/design.md).
constexpr int kMinSimdLaw = 16;

// What every chunk reads, set once per force loop.
struct ChunkInput {
  const ForceLoopInput& in;
  CandidateArrays candidates;
  PairLawArrays law;
  bool simd;  // simd_loops_on()
  std::uint8_t* touched;  // ForceBlocks::touched
  std::uint8_t stamp;     // the low byte of ForceBlocks::epoch
};

inline PairLawArrays with_broken(PairLawArrays a, std::vector<int>& broken) {
  a.broken = &broken;
  return a;
}

// The candidates [first, last) of one block. Periodic: distances to the nearest image; Fixed: some
// particles are fixed in place. Both are template parameters so that a scene without them pays
// nothing.
// `broken`: the thread's list of the candidates whose bond breaks.
template <class Model, bool Periodic, bool Fixed>
double pair_chunk(const ChunkInput& chunk, long first, long last, std::vector<int>& broken) {
  const PeriodicBox& box = chunk.in.periodic;
  const MaterialTable& materials = chunk.in.materials;
  const double dt = chunk.in.dt;
  const PairLawArrays a = with_broken(chunk.law, broken);  // a copy: stores through its arrays cannot change it
  // Pass 1 (find_contacts.hpp): which candidates are contacts, and their separations.
  int contact[kChunk + kFoundPadding];
  double dx[kChunk + kFoundPadding], dy[kChunk + kFoundPadding], dz[kChunk + kFoundPadding];
  const FoundInChunk found{contact, dx, dy, dz};
  const int m = find_contacts<Periodic>(chunk.candidates, box, first, last, found, chunk.simd);
  std::uint8_t* const touched = chunk.touched;  // local: a store through it could alias chunk
  const std::uint8_t stamp = chunk.stamp;
  for (int e = 0; e < m; ++e) {  // their particles have a contact this step (ForceBlocks::touched)
    const long k = contact[e];
    std::atomic_ref<std::uint8_t>(touched[a.slot_i[k]]).store(stamp, std::memory_order_relaxed);
    std::atomic_ref<std::uint8_t>(touched[a.slot_j[k]]).store(stamp, std::memory_order_relaxed);
  }
  // Pass 2 (pair_law_four_wide.hpp): the law on them, four at a time where the model allows.
  if constexpr (Model::four_wide)
    if (chunk.simd && m >= kMinSimdLaw) {
      return pair_law_four_wide<Model, Fixed>(a, materials, dt, found, m, chunk.in.any_bonds);
    }
  // Pass 2, in three loops over the chunk's contacts: their kinematics, their springs turned into
  // the tangent plane, the law. Each loop is short and its contacts independent, so the processor
  // overlaps the divisions and square roots of several contacts; in one long loop each contact
  // waited for its own (a chain of four).
  double worst = 0;
  ContactKinematics kin[kChunk];
  for (int e = 0; e < m; ++e) {
    const long k = contact[e];
    const int i = a.slot_i[k], j = a.slot_j[k];
    using lanes::triple;
    const double ri = a.radius[i], rj = a.radius[j];
    LaneKinematics<double> c;
    pair_geometry(lanes::Triple<double>{dx[e], dy[e], dz[e]}, ri, rj, c);
    pair_motion<Model::has_rolling>(ri, rj, triple(a.v[i]), triple(a.v[j]), triple(a.w[i]), triple(a.w[j]), c);
    pair_inertia<Fixed>(ri, rj, a.mass[i], a.mass[j], Fixed && a.fixed[i], Fixed && a.fixed[j], c);
    kin[e] = contact_kinematics<Model::has_rolling>(c);
  }
  for (int e = 0; e < m; ++e) {
    const long k = contact[e];
    a.spring[k] = Model::in_tangent_plane(a.spring[k], kin[e].n);
    if constexpr (Model::RollingModel::has_history) a.rolling[k] = Model::in_tangent_plane(a.rolling[k], kin[e].n);
  }
  for (int e = 0; e < m; ++e) {
    const long k = contact[e];
    const int i = a.slot_i[k], j = a.slot_j[k];
    const ContactKinematics& c = kin[e];
    const PairParams& params = materials.pair(a.material[i], a.material[j]);
    std::uint8_t bond = a.bonded[k];
    const ContactForce f = Model::evaluate_in_plane(params, c, dt, a.spring[k], bond, a.dashpot[k], a.rolling[k]);
    keep_bond(a, k, bond);
    keep_pair_result(a, k, c.n, f);
    if constexpr (Model::has_rolling) a.rolling[k] = f.couple;  // summed with the loads (finish_block)
    worst = std::max(worst, relative_overlap_if_larger(c.overlap, std::min(a.radius[i], a.radius[j]), worst));
  }
  return worst;
}

// Waits until block b of this force loop (`epoch`) is done: spins, as a barrier does.
inline void wait_until_done(std::vector<long>& done, long b, long epoch) {
  std::atomic_ref<long> flag(done[b]);
  for (long spins = 0; flag.load(std::memory_order_acquire) != epoch; ++spins) {
    // More threads than cores: the thread waited for may need this core.
    if (spins >= 4096) std::this_thread::yield();
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#endif
  }
}

// Each thread's working storage in the force loop, grown to the longest run of wall candidates, the
// most wall contacts of a block and the most bonds broken, then kept (no allocation per step:
// OpenMP keeps its threads, and with them these).
struct ThreadScratch {
  struct {
    std::vector<Vec3> to_wall;
    std::vector<std::uint8_t> touching, take;
    std::vector<int> order;
    WallContactsFound found;  // the block's contacts, for the law (wall_law.hpp)
  } walls;
  std::vector<int> broken_pairs, broken_walls;  // the candidates whose bond broke this step (ForceBlocks)
  WallWorkTerms wall_work;  // a block's wall contacts' terms of the step's work, while the energy log is on
  // A block's contact sums for the ledger, where its motion takes their work, and its state
  // before the motion, where only its own particle work reads it (finish_block): in cache, not
  // written to per-slot arrays.
  struct {
    ParticleWorkArrays work;
    std::vector<Vec3> x, v, w;
  } block;
};

// Wall candidate k of particle i after the selection: where `take`, a contact, appended to `found`
// with its kinematics (`to_wall`: closest point - centre); else it loses its history and sum.
template <class Model>
[[gnu::always_inline]] inline void take_wall_candidate(const ForceLoopInput& in, ContactList& wc, int k, int i, bool take, const Vec3& to_wall,
                                                       WallContactsFound& found) {
  const Particles& p = in.particles;
  if (!take) {
    if (!wc.active[k]) return;  // no contact at the last step either: its history and sum are zeros already
    if (in.wall_forces) in.wall_forces[in.wall_rank[k]].active = 0;
    wc.active[k] = 0;
    wc.spring[k] = Vec3::Zero();
    wc.rolling[k] = Vec3::Zero();
    wc.dashpot[k] = 0;
    wc.sum[k] = ContactSum();
    return;
  }
  const WallGeometry& g = in.geometry[wc.slot_j[k]];
  const double dist = to_wall.norm();
  ContactKinematics c;
  // A centre exactly on the wall has no direction to the contact point: use the plane normal.
  c.n = dist > 0 ? Vec3(to_wall * (1.0 / dist)) : g.normal;  // one division, as the pair contacts
  c.overlap = p.radius[i] - dist;  // eq. 2.17
  // eq. 2.18: the velocity of the wall's material at the contact point enters.
  const Vec3 v_wall = g.velocity_of(p.x[i] + to_wall);
  c.v_rel = v_wall - p.v[i];
  c.w_arm = p.radius[i] * p.w[i];
  c.m_eff = p.mass[i];
  c.r_eff = p.radius[i];  // a wall: infinite radius, eq. H3
  c.w_rel = Model::has_rolling ? Vec3(p.w[i] - g.spin) : Vec3::Zero();  // unread without rolling, but copied
  found.add(k, in.materials.pair(p.material[i], g.material), c, v_wall);
}

// The wall candidates of run r (one particle's, in order): which are contacts this step, those
// appended to `found` with their kinematics; the others lose their history and sum.
template <class Model>
void find_wall_contacts(const ForceLoopInput& in, ContactList& wc, long r, ThreadScratch& scratch) {
  const Particles& p = in.particles;
  const int first = in.wall_runs[r], n = in.wall_runs[r + 1] - first;
  const int i = wc.slot_i[first];
  auto& [to_wall, touching, take, order, found] = scratch.walls;
  if (n == 1) {  // one element near: a touch is a contact (none to weigh it against, no spring to take over)
    Vec3 to_this;
    const bool bonded = wc.bonded[first];
    const bool touches = wall_touches(p, in.geometry[wc.slot_j[first]], i, p.radius[i] * p.radius[i], wc.active[first], bonded, to_this);
    take_wall_candidate<Model>(in, wc, first, i, touches || bonded, to_this, found);
    return;
  }
  if (static_cast<int>(to_wall.size()) < n) to_wall.resize(n), touching.resize(n), take.resize(n), order.resize(n);
  counted_wall_touches(p, in.geometry, wc, first, n, to_wall.data(), touching.data(), take.data(), order.data());
  for (int e = 0; e < n; ++e) take[e] = take[e] || wc.bonded[first + e];  // a bond holds regardless
  // A new contact takes over the spring of a contact of this particle lost this step whose
  // direction is close (within 60 degrees): rolling or sliding from one element onto its
  // neighbour keeps the tangential force, as on a single plane.
  for (int e = 0; e < n; ++e) {
    const long k = first + e;
    if (!take[e] || wc.active[k]) continue;
    int from = -1;
    double best = 0.5;
    for (int o = 0; o < n; ++o) {
      const long ko = first + o;
      if (take[o] || !wc.active[ko] || wc.spring[ko] == Vec3::Zero()) continue;
      const double cosine = to_wall[o].normalized().dot(to_wall[e].normalized());
      if (cosine > best) best = cosine, from = o;
    }
    if (from >= 0) {
      wc.spring[k] = wc.spring[first + from], wc.spring[first + from] = Vec3::Zero();
      wc.rolling[k] = wc.rolling[first + from], wc.rolling[first + from] = Vec3::Zero();
      wc.dashpot[k] = wc.dashpot[first + from], wc.dashpot[first + from] = 0;  // and the dashpot's mark
    }
  }
  for (int e = 0; e < n; ++e) take_wall_candidate<Model>(in, wc, first + e, i, take[e], to_wall[e], found);
}

// The loads of the wall contacts `found` (their law done) added to their particles', in order;
// with `power`, the walls' power f · v_wall at the contact points added to it; with `work` (the
// energy log), each contact's terms of the step's work (add_wall_contact_work), its forces joining
// its particle's sums in `block_work` (the block's, entry 0 slot lo's). Returns the largest relative
// overlap.
template <class Model>
double add_wall_loads(const ForceLoopInput& in, ContactList& wc, const WallContactsFound& found, ForceBlocks& out, double* power,
                      WallWorkTerms* work, const ParticleWork& block_work, long lo) {
  const Particles& p = in.particles;
  double worst = 0;
  for (int e = 0; e < found.size(); ++e) {
    const int k = found.k[e], i = wc.slot_i[k];
    const ContactSum& s = wc.sum[k];
    const Vec3 couple = Model::has_rolling ? wc.rolling[k] : Vec3::Zero();
    wc.active[k] = 1;
    if (in.wall_forces) {
      WallForce& w = in.wall_forces[in.wall_rank[k]];
      w.force = s.force, w.active = 1;
    }
    out.force[i].v += s.force;  // eq. 2.31
    out.torque[i].v += p.radius[i] * s.torque_per_radius;  // eq. 2.33
    if constexpr (Model::has_rolling) out.torque[i].v += couple;  // eq. R1
    if (power) *power += s.force.dot(found.v_wall[e]);
    if (work)
      add_wall_contact_work(in.wall_work[k], s, couple, found.v_wall[e], in.geometry[wc.slot_j[k]].spin, in.dt, block_work, i - lo, *work);
    worst = std::max(worst, relative_overlap_if_larger(found.overlap[e], p.radius[i], worst));
  }
  return worst;
}

// A particle's three components as the sum pass adds them: a Vec3 in the plain loops, one Lanes4
// (its fourth lane unread) in the four-wide ones, so that the pass is written once (sum_loads).
// read_pair: a contact's two vectors (ContactSum, ContactWork: six doubles).
[[gnu::always_inline]] inline void read_pair(const double* six, Vec3& a, Vec3& b) { a = Vec3(six[0], six[1], six[2]), b = Vec3(six[3], six[4], six[5]); }
template <class V>
V xyz(const Vec3& a);
template <>
[[gnu::always_inline]] inline Vec3 xyz<Vec3>(const Vec3& a) {
  return a;
}
[[gnu::always_inline]] inline void put(LoadSum& s, const Vec3& a) { s.v = a; }
static_assert(sizeof(ContactSum) == 6 * sizeof(double) && offsetof(ContactSum, torque_per_radius) == 3 * sizeof(double));
static_assert(sizeof(ContactWork) == 6 * sizeof(double) && offsetof(ContactWork, tangential) == 3 * sizeof(double));
#ifdef DEM_SIMD_LOOPS
// Two loads that stay inside the contact's six doubles: [a0 a1 a2 b0] and [a2 b0 b1 b2] moved down.
[[gnu::always_inline]] inline void read_pair(const double* six, lanes::Lanes4& a, lanes::Lanes4& b) {
  a = lanes::load4(six), b = lanes::shift_down(lanes::load4(six + 2));
}
template <>
[[gnu::always_inline]] inline lanes::Lanes4 xyz<lanes::Lanes4>(const Vec3& a) {  // one at the end of an array: no wider load
  return lanes::lanes4(a.x(), a.y(), a.z(), 0.0);
}
[[gnu::always_inline]] inline void put(LoadSum& s, lanes::Lanes4 a) { lanes::store4(s.v.data(), a); }  // all four doubles of s
#endif

// What the sum pass reads per pair candidate (a candidate that is no contact holds zeros in each).
struct PairResults {
  const ContactSum* sum;
  const Vec3* couple;       // the rolling couples (read where the model has them)
  const ContactWork* work;  // while the energy log is on, else null
};

// The net loads of particles [lo, hi) from their weight and their pair contacts (written, not added
// to), each particle's in one order of its own (ForceBlocks::by_key): its weight m g, then + f of
// the contacts where it is i, then - f of those where it is j (each run in key order); its torque
// r Σ n x f_t over the same runs (eq. 2.31-2.34). Without a branch (whether a candidate touches is a
// coin toss to the branch predictor): mere candidates hold +0, which changes no bit of a sum that is
// never -0 (the weight + 0 starts it), so the candidate set, which depends on when the list was
// rebuilt, does not either; a particle without a contact this step (ForceBlocks::touched) skips
// its list, which changes no bit either. Written once over a particle's three components: a Vec3
// in the plain loops, one four-lane register with AVX2; the same operations, so the same bits.
// With couples (rolling resistance): + M where it is i, - M where it is j, added to the torque last
// (eq. R1). With the energy log (Ledger): the same runs of its contacts' ContactWork into
// block_work (entry 0 slot lo's), mere candidates' zeros included (pass 1 keeps them zero: no branch per
// candidate, whose outcome the predictor could not guess).
template <class V, bool Couples, bool Ledger>
[[gnu::always_inline]] inline void sum_loads(const ForceBlocks& out, const PairResults& r, const Particles& p, long lo, long hi,
                                             const ParticleWork& block_work) {
  const int* const by_key = out.by_key.data();
  const int* const start = out.by_key_start.data();
  const int* const split = out.by_key_split.data();
  LoadSum* const force = out.force.data();
  LoadSum* const torque = out.torque.data();
  const double *const mass = p.mass.data(), *const radius = p.radius.data();  // not reloaded after each store
  const std::uint8_t* const touched = out.touched.data();
  const std::uint8_t stamp = static_cast<std::uint8_t>(out.epoch);
  const V g = xyz<V>(out.body.gravity), zero = xyz<V>(Vec3::Zero());
  for (long i = lo; i < hi; ++i) {
    V f = V(mass[i] * g) + zero, arm = zero, spin = zero, damping = zero, tangential = zero;
    if (touched[i] != stamp) {  // mere candidates only: zeros to add
      put(force[i], f);
      put(torque[i], zero);
      if constexpr (Ledger) put(block_work.damping[i - lo], zero), put(block_work.tangential[i - lo], zero), put(block_work.torque_per_radius[i - lo], zero);
      if constexpr (Ledger && Couples) put(block_work.couple[i - lo], zero);
      continue;
    }
    V force_k, torque_k, damping_k, tangential_k;
    for (int e = start[i]; e < split[i]; ++e) {
      const int k = by_key[e];
      read_pair(r.sum[k].force.data(), force_k, torque_k);
      f = f + force_k, arm = arm + torque_k;
      if constexpr (Couples) spin = spin + xyz<V>(r.couple[k]);
      if constexpr (Ledger) read_pair(r.work[k].damping.data(), damping_k, tangential_k), damping = damping + damping_k, tangential = tangential + tangential_k;
    }
    for (int e = split[i]; e < start[i + 1]; ++e) {
      const int k = by_key[e];
      read_pair(r.sum[k].force.data(), force_k, torque_k);
      f = f - force_k, arm = arm + torque_k;
      if constexpr (Couples) spin = spin - xyz<V>(r.couple[k]);
      if constexpr (Ledger) read_pair(r.work[k].damping.data(), damping_k, tangential_k), damping = damping - damping_k, tangential = tangential - tangential_k;
    }
    put(force[i], f);
    if constexpr (Couples) put(torque[i], V(V(radius[i] * arm) + spin));
    else put(torque[i], V(radius[i] * arm));
    if constexpr (Ledger) put(block_work.damping[i - lo], damping), put(block_work.tangential[i - lo], tangential), put(block_work.torque_per_radius[i - lo], arm);
    if constexpr (Ledger && Couples) put(block_work.couple[i - lo], spin);  // without couples, never read (MotionWork::couples)
  }
}
template <bool Couples, bool Ledger>
void sum_pair_contacts_plain(const ForceBlocks& out, const PairResults& r, const Particles& p, long lo, long hi, const ParticleWork& block_work) {
  sum_loads<Vec3, Couples, Ledger>(out, r, p, lo, hi, block_work);
}
#ifdef DEM_SIMD_LOOPS
template <bool Couples, bool Ledger>
DEM_AVX2 void sum_pair_contacts_avx2(const ForceBlocks& out, const PairResults& r, const Particles& p, long lo, long hi, const ParticleWork& block_work) {
  sum_loads<lanes::Lanes4, Couples, Ledger>(out, r, p, lo, hi, block_work);
}
#endif
template <bool Couples, bool Ledger>
void sum_pair_contacts(const ForceBlocks& out, const PairResults& r, const Particles& p, long lo, long hi, const ParticleWork& block_work) {
#ifdef DEM_SIMD_LOOPS
  if (out.simd) return sum_pair_contacts_avx2<Couples, Ledger>(out, r, p, lo, hi, block_work);
#endif
  sum_pair_contacts_plain<Couples, Ledger>(out, r, p, lo, hi, block_work);
}

// The net loads of block b's particles (ForceBlocks): each one's weight and pair contacts, then its
// wall contacts, then the fluid's force; then, within a step, their motion (`not_finite`: the last
// slot whose new state is not finite) and, with the energy log, their work (`work`: the thread's
// sums; their contacts' taken by the motion), their energy taken before they move where asked
// (ForceBlocks::energy_before_motion). Called once every block holding a pair contact of theirs
// has been computed.
template <class Model>
double finish_block(const ForceLoopInput& in, const ContactList& pc, ContactList& wc, ForceBlocks& out, long b,
                    ThreadScratch& scratch, long& not_finite, StepWork& work) {
  const Particles& p = in.particles;
  const long lo = b * out.block, hi = std::min(static_cast<long>(p.size()), lo + out.block);
  const PairResults r{pc.sum.data(), pc.rolling.data(), in.work};
  // The contacts' sums for the ledger: the block's own where its motion takes their work, else
  // the per-slot arrays the motion after the loop reads.
  ParticleWork block_work;
  if (out.work.on() && out.motion) {
    scratch.block.work.resize(out.block);
    block_work = scratch.block.work.view();
  } else if (out.work.on()) {
    block_work = out.work.from(lo);
  }
  if (block_work.on()) sum_pair_contacts<Model::has_rolling, true>(out, r, p, lo, hi, block_work);
  else sum_pair_contacts<Model::has_rolling, false>(out, r, p, lo, hi, block_work);
  // Its wall contacts: found run by run, their law on them all, their loads added in that order.
  scratch.walls.found.clear();
  for (int q = in.wall_block_first[b]; q < in.wall_block_first[b + 1]; ++q)
    find_wall_contacts<Model>(in, wc, in.wall_run_order[q], scratch);
  WallContactsFound& found = scratch.walls.found;
  wall_law<Model>(with_broken(PairLawArrays(p, wc, true, in.wall_work), scratch.broken_walls), found, in.dt, out.simd, in.any_bonds);
  double power = 0;
  const double worst =
      add_wall_loads<Model>(in, wc, found, out, out.wall_power ? &power : nullptr, out.step_work ? &scratch.wall_work : nullptr, block_work, lo);
  if (out.step_work) scratch.wall_work.add_to(work);
  if (out.wall_power) out.wall_power[b] = power;
  if (out.body.fluid) out.body.add_fluid(p, lo, hi, out.force.data(), out.simd);
  // The state before the motion, for the particles' other work (a fluid, prescribed particles,
  // global damping): the ledger's arrays where it reads them after the step (move_particles keeps
  // it there), else the block's own copy.
  const bool other_work = out.particle_work && out.particle_work->any();
  BeforeMotion before{};
  if (other_work) {
    const MotionArrays& a = out.motion->arrays;
    if (a.before_x) {
      before = {a.before_x + lo, a.before_v + lo, a.before_w + lo};
    } else {
      std::vector<Vec3>&x = scratch.block.x, &v = scratch.block.v, &w = scratch.block.w;
      const bool fluid = out.particle_work->fluid;  // x^n is read only for the fluid's force
      x.resize(fluid ? out.block : 0), v.resize(out.block), w.resize(out.block);
      if (fluid) copy_vectors(p.x.data() + lo, hi - lo, x.data());
      copy_vectors(p.v.data() + lo, hi - lo, v.data()), copy_vectors(p.w.data() + lo, hi - lo, w.data());
      before = {fluid ? x.data() : nullptr, v.data(), w.data()};
    }
  }
  if (out.energy_before_motion) out.energy_before_motion[b] = energy_of_slots(p, out.body.gravity, in.periodic, lo, hi);
  if (out.motion) {
    const MotionWork motion_work{block_work, Model::has_rolling, &work};
    not_finite = std::max(not_finite, move_particles(out.motion->arrays, out.motion->constants, lo, hi, block_work.on() ? &motion_work : nullptr));
  }
  if (other_work) add_particle_work(p, *out.particle_work, before, lo, hi, work);
  return worst;
}

template <class Model, bool Periodic, bool Fixed>
double block_forces(const ForceLoopInput& in, ContactList& pc, ContactList& wc, ForceBlocks& out) {
  const long blocks = static_cast<long>(out.first.size()) - 1;
  out.times.fit(blocks, [&](long b) { return out.first[b + 1] - out.first[b] + 1; });  // candidates, until timed
  out.done.resize(blocks);
  out.touched.resize(in.particles.size());  // new slots hold 0: before any epoch
  const ChunkInput chunk{in, CandidateArrays(in.particles, pc, in.work, in.work_unset),
                         PairLawArrays(in.particles, pc, in.keep_pair_results, in.work),
                         simd_loops_on(), out.touched.data(), static_cast<std::uint8_t>(out.epoch)};
  double worst = 0;
  long not_finite = -1;
#pragma omp parallel reduction(max : worst, not_finite)
  {
    const long threads = omp_get_num_threads(), t = omp_get_thread_num();
    // Each thread takes a contiguous run of blocks holding about its share of the last step's
    // time (core/block_times.hpp): candidates are stored along the particles' order, so a thread
    // mostly reads particles that stay in its own core's cache.
    const long start = out.times.run_start(t, threads), end = out.times.run_start(t + 1, threads);
    static thread_local ThreadScratch scratch;
    static thread_local std::vector<long> later;
    ThreadScratch& mine = scratch;  // the thread's own, looked up once (each use of a thread_local looks it up)
    std::vector<long>& deferred = later;
    deferred.clear();
    mine.broken_pairs.clear(), mine.broken_walls.clear();
    StepWork work;  // the thread's share of the step's work, while the energy log is on
    const long tick = out.epoch;
    const auto pairs_of = [&](long b) {
      if (t == lagging_thread.thread) std::this_thread::sleep_for(std::chrono::microseconds(lagging_thread.microseconds));
      for (long first = out.first[b]; first < out.first[b + 1]; first += kChunk) {
        const long last = std::min(out.first[b + 1], first + kChunk);
        worst = std::max(worst, pair_chunk<Model, Periodic, Fixed>(chunk, first, last, mine.broken_pairs));
      }
      std::atomic_ref<long>(out.done[b]).store(tick, std::memory_order_release);
    };
    // The blocks the next thread's particles need come first, so that it need not wait for them.
    const long early = end < blocks ? std::clamp(out.needed_from[end], start, end) : end;
    for (long b = early; b < end; ++b) {
      const long tb = BlockTimes::now();
      pairs_of(b);
      out.times.record(b, tb);
    }
    for (long b = start; b < end; ++b) {
      const long tb = BlockTimes::now();
      if (b < early) pairs_of(b);
      // Finished now, while its contacts are in cache, unless some lie in another thread's blocks.
      if (out.needs[b] >= start) worst = std::max(worst, finish_block<Model>(in, pc, wc, out, b, mine, not_finite, work));
      else deferred.push_back(b);
      if (b < early) out.times.record(b, tb);
      else out.times.add(b, tb);
    }
    for (long b : deferred) {
      for (long o = out.needs[b]; o < start; ++o) wait_until_done(out.done, o, tick);
      const long tb = BlockTimes::now();  // after the wait: a block's time is its own work
      worst = std::max(worst, finish_block<Model>(in, pc, wc, out, b, mine, not_finite, work));
      out.times.add(b, tb);
    }
    if (out.step_work) {
#pragma omp critical(dem_step_work)
      out.step_work->add(work);  // exact: in any order
    }
    if (out.broken_pairs && (!mine.broken_pairs.empty() || !mine.broken_walls.empty())) {
#pragma omp critical(dem_broken_bonds)
      {
        out.broken_pairs->insert(out.broken_pairs->end(), mine.broken_pairs.begin(), mine.broken_pairs.end());
        out.broken_walls->insert(out.broken_walls->end(), mine.broken_walls.begin(), mine.broken_walls.end());
      }
    }
  }
  if (out.broken_pairs) {  // in the threads' order: made one
    std::sort(out.broken_pairs->begin(), out.broken_pairs->end());
    std::sort(out.broken_walls->begin(), out.broken_walls->end());
  }
  out.not_finite = not_finite;
  return worst;
}

template <class Model>
double all_forces(const ForceLoopInput& in, ContactList& pairs, ContactList& walls, ForceBlocks& loads) {
  if (in.periodic.any())
    return in.any_fixed ? block_forces<Model, true, true>(in, pairs, walls, loads) : block_forces<Model, true, false>(in, pairs, walls, loads);
  return in.any_fixed ? block_forces<Model, false, true>(in, pairs, walls, loads) : block_forces<Model, false, false>(in, pairs, walls, loads);
}

// The force loop of `m` where this unit compiles it (its normal law one of Normals, its tangential
// law Tangential unless that is AnyTangential), else none.
struct AnyTangential {};
template <class Tangential, class... Normals>
ForceLoopFn force_loop_if(ModelChoice m) {
  return with_compiled_model(m, [](auto model) -> ForceLoopFn {
    using M = decltype(model);
    constexpr bool normal = (std::is_same_v<typename M::NormalModel, Normals> || ...);
    constexpr bool tangential = std::is_same_v<Tangential, AnyTangential> || std::is_same_v<typename M::TangentialModel, Tangential>;
    if constexpr (normal && tangential) return &all_forces<M>;
    else return nullptr;
  });
}

}  // namespace

}  // namespace dem
