// VTK output read back with VTK's own readers: what ParaView will see must be exactly what the
// simulation holds. Failed writes throw IoError and leave neither a partial file nor a temporary.
#include <gtest/gtest.h>
#include <unistd.h>
#include <vtkAbstractArray.h>
#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkDataArray.h>
#include <vtkErrorCode.h>
#include <vtkFieldData.h>
#include <vtkIdList.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkStringArray.h>
#include <vtkUnstructuredGrid.h>
#include <vtkVariant.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLUnstructuredGridReader.h>
#include <vtkXMLUtilities.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "io/vtk_output.hpp"

namespace dem {
namespace {

namespace fs = std::filesystem;

vtkSmartPointer<vtkUnstructuredGrid> read_vtu(const fs::path& path) {
  auto reader = vtkSmartPointer<vtkXMLUnstructuredGridReader>::New();
  reader->SetFileName(path.c_str());
  reader->Update();
  EXPECT_EQ(reader->GetErrorCode(), vtkErrorCode::NoError) << path;
  return reader->GetOutput();
}

vtkSmartPointer<vtkPolyData> read_vtp(const fs::path& path) {
  auto reader = vtkSmartPointer<vtkXMLPolyDataReader>::New();
  reader->SetFileName(path.c_str());
  reader->Update();
  EXPECT_EQ(reader->GetErrorCode(), vtkErrorCode::NoError) << path;
  return reader->GetOutput();
}

// A signed integer array of the given width, whatever concrete class the reader chose.
bool is_int(vtkDataArray* a, int bits) {
  const double lowest = bits == 64 ? static_cast<double>(std::numeric_limits<std::int64_t>::min())
                                   : static_cast<double>(std::numeric_limits<std::int32_t>::min());
  return a->GetDataTypeSize() == bits / 8 && a->GetDataTypeMin() == lowest;
}

// Names of the entries of `dir`, to check that nothing (no temporary) was left behind.
std::vector<std::string> listing(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

class VtkOutputTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("dem_vtk_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);

    // Ids far apart (one beyond 32 bits), every property distinct per particle.
    p_.add(7, Vec3(0.1, 0.2, 0.3), 0.001, 2500, 1);
    p_.add((Index{1} << 40) + 3, Vec3(-1.5, 2.25, 1e-9), 0.0025, 2500, 0);
    p_.add(42, Vec3(3.0, -0.125, 7.5), 1.0 / 3.0, 7800, 2);
    for (std::size_t i = 0; i < p_.size(); ++i) {
      const double s = static_cast<double>(i + 1);
      p_.v[i] = Vec3(0.5 * s, -0.1 * s, 1.0 / (3.0 * s));
      p_.w[i] = Vec3(10.0 * s, 0.0, -2.0 / 7.0 * s);
    }
    names_ = {"glass", "steel", "rubber"};
    disp_ = {Vec3(0.001, 0, 0), Vec3(0, -0.002, 0.5), Vec3(3, 4, 12)};

    Wall tri{"floor", 1, {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}, {}};
    Wall quad{"lid", 2, {Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(1, 1, 1), Vec3(0, 1, 1)}, {}};
    quad.motion.velocity = Vec3(0, 0, 0.5);  // binary-exact numbers: at t = 0.75 the lid is 0.25 higher
    quad.motion.t0 = 0.25;
    walls_ = {tri, quad};
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path dir_;
  Particles p_;
  std::vector<std::string> names_;
  std::vector<Vec3> disp_;
  std::vector<Wall> walls_;
};

TEST_F(VtkOutputTest, ParticlesRoundTripExactly) {
  const fs::path path = dir_ / "frames" / "stage" / "particles_000000.vtu";  // parents do not exist yet
  write_particles_vtu(path.string(), p_, names_, &disp_);
  EXPECT_EQ(listing(path.parent_path()), std::vector<std::string>{"particles_000000.vtu"});

  vtkSmartPointer<vtkUnstructuredGrid> g = read_vtu(path);
  const vtkIdType n = static_cast<vtkIdType>(p_.size());
  ASSERT_EQ(g->GetNumberOfPoints(), n);
  ASSERT_EQ(g->GetNumberOfCells(), n);

  vtkPointData* pd = g->GetPointData();
  vtkDataArray* id = pd->GetArray("id");
  vtkDataArray* radius = pd->GetArray("radius");
  vtkDataArray* vel = pd->GetArray("velocity");
  vtkDataArray* ang = pd->GetArray("angular_velocity");
  vtkDataArray* mat = pd->GetArray("material");
  vtkDataArray* dsp = pd->GetArray("displacement");
  vtkDataArray* dmag = pd->GetArray("displacement_magnitude");
  ASSERT_TRUE(id && radius && vel && ang && mat && dsp && dmag);
  EXPECT_TRUE(is_int(id, 64));
  EXPECT_TRUE(is_int(mat, 32));
  EXPECT_EQ(radius->GetNumberOfComponents(), 1);
  EXPECT_EQ(vel->GetNumberOfComponents(), 3);
  EXPECT_EQ(ang->GetNumberOfComponents(), 3);
  EXPECT_EQ(dsp->GetNumberOfComponents(), 3);
  EXPECT_EQ(dmag->GetNumberOfComponents(), 1);

  for (vtkIdType i = 0; i < n; ++i) {
    SCOPED_TRACE(i);
    EXPECT_EQ(g->GetCellType(i), VTK_VERTEX);
    auto cell = vtkSmartPointer<vtkIdList>::New();
    g->GetCellPoints(i, cell);
    ASSERT_EQ(cell->GetNumberOfIds(), 1);
    EXPECT_EQ(cell->GetId(0), i);

    double x[3];
    g->GetPoint(i, x);
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(x[c], p_.x[i][c]);
      EXPECT_EQ(vel->GetComponent(i, c), p_.v[i][c]);
      EXPECT_EQ(ang->GetComponent(i, c), p_.w[i][c]);
      EXPECT_EQ(dsp->GetComponent(i, c), disp_[i][c]);
    }
    EXPECT_EQ(id->GetVariantValue(i).ToTypeInt64(), p_.id[i]);
    EXPECT_EQ(radius->GetComponent(i, 0), p_.radius[i]);
    EXPECT_EQ(mat->GetVariantValue(i).ToInt(), p_.material[i]);
    EXPECT_EQ(dmag->GetComponent(i, 0), disp_[i].norm());
  }
  EXPECT_EQ(dmag->GetComponent(2, 0), 13.0);  // |(3, 4, 12)|

  auto* mn = vtkStringArray::SafeDownCast(g->GetFieldData()->GetAbstractArray("material_names"));
  ASSERT_NE(mn, nullptr);
  ASSERT_EQ(mn->GetNumberOfValues(), 3);
  for (vtkIdType k = 0; k < 3; ++k) EXPECT_EQ(mn->GetValue(k), names_[k]);
}

TEST_F(VtkOutputTest, ParticlesWithoutDisplacementHaveNoDisplacementArrays) {
  const fs::path path = dir_ / "p.vtu";
  write_particles_vtu(path.string(), p_, names_);
  vtkSmartPointer<vtkUnstructuredGrid> g = read_vtu(path);
  ASSERT_EQ(g->GetNumberOfPoints(), 3);
  EXPECT_NE(g->GetPointData()->GetArray("velocity"), nullptr);
  EXPECT_EQ(g->GetPointData()->GetArray("displacement"), nullptr);
  EXPECT_EQ(g->GetPointData()->GetArray("displacement_magnitude"), nullptr);
}

TEST_F(VtkOutputTest, EmptyParticleSetIsAValidFile) {
  const fs::path path = dir_ / "empty.vtu";
  write_particles_vtu(path.string(), Particles{}, names_);
  vtkSmartPointer<vtkUnstructuredGrid> g = read_vtu(path);
  EXPECT_EQ(g->GetNumberOfPoints(), 0);
  EXPECT_EQ(g->GetNumberOfCells(), 0);
}

TEST_F(VtkOutputTest, RewriteReplacesTheFile) {
  const fs::path path = dir_ / "p.vtu";
  write_particles_vtu(path.string(), p_, names_);
  std::vector<bool> keep{true, false, false};
  p_.keep_only(keep);
  write_particles_vtu(path.string(), p_, names_);
  EXPECT_EQ(read_vtu(path)->GetNumberOfPoints(), 1);
  EXPECT_EQ(listing(dir_), std::vector<std::string>{"p.vtu"});
}

TEST_F(VtkOutputTest, DisplacementOfTheWrongSizeIsRejected) {
  const fs::path path = dir_ / "p.vtu";
  disp_.pop_back();
  EXPECT_THROW(write_particles_vtu(path.string(), p_, names_, &disp_), std::invalid_argument);
  EXPECT_TRUE(listing(dir_).empty());
}

TEST_F(VtkOutputTest, WallsAtTheGivenTime) {
  const fs::path path = dir_ / "walls.vtp";
  const double t = 0.75;
  ASSERT_NE(walls_[1].vertices_at(t)[0], walls_[1].base[0]);  // the lid has moved
  write_walls_vtp(path.string(), walls_, t);

  vtkSmartPointer<vtkPolyData> poly = read_vtp(path);
  ASSERT_EQ(poly->GetNumberOfCells(), 2);
  ASSERT_EQ(poly->GetNumberOfPolys(), 2);
  ASSERT_EQ(poly->GetNumberOfPoints(), 7);

  const std::vector<std::vector<Vec3>> expected = {
      {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)},
      {Vec3(0, 0, 1.25), Vec3(1, 0, 1.25), Vec3(1, 1, 1.25), Vec3(0, 1, 1.25)},
  };
  vtkDataArray* index = poly->GetCellData()->GetArray("wall_index");
  vtkDataArray* mat = poly->GetCellData()->GetArray("material");
  ASSERT_TRUE(index && mat);
  EXPECT_TRUE(is_int(index, 32));
  EXPECT_TRUE(is_int(mat, 32));
  for (vtkIdType k = 0; k < 2; ++k) {
    SCOPED_TRACE(k);
    EXPECT_EQ(poly->GetCellType(k), k == 0 ? VTK_TRIANGLE : VTK_QUAD);
    auto cell = vtkSmartPointer<vtkIdList>::New();
    poly->GetCellPoints(k, cell);
    ASSERT_EQ(cell->GetNumberOfIds(), static_cast<vtkIdType>(expected[k].size()));
    for (vtkIdType j = 0; j < cell->GetNumberOfIds(); ++j) {
      double x[3];
      poly->GetPoint(cell->GetId(j), x);
      for (int c = 0; c < 3; ++c) EXPECT_EQ(x[c], expected[k][j][c]) << "vertex " << j << " component " << c;
    }
    EXPECT_EQ(index->GetVariantValue(k).ToInt(), k);
    EXPECT_EQ(mat->GetVariantValue(k).ToInt(), walls_[k].material);
  }

