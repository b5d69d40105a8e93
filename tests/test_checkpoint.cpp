// Checkpoint round trip, and damaged or foreign files detected with a clear IoError instead of
// being read as wrong numbers.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>

#include "core/error.hpp"
#include "generation/fill.hpp"
#include "io/checkpoint.hpp"
#include "io/file_seal.hpp"

namespace dem {
namespace {

namespace fs = std::filesystem;

class CheckpointTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("dem_ckpt_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    Material m;
    m.name = "glass";
    Material steel;
    steel.name = "steel", steel.density = 7800, steel.kn = 2e5, steel.kt = 1e5, steel.friction_angle = 20, steel.restitution = 0.4,
    steel.restitution_t = 0.6;
    PairOverride glass_steel;  // a [[pair]]: the checkpoint must hold it (schema 3)
    glass_steel.b = 1;
    glass_steel.set("friction_angle", 33);
    glass_steel.set("no_viscous_attraction", 1);
    sim_.materials = MaterialTable({m, steel}, {}, {glass_steel});
    sim_.walls.push_back(Wall{"floor", 1, {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)}, {}});
    WallMotion vib;  // every part of a motion at once: it must come back exactly
    vib.frequency = 20;
    vib.amplitude = 1e-3;
    vib.velocity = Vec3(0, 0, 0.01);
    vib.table_time = {0, 0.01, 0.5};
    vib.table_offset = {Vec3::Zero(), Vec3(0.001, 0, 0), Vec3(0.001, 0.002, 0)};
    vib.centre = Vec3(0.5, 0.5, 0);
    vib.axis = Vec3(0, 0, 1);
    vib.angular_speed = 3;
    sim_.walls[0].start_motion(vib, 0.0);
    GenerationSpec g;
    g.box_min = Vec3(0, 0, 0);
    g.box_max = Vec3(0.02, 0.02, 0.02);
    g.count = 150;
    g.radius_min = 0.001;
    g.radius_max = 0.0015;
    g.material_fractions = {{0, 1.0}};
    std::mt19937_64 rng(11);
    fill_random(sim_, g, rng);
    // Random velocities towards the floor so that both kinds of contact exist when it is written.
    std::uniform_real_distribution<double> u(-0.5, 0.5);
    for (Vec3& v : sim_.particles.v) v = Vec3(u(rng), u(rng), u(rng) - 0.5);
    sim_.dt = 0.1 * sim_.critical_time_step();
    for (int s = 0; s < 50000 && (s < 3000 || sim_.pair_contacts().size() == 0 || sim_.wall_contacts().size() == 0); ++s) sim_.advance();
    meta_.writer = "test";
    meta_.scene_text = "# scene text\n";
    meta_.scene_path = "x.toml";
    meta_.run = {"shake", 10, 20, 0.5, {0.1, 0.2}, {0.25, -1e-3}};
    path_ = (dir_ / "a.h5").string();
    write_checkpoint(path_, sim_, meta_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  void expect_rejected(const std::string& path, const std::string& fragment) {
    Simulation s;
    CheckpointMeta m;
    try {
      read_checkpoint(path, s, m);
      FAIL() << "read_checkpoint accepted a bad file: " << fragment;
    } catch (const IoError& e) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << "the message names the file: " << e.what();
    }
  }

