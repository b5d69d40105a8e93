#pragma once
// A scene as plain, validated data: what io/scene_parser.cpp reads from a TOML file. Strings end
// at the parser; inside the library everything is enums and numbers in SI units.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "contact/normal_laws.hpp"
#include "core/interval.hpp"
#include "core/types.hpp"
#include "forces/fluid.hpp"
#include "scene/region.hpp"
#include "state/materials.hpp"
#include "state/periodic.hpp"
#include "walls/wall.hpp"

namespace dem {

struct SimulationSpec {
  double time_step = 0;          // [s]; 0 = automatic (eq. 2.48)
  double frac = 0.1;             // FRAC of eq. 2.48
  bool force_time_step = false;  // allow a time_step above the critical one
  Vec3 gravity = Vec3(0, 0, -9.81);
  double alpha_r = 0, alpha_theta = 0;  // global damping [1/s], eq. 2.36-2.37
  double skin = 0;                      // neighbour-list skin [m]; 0 = automatic
  double max_overlap = 0.5;             // unstable-run check: overlap / smaller radius
  double max_energy_gain = 0.5;         // unstable-run check: energy created / energy scale; 0 = off
  PeriodicBox periodic;                 // [simulation.periodic]: none by default
  long sort_every = 1000;                // storage re-sort cadence [steps]; 0 = never (SimParams::sort_every)
};

struct WallSpec {
  std::string name;
  int material = 0;
  std::vector<Vec3> vertices;
};

// Stop criterion for settling under gravity: mean kinetic energy per particle below
// `ke_ratio` x (mean mass x |g| x mean diameter), checked every `check_every` (seconds, or "N steps"), or
// `max_time` seconds of simulated time at most.
struct SettleSpec {
  double ke_ratio = 1e-4;
  double max_time = 1.0;  // [s]
  Interval check_every = seconds(0.01);
};

// One sphere placed at a given position before the random ones ([[generation.place]]).
struct PlacedSphere {
  Vec3 centre = Vec3::Zero();  // [m]
  double radius = 0;           // [m]
  int material = 0;
};

// `[[generation.cut]]`: remove the particles whose centre is inside (or outside) a region.
struct CutSpec {
  Region region;
  bool inside = true;  // remove those inside (true) or outside (false) the region
};

// `[generation.size]`: how the random spheres' radii are drawn (generation/size_distribution.hpp).
struct SizeSpec {
  enum class Kind { Uniform, Normal, LogNormal, Sieve };
  Kind kind = Kind::Uniform;         // uniform in radius on [radius_min, radius_max]: the default
  double mean_radius = 0;            // Normal: mean of the untruncated radius distribution [m]
  double std_radius = 0;             // Normal: its standard deviation [m]
  double median_radius = 0;          // LogNormal: median of the untruncated radius distribution [m]
  double geometric_std = 1;          // LogNormal: exp(standard deviation of ln r), > 1
  std::vector<std::pair<double, double>> sieve;  // Sieve: (diameter [m], cumulative mass fraction passing)
  bool given = false;  // [generation.size] present: the radii are drawn first (uniform too), not per attempt
};

struct GenerationSpec {
  Vec3 box_min, box_max;  // region to fill [m]
  int count = 0;          // random spheres, placed after `placed`
  std::vector<PlacedSphere> placed;  // ids 0..placed.size()-1, in file order
  double radius_min = 0, radius_max = 0;  // [m]: the sizes' bounds (a sieve curve's first and last diameter / 2)
  SizeSpec size;                          // how radii are drawn in [radius_min, radius_max]
  std::vector<std::pair<int, double>> material_fractions;  // material index, fraction (sum 1)
  std::uint64_t seed = 1;
  SettleSpec settle;
  std::vector<CutSpec> cuts;  // applied in order after settling, before the checkpoint is written
};

struct CopySpec {
  int nx = 1, ny = 1, nz = 1;
  std::optional<Vec3> spacing;  // tile period [m]; default: the primary set's bounding box
  SettleSpec settle;
};

struct CompactSpec {
  std::vector<std::string> walls;  // walls (or wall groups) moved inward
  double speed = 0;                // [m/s]
  double target_stress = 0;        // [Pa] mean normal stress on the moving walls; 0 when not given
  double target_porosity = 0;      // 0 when not given (exactly one of the two is given)
  double max_time = 1.0;           // [s]
  SettleSpec settle;               // relaxation after the target is reached
};

struct ActionSpec {
  enum class Kind { Remove, ResetReference, Bond, Fix, Release };
  Kind kind = Kind::Remove;
  std::optional<Region> region;  // Remove, Fix (required); Release (none: every particle)
  bool inside = true;   // Remove, Fix, Release: particles inside (true) or outside (false) the region
  bool walls = false;   // Bond: also bond the particles touching walls
  // Bond: a pair apart by less than gap x the smaller radius (a sphere and a wall: x its radius)
  // counts as touching; the default, round-off of touching positions, is the gap below which a
  // bond of a law without tension still holds (contact/normal_laws.hpp).
  double gap = kBondTouchTolerance;
};

// One `[[stage.motion]]` entry: one part of a wall's motion. Entries selecting the same wall
// compose (a drum rotates and vibrates); a later entry of the same part replaces the earlier one,
// and `fixed` clears what came before.
struct MotionSpec {
  enum class Part { Fixed, Translate, Table, Vibrate, Rotate };
  std::string wall;  // a wall name, or a group prefix ("box" matches "box.zmin", ...)
  Part part = Part::Fixed;
  WallMotion motion;  // the fields of `part`
  void apply_to(WallMotion& m) const;
};

// `[[stage.servo]]`: a wall group translating to hold a target normal stress (control/servo.hpp).
struct ServoSpec {
  std::string wall;                // wall or group name
  double target_stress = 0;        // [Pa], compression positive
  double max_speed = 0;            // [m/s]
  double gain = 0.2;               // fraction of the force error corrected per step
  double integral_time = 0;        // [s] T_i of the integral action; 0 = proportional only
  std::optional<Vec3> direction;   // direction of compression; default: the group's normal towards the particles
};

// `[[stage.insert]]`: particles poured into a region during the stage (generation/insertion.hpp).
// Particle i of the group is due once the amount placed before it (i for count_rate, the mass of
// particles 0..i-1 for mass_rate) is at most rate x (time since `start`, up to `end`).
struct InsertSpec {
  enum class Rate { Count, Mass };
  Region region;                          // box, sphere, cylinder of finite length, mesh
  std::vector<std::pair<int, double>> material_fractions;  // material index, fraction (sum 1)
  SizeSpec size;                          // as [generation.size]
  double radius_min = 0, radius_max = 0;  // [m]
  Rate rate_kind = Rate::Count;
  double rate = 0;                        // [1/s] or [kg/s]
  Vec3 velocity = Vec3::Zero();           // initial velocity [m/s]
  double start = 0;                       // [s] since the stage start
  double end = 0;                         // [s] since the stage start; +inf = to the stage end
  double total = 0;                       // at most this many particles (count) or this mass [kg]; +inf = no cap
  Rate total_kind = Rate::Count;
  std::uint64_t seed = 1;
  long every = 1;                         // steps between insertion events (from the stage start)
  int attempts = 100;                     // positions tried per particle and event before deferring it
};

// A group of particles chosen at the start of a stage by material, id range and region: a
// particle belongs when it meets every criterion given (at least one is).
struct ParticleGroupSpec {
  int material = -1;               // material index; -1: any
  bool by_ids = false;             // ids in [id_first, id_last]
  Index id_first = 0, id_last = 0;
  std::optional<Region> region;    // centre inside (or outside, `inside` = false) the region
  bool inside = true;
};

// `[[stage.set_velocity]]` (given once, at the stage start) and `[[stage.prescribe]]` (kept for the
// whole stage, forces ignored): a group's velocity and angular velocity.
struct VelocitySpec {
  ParticleGroupSpec group;
  Vec3 velocity = Vec3::Zero();          // [m/s]
  std::optional<Vec3> angular_velocity;  // [rad/s]; set_velocity: none = spins kept; prescribe: none = zero
};

// `[stage.fibres]`: straight fibres placed at random in the sample at the stage start
// (generation/fibre_placement.hpp), each tied to the particles it passes through.
struct FibreSpec {
  long count = 0;                 // fibres to place; 0: by volume_fraction
  double volume_fraction = 0;     // fibre volume / the particles' bounding box; 0: by count
  double length_min = 0, length_max = 0;  // [m], drawn uniformly (equal: one length)
  double diameter = 0;            // [m]
  double youngs_modulus = 0;      // [Pa]
  double tensile_strength = 0;    // [Pa]
  std::uint64_t seed = 1;
};

// `[stage.sink]`: particles whose centre is in the region at a sink event are removed and counted
// (generation/sink.hpp): the sand a well produces.
struct SinkSpec {
  Region region;
  long every = 1;  // steps between sink events (from the stage start)
};

struct StageSpec {
  std::string name;
  double duration = 0;      // [s]
  Interval output_every;  // VTK frame cadence; not given = first and last frame only
  std::optional<Vec3> gravity;  // this stage's gravity [m/s^2]; none: [simulation] gravity
  Interval energy_every;  // energy log cadence (run/energy_log.hpp); not given = none
  Interval health_every;  // health log cadence (run/health_log.hpp); not given = a hundredth of the stage, at least 500 steps
  std::vector<ActionSpec> actions;  // applied in order at the start of the stage
  std::vector<MotionSpec> motions;  // wall motions during the stage (others stay fixed)
  std::vector<ServoSpec> servos;    // servo-controlled wall groups
  std::vector<InsertSpec> inserts;  // particles poured in during the stage
  std::vector<VelocitySpec> set_velocities;  // applied in order at the start, after the actions
  std::vector<VelocitySpec> prescribes;      // groups moved at a set velocity for the whole stage
  std::optional<FluidParams> fluid;          // [stage.fluid]: the fluid's force during the stage
  std::optional<FibreSpec> fibres;           // fibres placed at the start, after the actions
  std::optional<SinkSpec> sink;              // [stage.sink]: particles removed where they enter a region
};

struct Scene {
  std::string path;  // file it came from
  std::string text;  // its full text, stored in every checkpoint
  SimulationSpec simulation;
  std::vector<Material> materials;
  MixingRules mixing;
  std::vector<PairOverride> pairs;  // [[pair]]: explicit parameters for material pairs
  std::vector<WallSpec> walls;
  std::optional<GenerationSpec> generation;
  std::optional<CopySpec> copy;
  std::optional<CompactSpec> compact;
  std::vector<StageSpec> stages;
  // Every other file the scene reads (STL walls, mesh regions), each "fnv1a64=<hex> size=N PATH"
  // (io/file_seal.hpp), in the order first read: a restart compares them, as the scene text.
  std::vector<std::string> files;
  // Plausibility warnings (docs/scene.md, "Warnings"): values the parser accepts but a granular scene
  // does not have (units mistaken, most likely), each "file:line:col: key = value: why". The tools
  // print them on stderr (print_scene_warnings) and run on.
  std::vector<std::string> warnings;

  const StageSpec* stage(const std::string& name) const;
  // A fingerprint of the walls as built (names, materials, every vertex to the bit): the walls
  // come partly from files the scene names (STL), which the scene text does not hold, so a
  // restart compares this too. "fnv1a64=<16 hex digits> elements=<n>".
  std::string walls_fingerprint() const;
};

// Does a wall name match a name or a group prefix given in the scene?
bool wall_matches(const std::string& wall_name, const std::string& pattern);

}  // namespace dem