  auto* wn = vtkStringArray::SafeDownCast(poly->GetFieldData()->GetAbstractArray("wall_names"));
  ASSERT_NE(wn, nullptr);
  ASSERT_EQ(wn->GetNumberOfValues(), 2);
  EXPECT_EQ(wn->GetValue(0), "floor");
  EXPECT_EQ(wn->GetValue(1), "lid");
  EXPECT_EQ(listing(dir_), std::vector<std::string>{"walls.vtp"});
}

TEST_F(VtkOutputTest, PvdListsFramesWithExactTimes) {
  const fs::path path = dir_ / "out" / "stage_particles.pvd";
  const std::vector<PvdEntry> entries = {
      {0.0, "stage/particles_000000.vtu"},
      {0.1, "stage/particles_000001.vtu"},
      {1.0 / 3.0, "stage/particles_000002.vtu"},
      {2.5e-7 + 1e-23, "odd & <name>.vtu"},  // markup characters must be escaped
  };
  write_pvd(path.string(), {{9.0, "old.vtu"}});
  write_pvd(path.string(), entries);  // replaces the first version

  vtkXMLDataElement* root = vtkXMLUtilities::ReadElementFromFile(path.c_str());
  ASSERT_NE(root, nullptr) << "not well-formed XML";
  EXPECT_STREQ(root->GetName(), "VTKFile");
  EXPECT_STREQ(root->GetAttribute("type"), "Collection");
  ASSERT_EQ(root->GetNumberOfNestedElements(), 1);
  vtkXMLDataElement* coll = root->GetNestedElement(0);
  EXPECT_STREQ(coll->GetName(), "Collection");
  ASSERT_EQ(coll->GetNumberOfNestedElements(), static_cast<int>(entries.size()));
  for (int k = 0; k < coll->GetNumberOfNestedElements(); ++k) {
    SCOPED_TRACE(k);
    vtkXMLDataElement* ds = coll->GetNestedElement(k);
    EXPECT_STREQ(ds->GetName(), "DataSet");
    ASSERT_NE(ds->GetAttribute("timestep"), nullptr);
    ASSERT_NE(ds->GetAttribute("file"), nullptr);
    EXPECT_EQ(std::strtod(ds->GetAttribute("timestep"), nullptr), entries[k].time);
    EXPECT_EQ(std::string(ds->GetAttribute("file")), entries[k].file);
  }
  root->Delete();
  EXPECT_EQ(listing(path.parent_path()), std::vector<std::string>{"stage_particles.pvd"});
}

// A regular file where a directory is needed: the parent cannot be created.
TEST_F(VtkOutputTest, UnwritableLocationThrowsAndLeavesNothing) {
  const fs::path blocker = dir_ / "blocker";
  std::ofstream(blocker) << "not a directory\n";
  const fs::path base = blocker / "sub";
  const auto expect_io_error = [&](auto&& write, const fs::path& path) {
    try {
      write(path.string());
      ADD_FAILURE() << "no IoError for " << path;
    } catch (const IoError& e) {
      EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
    }
  };
  expect_io_error([&](const std::string& s) { write_particles_vtu(s, p_, names_, &disp_); }, base / "p.vtu");
  expect_io_error([&](const std::string& s) { write_walls_vtp(s, walls_, 0.0); }, base / "w.vtp");
  expect_io_error([&](const std::string& s) { write_pvd(s, {{0.0, "p.vtu"}}); }, base / "p.pvd");
  // write_particles_vtu directly under the file: the parent exists but is not a directory.
  expect_io_error([&](const std::string& s) { write_particles_vtu(s, p_, names_); }, blocker / "p.vtu");
  EXPECT_EQ(listing(dir_), std::vector<std::string>{"blocker"});
  EXPECT_TRUE(fs::is_regular_file(blocker));
}

// The temporary cannot be created (its name is taken by a non-empty directory): VTK's writer fails.
TEST_F(VtkOutputTest, WriterFailureThrowsAndLeavesNoTarget) {
  for (const char* name : {"p.vtu", "w.vtp", "s.pvd"}) {
    fs::create_directories(dir_ / (std::string(name) + ".tmp") / "keep");
  }
  EXPECT_THROW(write_particles_vtu((dir_ / "p.vtu").string(), p_, names_), IoError);
  EXPECT_THROW(write_walls_vtp((dir_ / "w.vtp").string(), walls_, 0.0), IoError);
  EXPECT_THROW(write_pvd((dir_ / "s.pvd").string(), {{0.0, "p.vtu"}}), IoError);
  EXPECT_EQ(listing(dir_), (std::vector<std::string>{"p.vtu.tmp", "s.pvd.tmp", "w.vtp.tmp"}));
}

// The finished temporary cannot be renamed (the target is a directory): the temporary is removed.
TEST_F(VtkOutputTest, RenameFailureThrowsAndRemovesTheTemporary) {
  for (const char* name : {"p.vtu", "w.vtp", "s.pvd"}) fs::create_directories(dir_ / name);
  EXPECT_THROW(write_particles_vtu((dir_ / "p.vtu").string(), p_, names_), IoError);
  EXPECT_THROW(write_walls_vtp((dir_ / "w.vtp").string(), walls_, 0.0), IoError);
  EXPECT_THROW(write_pvd((dir_ / "s.pvd").string(), {{0.0, "p.vtu"}}), IoError);
  EXPECT_EQ(listing(dir_), (std::vector<std::string>{"p.vtu", "s.pvd", "w.vtp"}));
}

}  // namespace
}  // namespace dem