  // After editing a checkpoint with HDF5, seal it again so that the reader's own checks (not the
  // whole-file seal) are what the test exercises.
  static void reseal(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::vector<char> image((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    in.close();
    seal_image(image);
    std::ofstream(path, std::ios::binary).write(image.data(), static_cast<std::streamsize>(image.size()));
  }

  fs::path dir_;
  Simulation sim_;
  CheckpointMeta meta_;
  std::string path_;
};

TEST_F(CheckpointTest, RoundTripIsExact) {
  ASSERT_GT(sim_.pair_contacts().size(), 0u);
  ASSERT_GT(sim_.wall_contacts().size(), 0u);
  Simulation s;
  CheckpointMeta m;
  read_checkpoint(path_, s, m);
  EXPECT_EQ(s.particles.id, sim_.particles.id);
  EXPECT_EQ(s.particles.x, sim_.particles.x);
  EXPECT_EQ(s.particles.v, sim_.particles.v);
  EXPECT_EQ(s.particles.w, sim_.particles.w);
  EXPECT_EQ(s.particles.radius, sim_.particles.radius);
  EXPECT_EQ(s.particles.mass, sim_.particles.mass);
  EXPECT_EQ(s.pair_contacts().key_i, sim_.pair_contacts().key_i);
  EXPECT_EQ(s.pair_contacts().spring, sim_.pair_contacts().spring);
  EXPECT_EQ(s.wall_contacts().key_j, sim_.wall_contacts().key_j);
  EXPECT_EQ(s.time, sim_.time);
  EXPECT_EQ(s.step, sim_.step);
  EXPECT_EQ(s.dt, sim_.dt);
  EXPECT_EQ(s.walls[0].vertices_at(s.time), sim_.walls[0].vertices_at(sim_.time));
  const WallMotion &a = s.walls[0].motion, &b = sim_.walls[0].motion;
  EXPECT_EQ(a.table_time, b.table_time);
  EXPECT_EQ(a.table_offset, b.table_offset);
  EXPECT_EQ(a.velocity, b.velocity);
  EXPECT_EQ(a.centre, b.centre);
  EXPECT_EQ(a.axis, b.axis);
  EXPECT_EQ(a.angular_speed, b.angular_speed);
  EXPECT_EQ(a.t0, b.t0);
  EXPECT_EQ(s.materials.materials()[1].kt, 1e5);
  // Every pair's constants as written, the [[pair]] override included (by hand: tan 33 degrees).
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b) {
      const PairParams &p = s.materials.pair(a, b), &q = sim_.materials.pair(a, b);
      EXPECT_EQ(p.mu, q.mu);
      EXPECT_EQ(p.kn, q.kn);
      EXPECT_EQ(p.damping_n, q.damping_n);
      EXPECT_EQ(p.no_viscous_attraction, q.no_viscous_attraction);
    }
  EXPECT_NEAR(s.materials.pair(1, 0).mu, 0.6494075931975106, 1e-15);
  EXPECT_TRUE(s.materials.pair(0, 1).no_viscous_attraction);
  EXPECT_FALSE(s.materials.pair(1, 1).no_viscous_attraction);
  EXPECT_EQ(m.run.stage, "shake");
  EXPECT_EQ(m.run.frame_times, meta_.run.frame_times);
  EXPECT_EQ(m.run.servo_integral, meta_.run.servo_integral);
  EXPECT_EQ(m.scene_text, meta_.scene_text);

  // Continuing from the checkpoint gives the same bits as continuing in memory.
  for (int k = 0; k < 500; ++k) s.advance(), sim_.advance();
  EXPECT_EQ(s.particles.x, sim_.particles.x);
  EXPECT_EQ(s.particles.w, sim_.particles.w);
}

// The writer frees the compacted contact lists it used (a week-long run would otherwise carry a
// copy of its contacts between checkpoints); they come back the same on demand, and the counts
// that need no copy agree with them.
TEST_F(CheckpointTest, WritingFreesTheContactViewsWhichComeBackTheSame) {
  const ContactList pairs = sim_.pair_contacts(), walls = sim_.wall_contacts();
  ASSERT_GT(pairs.size(), 0u);
  EXPECT_EQ(sim_.pair_contact_count(), pairs.size());
  EXPECT_EQ(sim_.wall_contact_count(), walls.size());
  write_checkpoint(path_, sim_, meta_);
  EXPECT_EQ(sim_.pair_contacts().key_i, pairs.key_i);
  EXPECT_EQ(sim_.pair_contacts().key_j, pairs.key_j);
  EXPECT_EQ(sim_.pair_contacts().spring, pairs.spring);
  EXPECT_EQ(sim_.wall_contacts().key_i, walls.key_i);
  sim_.release_contact_views();
  EXPECT_EQ(sim_.wall_contacts().spring, walls.spring);
  EXPECT_EQ(sim_.pair_contacts().size(), sim_.pair_contact_count());
}

// Periodic boundaries (the period, each particle's image counts) and fixed particles come back
// exactly, and a run continued from the file equals one continued in memory.
TEST_F(CheckpointTest, PeriodicAndFixedRoundTrip) {
  // The cloud has spread beyond the generation box (no side walls): a period around it, one
  // diameter wider, so that wrapping makes no overlap.
  PeriodicBox box;
  box.axis = {true, false, true};
  box.lo = Vec3(INFINITY, 0, -0.01);  // z: a period far above anything the cloud reaches
  box.hi = Vec3(-INFINITY, 0, 0.1);
  for (const Vec3& x : sim_.particles.x) box.lo.x() = std::min(box.lo.x(), x.x() - 0.0015), box.hi.x() = std::max(box.hi.x(), x.x() + 0.0015);
  sim_.set_periodic(box);
  sim_.params.max_energy_gain = 0;  // the test adds a drift by hand: energy the check would flag
  std::size_t fixed = 0;
  for (std::size_t k = 0; k < sim_.particles.size(); ++k) {
    if (k % 4 == 0) sim_.particles.fixed[k] = 1, sim_.particles.v[k] = sim_.particles.w[k] = Vec3::Zero(), ++fixed;
    else sim_.particles.v[k].x() += 3.0;  // a drift along x: some cross the boundary
  }
  for (int k = 0; k < 1000; ++k) sim_.advance();
  bool crossed = false;
  for (const Vec3i& i : sim_.particles.image) crossed = crossed || i != Vec3i::Zero();
  ASSERT_TRUE(crossed) << "some particle must have crossed a periodic boundary";
  write_checkpoint(path_, sim_, meta_);
  Simulation s;
  CheckpointMeta m;
  read_checkpoint(path_, s, m);
  EXPECT_TRUE(s.periodic == box);
  EXPECT_EQ(s.particles.image, sim_.particles.image);
  EXPECT_EQ(s.particles.fixed, sim_.particles.fixed);
  EXPECT_EQ(std::count(s.particles.fixed.begin(), s.particles.fixed.end(), 1), static_cast<long>(fixed));
  for (int k = 0; k < 500; ++k) s.advance(), sim_.advance();
  EXPECT_EQ(s.particles.x, sim_.particles.x);
  EXPECT_EQ(s.particles.v, sim_.particles.v);
  EXPECT_EQ(s.particles.image, sim_.particles.image);
}

TEST_F(CheckpointTest, MissingFile) { expect_rejected((dir_ / "none.h5").string(), "no such checkpoint"); }

TEST_F(CheckpointTest, NotHdf5) {
  const std::string p = (dir_ / "text.h5").string();
  std::ofstream(p) << "particles 1 2 3\n";
  expect_rejected(p, "not a dem checkpoint");
}

TEST_F(CheckpointTest, Truncated) {
  const std::string p = (dir_ / "cut.h5").string();
  fs::copy_file(path_, p);
  fs::resize_file(p, fs::file_size(p) / 2);
  Simulation s;
  CheckpointMeta m;
  EXPECT_THROW(read_checkpoint(p, s, m), IoError);
}

TEST_F(CheckpointTest, ForeignHdf5) {
  const std::string p = (dir_ / "foreign.h5").string();
  hid_t f = H5Fcreate(p.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  hsize_t n = 4;
  hid_t sp = H5Screate_simple(1, &n, nullptr);
  hid_t d = H5Dcreate2(f, "/positions", H5T_NATIVE_DOUBLE, sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  H5Dclose(d);
  H5Sclose(sp);
  H5Fclose(f);
  expect_rejected(p, "not a dem checkpoint");
}

// Edits the file's schema_version to v and, when given, deletes the group `drop` (unsealed).
void set_schema_version(const std::string& path, int v, const char* drop = nullptr) {
  hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  hid_t a = H5Aopen(f, "schema_version", H5P_DEFAULT);
  H5Awrite(a, H5T_NATIVE_INT, &v);
  H5Aclose(a);
  if (drop) H5Ldelete(f, drop, H5P_DEFAULT);
  H5Fclose(f);
}

TEST_F(CheckpointTest, WrongSchemaVersion) {
  set_schema_version(path_, 99);
  expect_rejected(path_, "does not match its seal");  // an edited file is refused as such
  reseal(path_);
  expect_rejected(path_, "schema version 99");
}

// A schema 2 file (before [[pair]] overrides were stored) is still read, without overrides.
TEST_F(CheckpointTest, SchemaTwoIsReadWithoutPairOverrides) {
  set_schema_version(path_, 2, "/pairs");
  reseal(path_);
  Simulation s;
  CheckpointMeta m;
  read_checkpoint(path_, s, m);
  EXPECT_TRUE(s.materials.overrides().empty());
  EXPECT_EQ(s.materials.pair(0, 1).mu, std::tan(20 * (M_PI / 180)));  // mixed: the smaller angle
  EXPECT_EQ(s.particles.x, sim_.particles.x);
}

// A schema 3 file (before tangential laws were stored) is read with every tangential law coulomb;
// a schema 4 file without them is damaged.
TEST_F(CheckpointTest, SchemaThreeIsReadWithCoulombSprings) {
  set_schema_version(path_, 4, "/materials/tangential");
  reseal(path_);
  expect_rejected(path_, "/materials/tangential is missing");
  set_schema_version(path_, 3, "/pairs/tangential");
  reseal(path_);
  Simulation s;
  CheckpointMeta m;
  read_checkpoint(path_, s, m);
  EXPECT_EQ(s.materials.pair(0, 1).tangential, TangentialLaw::Coulomb);
  EXPECT_EQ(s.materials.pair(0, 1).mu, std::tan(33 * (M_PI / 180))) << "the pair's own angle";
}

// The explicit dashpot (a material's flag and a pair's) comes back; a file written before the flag
// existed (its datasets deleted here) reads with it off, as that build ran.
TEST_F(CheckpointTest, ExplicitDashpotRoundTripsAndIsOffInOlderFiles) {
  std::vector<Material> mats = sim_.materials.materials();
  mats[1].explicit_dashpot = true;
  PairOverride pair;
  pair.b = 0, pair.set("explicit_dashpot", 1);  // glass with itself
  sim_.materials = MaterialTable(mats, {}, {pair});
  write_checkpoint(path_, sim_, meta_);
  {
    Simulation s;
    CheckpointMeta m;
    read_checkpoint(path_, s, m);
    EXPECT_FALSE(s.materials.materials()[0].explicit_dashpot);
    EXPECT_TRUE(s.materials.materials()[1].explicit_dashpot);
    EXPECT_TRUE(s.materials.pair(0, 0).explicit_dashpot) << "the pair's own";
    EXPECT_TRUE(s.materials.pair(0, 1).explicit_dashpot) << "either material's";
    EXPECT_TRUE(s.materials.pair(1, 1).explicit_dashpot);
  }
  set_schema_version(path_, 4, "/materials/explicit_dashpot");
  set_schema_version(path_, 4, "/pairs/explicit_dashpot");
  reseal(path_);
  Simulation s;
  CheckpointMeta m;
  read_checkpoint(path_, s, m);
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b) EXPECT_FALSE(s.materials.pair(a, b).explicit_dashpot) << a << " " << b;
}

// Tangential and rolling laws, a material's and a pair's, come back with the constants they
// derive, and so does the rolling history of each contact.
TEST_F(CheckpointTest, TangentialAndRollingLawsRoundTrip) {
  Material glass, steel;
  glass.name = "glass", glass.young_modulus = 6e10, glass.poisson_ratio = 0.23;
  steel.name = "steel", steel.young_modulus = 2e11, steel.poisson_ratio = 0.3, steel.tangential = TangentialLaw::Mindlin;
  steel.rolling = RollingLaw::ElasticPlastic, steel.rolling_friction = 0.2;
  PairOverride pair;
  pair.b = 1, pair.tangential = TangentialLaw::Mindlin, pair.rolling = RollingLaw::ConstantTorque;
  pair.set("rolling_friction", 0.05);
  sim_.materials = MaterialTable({glass, steel}, {}, {pair});
  ContactList pairs = sim_.pair_contacts(), walls = sim_.wall_contacts();
  ASSERT_GT(pairs.size(), 0u);
  for (std::size_t k = 0; k < pairs.size(); ++k) pairs.rolling[k] = Vec3(1e-6 * k, -2e-7, 3e-9 * k);
  sim_.set_contacts(pairs, walls);
  write_checkpoint(path_, sim_, meta_);
  Simulation s;
  CheckpointMeta m;
  read_checkpoint(path_, s, m);
  EXPECT_EQ(s.materials.materials()[0].tangential, TangentialLaw::Coulomb);
  EXPECT_EQ(s.materials.materials()[1].tangential, TangentialLaw::Mindlin);
  ASSERT_EQ(s.materials.overrides().size(), 1u);
  EXPECT_EQ(s.materials.overrides()[0].tangential, TangentialLaw::Mindlin);
  EXPECT_EQ(s.materials.pair(0, 1).tangential, TangentialLaw::Mindlin);
  EXPECT_EQ(s.materials.pair(0, 1).mindlin_modulus, sim_.materials.pair(0, 1).mindlin_modulus);
  EXPECT_GT(s.materials.pair(0, 1).mindlin_modulus, 0);
  EXPECT_EQ(s.materials.materials()[1].rolling, RollingLaw::ElasticPlastic);
  EXPECT_EQ(s.materials.pair(1, 1).rolling_friction, 0.2);
  EXPECT_EQ(s.materials.pair(0, 1).rolling, RollingLaw::ConstantTorque);
  EXPECT_EQ(s.materials.pair(0, 1).rolling_friction, 0.05);
  EXPECT_EQ(s.pair_contacts().rolling, pairs.rolling);
}

TEST_F(CheckpointTest, MissingDataset) {
  hid_t f = H5Fopen(path_.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  H5Ldelete(f, "/particles/velocity", H5P_DEFAULT);
  H5Fclose(f);
  reseal(path_);
  expect_rejected(path_, "'/particles/velocity' is missing");
}

// A flipped byte inside the position data is caught by the seal and, in a resealed file, by the
// dataset's own Fletcher32 checksum.
TEST_F(CheckpointTest, FlippedByteInData) {
  haddr_t addr = 0;
  hsize_t size = 0;
  {
    hid_t f = H5Fopen(path_.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    hid_t d = H5Dopen2(f, "/particles/position", H5P_DEFAULT);
    hid_t space = H5Dget_space(d);
    hsize_t offset[2];
    unsigned mask = 0;
    ASSERT_GE(H5Dget_chunk_info(d, space, 0, offset, &mask, &addr, &size), 0);
    H5Sclose(space);
    H5Dclose(d);
    H5Fclose(f);
  }
  std::fstream io(path_, std::ios::in | std::ios::out | std::ios::binary);
  const auto at = static_cast<std::streamoff>(kSealBytes + addr + size / 2);  // HDF5 addresses start after the seal
  io.seekg(at);
  char c = 0;
  io.read(&c, 1);
  c ^= 0x10;
  io.seekp(at);
  io.write(&c, 1);
  io.close();
  expect_rejected(path_, "does not match its seal");
  reseal(path_);
  expect_rejected(path_, "'/particles/position' fails its checksum");
}

// A failed write leaves the previous checkpoint intact and no temporary behind.
TEST_F(CheckpointTest, FailedWriteKeepsPreviousFile) {
  const auto before = fs::file_size(path_);
  fs::create_directories(path_ + ".tmp");  // the temporary name cannot be created
  EXPECT_THROW(write_checkpoint(path_, sim_, meta_), IoError);
  fs::remove_all(path_ + ".tmp");
  EXPECT_EQ(fs::file_size(path_), before);
  Simulation s;
  CheckpointMeta m;
  EXPECT_NO_THROW(read_checkpoint(path_, s, m));
}

}  // namespace
}  // namespace dem
