// Mesh walls (SPEC §3: walls "alone or as meshes"; the helical-flow case's drum is a quad mesh,
// fig. 4.4): STL reading and writing, the mesh primitives, and their scene syntax.
// Each check states its tolerance and why. "Round-off" tolerances are a few units in the last
// place of the coordinates involved (the vertices are sums of a handful of products).
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "io/scene_parser.hpp"
#include "io/stl.hpp"
#include "scene_rejects.hpp"
#include "walls/primitives.hpp"
#include "walls/wall.hpp"

namespace dem {
namespace {

namespace fs = std::filesystem;
constexpr double kPi = std::numbers::pi;
constexpr double kEps = std::numeric_limits<double>::epsilon();

class TempDir : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("dem_mesh_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  void write(const std::string& name, const std::string& bytes) const {
    std::ofstream(path(name), std::ios::binary) << bytes;
  }
  std::string slurp(const std::string& name) const {
    std::ifstream in(path(name), std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  }
  fs::path dir_;
};

// The message of the IoError that read_stl throws, or "" if it reads the file.
std::string stl_error(const std::string& file) {
  try {
    read_stl(file);
  } catch (const IoError& e) {
    return e.what();
  }
  return "";
}

double polygon_area(const Polygon& p) {
  Vec3 s = Vec3::Zero();
  for (std::size_t k = 1; k + 1 < p.size(); ++k) s += (p[k] - p[0]).cross(p[k + 1] - p[0]);
  return 0.5 * s.norm();
}

double total_area(const std::vector<Polygon>& mesh) {
  double a = 0;
  for (const Polygon& p : mesh) a += polygon_area(p);
  return a;
}

void expect_valid_elements(const std::vector<Polygon>& mesh) {
  for (std::size_t k = 0; k < mesh.size(); ++k) EXPECT_EQ(polygon_problem(mesh[k]), "") << "element " << k;
}

// Counts the boundary edges of a mesh, comparing vertices with exact equality: an edge used by
// two elements is interior, an edge used once is on the boundary. Gaps or T-junctions between
// neighbours (vertices that differ by round-off) would show up as extra boundary edges. Also
// checks that no edge is used more than twice and that neighbours run along a shared edge in
// opposite directions (consistent orientation).
std::size_t boundary_edges(const std::vector<Polygon>& mesh) {
  using Key = std::array<double, 6>;
  auto key = [](const Vec3& a, const Vec3& b) { return Key{a.x(), a.y(), a.z(), b.x(), b.y(), b.z()}; };
  std::map<Key, int> directed;
  for (const Polygon& p : mesh)
    for (std::size_t k = 0; k < p.size(); ++k) ++directed[key(p[k], p[(k + 1) % p.size()])];
  std::size_t boundary = 0;
  for (const auto& [k, n] : directed) {
    EXPECT_EQ(n, 1) << "an edge is traversed twice in the same direction";
    const Key rev{k[3], k[4], k[5], k[0], k[1], k[2]};
    if (!directed.count(rev)) ++boundary;
  }
  return boundary;
}

std::vector<Triangle> triangulate(const std::vector<Polygon>& mesh) {
  std::vector<Triangle> t;
  for (const Polygon& p : mesh)
    for (std::size_t k = 1; k + 1 < p.size(); ++k) t.push_back({p[0], p[k], p[k + 1]});
  return t;
}

// A test mesh with awkward coordinates: a tilted cylinder far from the origin, plus values
// needing all 17 digits, tiny and large magnitudes.
std::vector<Triangle> sample_triangles() {
  std::vector<Triangle> t = triangulate(cylinder_mesh(Vec3(10.1, -3.7, 0.3), Vec3(1, 2, 3), 0.123456789, 0.7, 12, 2));
  t.push_back({Vec3(0.1, 0.2, 0.3), Vec3(1.0 / 3, 2.0 / 3, -1e-20), Vec3(-12345.678901234567, 1e-7, 3e5)});
  return t;
}

// ---------------------------------------------------------------------------------------- STL

// ASCII writes each coordinate as the shortest text that reads back as the same double
// (std::to_chars), so the round trip is exact: tolerance 0.
TEST_F(TempDir, StlAsciiRoundTripIsExact) {
  const std::vector<Triangle> tris = sample_triangles();
  write_stl_ascii(path("a.stl"), tris, "sample");
  const std::vector<Triangle> back = read_stl(path("a.stl"));
  ASSERT_EQ(back.size(), tris.size());
  for (std::size_t t = 0; t < tris.size(); ++t)
    for (int v = 0; v < 3; ++v) EXPECT_EQ(back[t][v], tris[t][v]) << "triangle " << t << " vertex " << v;
  EXPECT_EQ(slurp("a.stl").rfind("solid sample\n", 0), 0u);
}

// Binary STL stores float32: each coordinate reads back as the nearest float, i.e. exactly
// static_cast<float>(x), within a relative 2^-24 (≈ 6e-8) of the double written.
TEST_F(TempDir, StlBinaryRoundTripToFloatPrecision) {
  const std::vector<Triangle> tris = sample_triangles();
  write_stl_binary(path("b.stl"), tris);
  EXPECT_EQ(fs::file_size(path("b.stl")), 84 + 50 * tris.size());
  const std::vector<Triangle> back = read_stl(path("b.stl"));
  ASSERT_EQ(back.size(), tris.size());
  for (std::size_t t = 0; t < tris.size(); ++t)
    for (int v = 0; v < 3; ++v)
      for (int c = 0; c < 3; ++c) {
        const double x = tris[t][v][c];
        EXPECT_EQ(back[t][v][c], static_cast<double>(static_cast<float>(x)));
        EXPECT_LE(std::abs(back[t][v][c] - x), std::ldexp(std::abs(x), -24) + 1e-45);
      }
}

// Many exporters write binary files whose header starts with "solid"; the size decides.
TEST_F(TempDir, StlBinaryWithSolidHeaderIsReadAsBinary) {
  const std::vector<Triangle> tris = sample_triangles();
  write_stl_binary(path("s.stl"), tris, "solid exported by some CAD program");
  ASSERT_EQ(slurp("s.stl").rfind("solid", 0), 0u);
  const std::vector<Triangle> back = read_stl(path("s.stl"));
  ASSERT_EQ(back.size(), tris.size());
  EXPECT_EQ(back[3][1].x(), static_cast<double>(static_cast<float>(tris[3][1].x())));
}

TEST_F(TempDir, StlAsciiVariantsAreRead) {
  // Upper-case keywords, CRLF line ends, '+' signs, exponents, nan normals, two solids.
  write("v.stl",
        "SOLID first part\r\n FACET NORMAL nan nan nan\r\n  OUTER LOOP\r\n   VERTEX +0 0 0\r\n   VERTEX 1e0 0 0\r\n"
        "   VERTEX 0 1.0E+00 0\r\n  ENDLOOP\r\n ENDFACET\r\nENDSOLID first part\r\n"
        "solid\nfacet normal 0 0 1\nouter loop\nvertex 0 0 1\nvertex 1 0 1\nvertex 0 1 1\nendloop\nendfacet\nendsolid\n");
  const std::vector<Triangle> t = read_stl(path("v.stl"));
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(t[0][2], Vec3(0, 1, 0));
  EXPECT_EQ(t[1][1], Vec3(1, 0, 1));
}

TEST_F(TempDir, StlErrorsNameTheFileAndTheProblem) {
  const std::vector<Triangle> tris = sample_triangles();
  write_stl_binary(path("good.stl"), tris);
  const std::string good = slurp("good.stl");
  const std::string facet = "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n";

  struct Case {
    std::string name, bytes;
    std::vector<std::string> expect;
  };
  std::string count_zero(84, '\0');
  std::string nan_binary = good;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(&nan_binary[84 + 12 + 4], &nan, 4);  // first triangle, first vertex, y
  std::string solid_truncated = good.substr(0, good.size() - 7);
  solid_truncated.replace(0, 5, "solid");
  const std::vector<Case> cases = {
      {"empty.stl", "", {"empty.stl: empty file"}},
      {"short.stl", "hello", {"short.stl", "too short for binary STL (5 bytes"}},
      {"truncated.stl", good.substr(0, good.size() - 7), {"truncated binary STL", std::to_string(tris.size()) + " triangles", std::to_string(good.size() - 7)}},
      {"extra.stl", good + "xyz", {"triangle count disagrees with the size", std::to_string(good.size() + 3)}},
      {"zero_binary.stl", count_zero, {"zero_binary.stl: the STL file holds no triangles"}},
      {"nan_binary.stl", nan_binary, {"nan_binary.stl", "triangle 0 has a non-finite coordinate"}},
      {"solid_truncated.stl", solid_truncated, {"solid_truncated.stl: not a valid STL file: it starts with 'solid' but holds binary data", "needing " + std::to_string(good.size()), "has " + std::to_string(good.size() - 7)}},
      {"zero_ascii.stl", "solid x\nendsolid x\n", {"zero_ascii.stl: the STL file holds no triangles"}},
      {"typo.stl", "solid x\nfacet normal 0 0 1\nouter lop\n", {"typo.stl:3: ASCII STL: expected 'loop', got 'lop'"}},
      {"number.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 abc\n",
       {"number.stl:5: ASCII STL: expected a number, got 'abc'"}},
      {"nan_ascii.stl", "solid x\n" + facet + "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 inf\n",
       {"nan_ascii.stl:12: ASCII STL: non-finite vertex coordinate, got 'inf'"}},
      {"unfinished.stl", "solid x\n" + facet, {"unfinished.stl:9: ASCII STL: expected 'facet' or 'endsolid', got the end of the file"}},
      {"trailing.stl", "solid x\n" + facet + "endsolid x\ngarbage\n", {"trailing.stl:10", "expected 'solid' or the end of the file"}},
      {"garbage.stl", std::string(200, 'x'), {"garbage.stl", "truncated binary STL (or not an STL file)"}},
  };
  for (const Case& c : cases) {
    write(c.name, c.bytes);
    const std::string msg = stl_error(path(c.name));
    EXPECT_FALSE(msg.empty()) << c.name << " was accepted";
    for (const std::string& f : c.expect) EXPECT_NE(msg.find(f), std::string::npos) << c.name << ": missing '" << f << "' in: " << msg;
  }
  const std::string missing = stl_error(path("none.stl"));
  EXPECT_NE(missing.find("none.stl: cannot open the STL file"), std::string::npos) << missing;
}

TEST(Stl, DegenerateTrianglesAreCountedAndRemoved) {
  std::vector<Triangle> t = {
      {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)},
      {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0)},  // collinear
      {Vec3(0, 0, 0), Vec3(1, 1, 1), Vec3(0, 0, 1)},
      {Vec3(5, 5, 5), Vec3(5, 5, 5), Vec3(5, 5, 5)},  // one point
  };
  std::size_t first = 99;
  EXPECT_EQ(remove_degenerate(t, &first), 2u);
  EXPECT_EQ(first, 1u);
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(t[1][1], Vec3(1, 1, 1)) << "order kept";
}

// ----------------------------------------------------------------------------------- primitives

// Distance of p from the line through `base` along unit `e`.
double radial(const Vec3& p, const Vec3& base, const Vec3& e) {
  const Vec3 d = p - base;
  return (d - d.dot(e) * e).norm();
}

TEST(MeshPrimitives, CylinderVerticesAreOnTheCircleAndTheAreaIsThePrisms) {
  const Vec3 base(1.5, -2.0, 0.25), axis = Vec3(1, -2, 4);
  const Vec3 e = axis.normalized();
  const double r = 0.3, h = 0.8;
  const int n = 48, rings = 5;
  const std::vector<Polygon> m = cylinder_mesh(base, axis, r, h, n, rings);
  ASSERT_EQ(m.size(), std::size_t(n * rings));
  expect_valid_elements(m);
  // Round-off: coordinates are O(3), so distances carry errors of a few ulps of 3.
  const double tol = 16 * kEps * 3;
  for (const Polygon& p : m)
    for (const Vec3& v : p) {
      EXPECT_NEAR(radial(v, base, e), r, tol);
      const double z = (v - base).dot(e);
      EXPECT_TRUE(z > -tol && z < h + tol) << z;
    }
  // Inscribed polygonal prism: 2·n·r·sin(π/n)·h, to round-off: vertex coordinates O(3) carry
  // errors ~ε·3 against edges of 0.04, i.e. ~2e-14 relative per element (measured 2e-14 on the
  // sum); tolerance 1e-12 relative.
  EXPECT_NEAR(total_area(m), 2 * n * r * std::sin(kPi / n) * h, 1e-12 * 2 * kPi * r * h);
  EXPECT_EQ(boundary_edges(m), std::size_t(2 * n)) << "only the two end circles are open";
}

// The area tends to 2πrh as 1 − sin(π/n)/(π/n) ≈ π²/(6n²): each doubling of n divides the
// error by 4 (checked to 1 %, far above round-off, far below the factor 4).
TEST(MeshPrimitives, CylinderAreaConvergesToTheCylinder) {
  const double r = 0.5, h = 2, exact = 2 * kPi * r * h;
  double prev = 0;
  for (int n : {16, 32, 64, 128, 256}) {
    const double err = (exact - total_area(cylinder_mesh(Vec3::Zero(), Vec3::UnitZ(), r, h, n))) / exact;
    EXPECT_NEAR(err, 1 - std::sin(kPi / n) / (kPi / n), 1e-12);
    if (prev > 0) EXPECT_NEAR(prev / err, 4.0, 0.04) << n;
    prev = err;
  }
  EXPECT_LT(prev, 3e-5) << "256 segments";
}

// Angle 0 is on e1 = +x for the z axis, counter-clockwise seen from +z (documented convention).
TEST(MeshPrimitives, AngleConventionAboutZ) {
  const std::vector<Polygon> m = cylinder_mesh(Vec3::Zero(), Vec3::UnitZ(), 1, 1, 4);
  EXPECT_EQ(m[0][0], Vec3(1, 0, 0));
  EXPECT_NEAR((m[0][1] - Vec3(0, 1, 0)).norm(), 0, 1e-16) << "cos(π/2) is 6e-17, not 0";
  EXPECT_EQ(m[3][1], m[0][0]) << "the ring closes on its first vertex exactly";
}

TEST(MeshPrimitives, DiscAndAnnulusAreas) {
  const Vec3 c(0.2, 0.1, -0.4), normal(0, 1, 1);
  const Vec3 e = normal.normalized();
  const double r = 0.25;
  const int n = 40;
  const std::vector<Polygon> disc = disc_mesh(c, normal, r, 0, n);
  ASSERT_EQ(disc.size(), std::size_t(n));
  expect_valid_elements(disc);
  for (const Polygon& p : disc) {
    EXPECT_EQ(p.size(), 3u);
    for (const Vec3& v : p) EXPECT_NEAR((v - c).dot(e), 0, 1e-15) << "in the plane (round-off, coordinates O(1))";
  }
  // Inscribed n-gon: (n/2)·r²·sin(2π/n), round-off of the sum.
  EXPECT_NEAR(total_area(disc), 0.5 * n * r * r * std::sin(2 * kPi / n), 1e-14);
  EXPECT_EQ(boundary_edges(disc), std::size_t(n)) << "the fan closes around the centre";

  const double ri = 0.1;
  const std::vector<Polygon> ring = disc_mesh(c, normal, r, ri, n);
  expect_valid_elements(ring);
  for (const Polygon& p : ring) {
    ASSERT_EQ(p.size(), 4u);
    EXPECT_NEAR((p[0] - c).norm(), ri, 1e-15);
    EXPECT_NEAR((p[1] - c).norm(), r, 1e-15);
  }
  EXPECT_NEAR(total_area(ring), 0.5 * n * (r * r - ri * ri) * std::sin(2 * kPi / n), 1e-14);
  EXPECT_EQ(boundary_edges(ring), std::size_t(2 * n));
}

// Frustum of the inscribed polygon: n trapezoids with parallel sides 2·r·sin(π/n) and slant height
// sqrt(h² + (rb − rt)²·cos²(π/n)) (between the chords' midpoints); tends to π(rb+rt)·slant.
TEST(MeshPrimitives, ConeSlantArea) {
  const double rb = 0.05, rt = 0.4, h = 0.3;  // a funnel: narrow outlet at the bottom
  for (int n : {8, 64, 512}) {
    const std::vector<Polygon> m = cone_mesh(Vec3(0, 0, 1), Vec3(0, 0, 1), rb, rt, h, n);
    ASSERT_EQ(m.size(), std::size_t(n));
    expect_valid_elements(m);
    const double c = std::cos(kPi / n);
    EXPECT_NEAR(total_area(m), n * (rb + rt) * std::sin(kPi / n) * std::sqrt(h * h + (rb - rt) * (rb - rt) * c * c), 1e-14);
    EXPECT_EQ(boundary_edges(m), std::size_t(2 * n));
  }
  // The true frustum: π(rb + rt)·s, s = sqrt(h² + (rb − rt)²). Expanding the formula above, the
  // inscribed one falls short by (π/n)²·(1/6 + (rb − rt)²/(2s²)) + O(n⁻⁴): checked to 1 %.
  const double s2 = h * h + (rb - rt) * (rb - rt), exact = kPi * (rb + rt) * std::sqrt(s2);
  for (int n : {64, 256}) {
    const double shortfall = 1 - total_area(cone_mesh(Vec3::Zero(), Vec3::UnitZ(), rb, rt, h, n)) / exact;
    const double x = kPi / n;
    EXPECT_NEAR(shortfall, x * x * (1.0 / 6 + (rb - rt) * (rb - rt) / (2 * s2)), 0.01 * x * x) << n;
  }

  // A cone with its apex at the top: triangles meeting at one point.
  const std::vector<Polygon> cone = cone_mesh(Vec3::Zero(), Vec3(1, 0, 0), 0.2, 0, 0.5, 16);
  expect_valid_elements(cone);
  for (const Polygon& p : cone) {
    ASSERT_EQ(p.size(), 3u);
    EXPECT_EQ(p[2], Vec3(0.5, 0, 0));
  }
  EXPECT_EQ(boundary_edges(cone), 16u) << "only the base circle is open";
  const std::vector<Polygon> inverted = cone_mesh(Vec3::Zero(), Vec3::UnitZ(), 0, 0.2, 0.5, 16);
  expect_valid_elements(inverted);
  EXPECT_EQ(boundary_edges(inverted), 16u);
}

// Helicoid: the vertex of step k (angle θ = 2π·turns·k/N) lies at height pitch·θ/(2π) and at the
// inner or outer radius (round-off: coordinates below 0.4, ulp 5.6e-17; measured 3.5e-16;
// tolerance 2e-15).
TEST(MeshPrimitives, HelixVerticesAtTheRightRadiiAndHeights) {
  const double ri = 0.05, ro = 0.2, pitch = 0.15, turns = 2.5;
  const int spt = 24;
  const std::vector<Polygon> m = helical_ramp_mesh(Vec3::Zero(), Vec3::UnitZ(), ri, ro, pitch, turns, spt);
  const int steps = 60;  // 2.5 turns x 24
  ASSERT_EQ(m.size(), std::size_t(2 * steps));
  EXPECT_EQ(helical_ramp_elements(turns, spt), 2 * steps);
  expect_valid_elements(m);
  const double tol = 2e-15;
  for (int k = 0; k < steps; ++k) {
    // Element 2k = (inner_k, outer_k, outer_k+1); element 2k+1 = (inner_k, outer_k+1, inner_k+1).
    const Polygon& a = m[2 * k];
    const Polygon& b = m[2 * k + 1];
    for (int s = 0; s < 2; ++s) {
      const int step = k + s;
      const double theta = 2 * kPi * turns * step / steps;
      const Vec3& in = s == 0 ? a[0] : b[2];
      const Vec3& out = s == 0 ? a[1] : b[1];
      EXPECT_NEAR(std::hypot(in.x(), in.y()), ri, tol);
      EXPECT_NEAR(std::hypot(out.x(), out.y()), ro, tol);
      EXPECT_NEAR(in.z(), pitch * theta / (2 * kPi), tol);
      EXPECT_NEAR(out.z(), pitch * theta / (2 * kPi), tol);
      EXPECT_NEAR(out.x(), ro * std::cos(theta), tol);
      EXPECT_NEAR(out.y(), ro * std::sin(theta), tol);
    }
    EXPECT_EQ(a[2], b[1]) << "the two triangles of a step share the diagonal exactly";
  }
  EXPECT_EQ(boundary_edges(m), std::size_t(2 * steps + 2)) << "inner and outer edges and the two ends";
  // Left-handed: negative pitch goes down.
  EXPECT_LT(helical_ramp_mesh(Vec3::Zero(), Vec3::UnitZ(), ri, ro, -pitch, 1, 8).back()[2].z(), 0);
  // No shaft (inner radius 0): the inner edge is the axis.
  expect_valid_elements(helical_ramp_mesh(Vec3(1, 2, 3), Vec3(0, 1, 0), 0, ro, pitch, 1.3, 16));
}

// The helicoid's area is turns·2π·∫ sqrt(r² + c²) dr over [ri, ro], c = pitch/(2π). With one
// radial band the flat triangles converge, as the angular step shrinks, to the trapezoid rule
// across r (not to the surface: the twisted strip is a "Schwarz lantern"); refining both ways the
// error is second order (falls by about 4 per doubling of both, checked to 10 %).
TEST(MeshPrimitives, HelixAreaConverges) {
  const double ri = 0.05, ro = 0.2, pitch = 0.15, turns = 1.0, c = pitch / (2 * kPi);
  auto f = [c](double r) { return std::sqrt(r * r + c * c); };
  auto prim = [c](double r) { const double s = std::sqrt(r * r + c * c); return 0.5 * (r * s + c * c * std::log(r + s)); };
  const double exact = turns * 2 * kPi * (prim(ro) - prim(ri));
  const double trapezoid = turns * 2 * kPi * (ro - ri) * 0.5 * (f(ri) + f(ro));
  auto area = [&](int spt, int bands) {
    return total_area(helical_ramp_mesh(Vec3::Zero(), Vec3::UnitZ(), ri, ro, pitch, turns, spt, bands));
  };
  EXPECT_NEAR(area(4096, 1) / trapezoid, 1, 1e-6) << "one band: the trapezoid rule (angular error ~1/4096²)";
  double prev = 0;
  for (int k : {1, 2, 4, 8}) {
    const double err = std::abs(area(32 * k, 2 * k) - exact) / exact;
    if (prev > 0) EXPECT_NEAR(prev / err, 4.0, 0.4) << k;
    prev = err;
  }
  EXPECT_LT(prev, 1e-4) << "256 steps per turn, 16 bands";
}

// The flat triangles stray from the helicoid by less than one step's rise b·Δθ (b = pitch/2π),
// as documented (sampled worst: 0.69 b·Δθ for a strip reaching the axis, 0.3 for a ramp with a
// shaft). Distance measured along the surface normal from the height offset at the same (r, φ).
TEST(MeshPrimitives, HelixTrianglesStayCloseToTheSurface) {
  for (const double ri : {0.0, 0.05}) {
    const double ro = 0.2, pitch = 0.15, b = pitch / (2 * kPi);
    const int spt = 24;
    const double dtheta = 2 * kPi / spt;
    const std::vector<Polygon> m = helical_ramp_mesh(Vec3::Zero(), Vec3::UnitZ(), ri, ro, pitch, 1.0, spt);
    double worst = 0;
    for (std::size_t e = 0; e < m.size(); ++e) {
      const double theta_k = dtheta * double(e / 2);  // one band: elements 2k, 2k+1 belong to step k
      for (int i = 0; i <= 20; ++i)
        for (int j = 0; i + j <= 20; ++j) {
          const Vec3 x = m[e][0] + (i / 20.0) * (m[e][1] - m[e][0]) + (j / 20.0) * (m[e][2] - m[e][0]);
          const double r = std::hypot(x.x(), x.y());
          if (r < 1e-12) continue;  // on the axis every height belongs to the surface
          double phi = std::atan2(x.y(), x.x());
          phi += 2 * kPi * std::round((theta_k + dtheta / 2 - phi) / (2 * kPi));  // unwrap near the step
          worst = std::max(worst, std::abs(x.z() - b * phi) * r / std::hypot(r, b));
        }
    }
    EXPECT_LT(worst, b * dtheta) << "inner radius " << ri;
    EXPECT_GT(worst, 0.1 * b * dtheta) << "the check sees the first-order error";
  }
}

// Several radial bands: every band's vertices at its radius, the bands share their edges.
TEST(MeshPrimitives, HelixRadialBands) {
  const int spt = 16, bands = 3;
  const std::vector<Polygon> m = helical_ramp_mesh(Vec3(0, 0, 1), Vec3::UnitZ(), 0.1, 0.4, 0.2, 1, spt, bands);
  ASSERT_EQ(m.size(), std::size_t(2 * spt * bands));
  EXPECT_EQ(helical_ramp_elements(1, spt, bands), 2 * spt * bands);
  expect_valid_elements(m);
  EXPECT_EQ(boundary_edges(m), std::size_t(2 * spt + 2 * bands)) << "inner and outer edges and the two end rulings";
  // Cell (k = 0, j = 1) is elements 2 and 3: from radius 0.2 to 0.3 (round-off).
  EXPECT_NEAR(std::hypot(m[2][0].x(), m[2][0].y()), 0.2, 1e-15);
  EXPECT_NEAR(std::hypot(m[2][1].x(), m[2][1].y()), 0.3, 1e-15);
}

TEST(MeshPrimitives, RectangleQuadsAndTriangles) {
  const Vec3 corner(0.1, 0.2, 0.3), u(0.3, 0, 0.1), v(0, 0.2, 0);
  const std::vector<Polygon> q = rectangle_mesh(corner, u, v, 3, 2);
  ASSERT_EQ(q.size(), 6u);
  expect_valid_elements(q);
  EXPECT_NEAR(total_area(q), u.cross(v).norm(), 1e-15);
  EXPECT_EQ(boundary_edges(q), 10u) << "2·(nu + nv) edges on the outline";
  EXPECT_EQ(q[0][0], corner);
  EXPECT_EQ(q[5][2], corner + u + v) << "cell (i, j) = (2, 1) is element j·nu + i = 5";
  const std::vector<Polygon> t = rectangle_mesh(corner, u, v, 3, 2, true);
  ASSERT_EQ(t.size(), 12u);
  expect_valid_elements(t);
  EXPECT_NEAR(total_area(t), u.cross(v).norm(), 1e-15);
  EXPECT_EQ(boundary_edges(t), 10u);
}

// Far from the origin, with a large radius and a fine mesh, elements are still planar within
// polygon_problem's tolerance (1e-9 of the edge length) and share their vertices.
TEST(MeshPrimitives, ValidFarFromTheOrigin) {
  const Vec3 base(1234.5, -987.6, 55.5);
  const std::vector<Polygon> m = cylinder_mesh(base, Vec3(0.3, 0.1, 1), 2.0, 3.0, 512, 3);
  expect_valid_elements(m);
  EXPECT_EQ(boundary_edges(m), 1024u);
  expect_valid_elements(cone_mesh(base, Vec3(-1, 0, 0.2), 2.0, 0.5, 1.0, 512));
  expect_valid_elements(helical_ramp_mesh(base, Vec3(0, 0, 1), 0.1, 2.0, 0.5, 3, 512));
}

TEST(MeshPrimitives, PreconditionsAreChecked) {
  EXPECT_THROW(cylinder_mesh(Vec3::Zero(), Vec3::Zero(), 1, 1), std::invalid_argument) << "zero axis";
  EXPECT_THROW(cylinder_mesh(Vec3::Zero(), Vec3::UnitZ(), -1, 1), std::invalid_argument);
  EXPECT_THROW(cylinder_mesh(Vec3::Zero(), Vec3::UnitZ(), 1, 1, 2), std::invalid_argument) << "2 segments";
  EXPECT_THROW(disc_mesh(Vec3::Zero(), Vec3::UnitZ(), 1, 1), std::invalid_argument) << "inner = outer";
  EXPECT_THROW(cone_mesh(Vec3::Zero(), Vec3::UnitZ(), 0, 0, 1), std::invalid_argument);
  EXPECT_THROW(helical_ramp_mesh(Vec3::Zero(), Vec3::UnitZ(), 0, 1, 0, 1), std::invalid_argument) << "zero pitch";
  EXPECT_THROW(rectangle_mesh(Vec3::Zero(), Vec3::UnitX(), 2 * Vec3::UnitX(), 1, 1), std::invalid_argument) << "parallel";
}

}  // namespace
}  // namespace dem

namespace dem {
namespace {

// ---------------------------------------------------------------------------------- scene syntax

// A scene with one material and the [[wall]] "drum" whose remaining keys are `wall`.
std::string scene_with(const std::string& wall, const std::string& more = "") {
  return "[[material]]\nname = \"steel\"\ndensity = 7800.0\nkn = 1.0e5\n\n"
         "[[wall]]\nname = \"drum\"\nmaterial = \"steel\"\n" + wall + "\n" + more;
}

// The names and vertices of the scene's walls are those of the primitive, in its order.
void expect_mesh(const Scene& s, const std::vector<Polygon>& want, std::size_t first = 0) {
  ASSERT_GE(s.walls.size(), first + want.size());
  for (std::size_t k = 0; k < want.size(); ++k) {
    const WallSpec& w = s.walls[first + k];
    EXPECT_EQ(w.name, "drum." + std::to_string(k));
    EXPECT_EQ(w.material, 0);
    EXPECT_EQ(w.vertices, want[k]) << w.name;
  }
}

TEST(MeshScene, EachPrimitiveTypeParses) {
  {
    const Scene s = parse_scene(scene_with("type = \"cylinder\"\nbase_centre = [0.0, 0.0, 0.1]\nradius = 0.5\nheight = 1.0\n"
                                           "segments = 32\nrings = 2\n"),
                                "scene.toml");
    ASSERT_EQ(s.walls.size(), 64u);
    expect_mesh(s, cylinder_mesh(Vec3(0, 0, 0.1), Vec3::UnitZ(), 0.5, 1.0, 32, 2));
    EXPECT_EQ(s.walls.back().name, "drum.63");
  }
  {
    const Scene s = parse_scene(scene_with("type = \"cylinder\"\nbase_centre = [0, 0, 0]\naxis = [1, 0, 0]\nradius = 0.5\nheight = 1\n"),
                                "scene.toml");
    EXPECT_EQ(s.walls.size(), std::size_t(kDefaultSegments)) << "segments defaults to 64, rings to 1";
  }
  {
    const Scene s = parse_scene(scene_with("type = \"disc\"\ncentre = [1, 2, 3]\nnormal = [0, 1, 0]\nradius = 0.2\ninner_radius = 0.05\nsegments = 12\n"),
                                "scene.toml");
    expect_mesh(s, disc_mesh(Vec3(1, 2, 3), Vec3::UnitY(), 0.2, 0.05, 12));
    EXPECT_EQ(s.walls.size(), 12u);
  }
  {
    const Scene s = parse_scene(scene_with("type = \"cone\"\nbase_centre = [0, 0, 0]\nradius_base = 0.02\nradius_top = 0.2\nheight = 0.3\nsegments = 16\n"),
                                "scene.toml");
    expect_mesh(s, cone_mesh(Vec3::Zero(), Vec3::UnitZ(), 0.02, 0.2, 0.3, 16));
    EXPECT_EQ(s.walls.size(), 16u);
  }
  {
    const Scene s = parse_scene(scene_with("type = \"helix\"\nbase_centre = [0, 0, 0]\nradius = 0.5\ninner_radius = 0.1\npitch = 0.4\n"
                                           "turns = 2.0\nsegments_per_turn = 32\nradial_segments = 2\n"),
                                "scene.toml");
    expect_mesh(s, helical_ramp_mesh(Vec3::Zero(), Vec3::UnitZ(), 0.1, 0.5, 0.4, 2.0, 32, 2));
    EXPECT_EQ(s.walls.size(), 256u) << "2 x 64 steps x 2 bands";
  }
  {
    const Scene s = parse_scene(scene_with("type = \"rectangle\"\ncorner = [0, 0, 0]\nedge_u = [1, 0, 0]\nedge_v = [0, 1, 0]\nnu = 3\nnv = 2\n"
                                           "elements = \"triangles\"\n"),
                                "scene.toml");
    expect_mesh(s, rectangle_mesh(Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY(), 3, 2, true));
    EXPECT_EQ(s.walls.size(), 12u);
  }
}

// The thesis's helical-flow case (§4.3, fig. 4.4): a drum with a ramp inside, each its own wall,
// next to a box; groups select whole meshes in stage motions, box faces keep their names.
TEST(MeshScene, DrumWithRampAndGroups) {
  const std::string text = scene_with(
      "type = \"cylinder\"\nbase_centre = [0, 0, 0]\nradius = 0.5\nheight = 1.0\nsegments = 48\n",
      "[[wall]]\nname = \"ramp\"\nmaterial = \"steel\"\ntype = \"helix\"\nbase_centre = [0, 0, 0]\nradius = 0.5\n"
      "inner_radius = 0.2\npitch = 0.5\nturns = 2\nsegments_per_turn = 48\n\n"
      "[[wall]]\nname = \"box\"\nmaterial = \"steel\"\ntype = \"box\"\nmin = [-1, -1, -0.1]\nmax = [1, 1, 1.5]\n\n"
      "[[stage]]\nname = \"spin\"\nduration = 0.1\n\n[[stage.motion]]\nwall = \"drum\"\ntype = \"translate\"\nvelocity = [0, 0, 0.1]\n\n"
      "[[stage.motion]]\nwall = \"ramp.7\"\ntype = \"fixed\"\n");
  const Scene s = parse_scene(text, "scene.toml");
  ASSERT_EQ(s.walls.size(), 48u + 192u + 6u);
  EXPECT_EQ(s.walls[47].name, "drum.47");
  EXPECT_EQ(s.walls[48].name, "ramp.0");
  EXPECT_EQ(s.walls[239].name, "ramp.191");
  EXPECT_EQ(s.walls[240].name, "box.xmin");
  std::size_t drum = 0;
  for (const WallSpec& w : s.walls) drum += wall_matches(w.name, "drum");
  EXPECT_EQ(drum, 48u) << "\"drum\" selects every element of the drum and nothing else";
}

TEST_F(TempDir, StlWallIsReadRelativeToTheSceneAndTransformed) {
  // A unit right triangle and a quad split in two, in millimetres, plus one degenerate triangle.
  std::vector<Triangle> tris = {{Vec3(0, 0, 0), Vec3(1000, 0, 0), Vec3(0, 1000, 0)},
                                {Vec3(0, 0, 0), Vec3(0, 0, 500), Vec3(0, 0, 1000)},
                                {Vec3(0, 0, 1000), Vec3(1000, 0, 1000), Vec3(1000, 1000, 1000)}};
  fs::create_directories(dir_ / "parts");
  write_stl_binary(path("parts/hopper.stl"), tris);
  const std::string scene = path("scene.toml");
  const std::string wall = "type = \"stl\"\nfile = \"parts/hopper.stl\"\nscale = 0.001\ntranslate = [0.0, 0.0, 2.0]\n"
                           "rotate = { axis = [0, 0, 1], angle = 90.0 }\n";
  try {
    parse_scene(scene_with(wall), scene);
    FAIL() << "degenerate triangle accepted";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.rfind(scene + ":10:8:", 0), 0u) << msg;
    for (const char* f : {"wall[0].file = \"parts/hopper.stl\"", "1 of 3 triangles are degenerate", "triangle 1", "skip_degenerate = true"})
      EXPECT_NE(msg.find(f), std::string::npos) << "missing '" << f << "' in: " << msg;
  }
  const Scene s = parse_scene(scene_with(wall + "skip_degenerate = true\n"), scene);
  ASSERT_EQ(s.walls.size(), 2u);
  EXPECT_EQ(s.walls[1].name, "drum.1") << "numbered after the degenerate one is dropped";
  // x -> R·(0.001·x) + (0, 0, 2) with R a quarter turn about z: (1000, 0, 0) mm -> (0, 1, 2) m.
  // Tolerance: cos(90°) computed in double is 6e-17.
  EXPECT_TRUE(s.walls[0].vertices[1].isApprox(Vec3(0, 1, 2), 1e-15)) << s.walls[0].vertices[1].transpose();
  EXPECT_TRUE(s.walls[1].vertices[2].isApprox(Vec3(-1, 1, 3), 1e-15)) << s.walls[1].vertices[2].transpose();
  // An absolute path works from anywhere.
  const Scene abs = parse_scene(scene_with("type = \"stl\"\nfile = \"" + path("parts/hopper.stl") + "\"\nskip_degenerate = true\n"), "elsewhere/scene.toml");
  EXPECT_EQ(abs.walls.size(), 2u);
}

// The committed fixture: tests/data/mesh_walls.toml and the STL files beside it (generated by
// tests/data/make_stl_fixtures.py), read through read_scene_file as the tools do.
TEST(MeshScene, FixtureSceneFromTestData) {
  const Scene s = read_scene_file(std::string(DEM_TEST_DATA) + "/mesh_walls.toml");
  std::map<std::string, int> per_wall;
  for (const WallSpec& w : s.walls) ++per_wall[w.name.substr(0, w.name.find('.'))];
  EXPECT_EQ(per_wall["hopper"], 32) << "cone, 32 segments";
  EXPECT_EQ(per_wall["floor"], 4) << "2 x 2 quads";
  EXPECT_EQ(per_wall["deflector"], 4) << "tetrahedron, ASCII STL";
  EXPECT_EQ(per_wall["baffle"], 2) << "square, binary STL whose header starts with \"solid\"";
}

struct MeshBadCase {
  const char* what;
  std::string wall;                  // keys after name and material
  std::vector<std::string> expect;   // fragments the message must contain
};

std::vector<MeshBadCase> mesh_bad_cases() {
  const std::string cyl = "type = \"cylinder\"\nbase_centre = [0, 0, 0]\nheight = 1.0\n";
  const std::string helix = "type = \"helix\"\nbase_centre = [0, 0, 0]\nradius = 0.5\nturns = 1.0\n";
  return {
      {"negative radius", cyl + "radius = -0.1\n", {"scene.toml:12:10: wall[0].radius = -0.1", "out of range: allowed (0, inf) m"}},
      {"zero segments", cyl + "radius = 0.5\nsegments = 0\n", {"scene.toml:13:12: wall[0].segments = 0", "out of range: allowed [3, 1000000]"}},
      {"segments not an integer", cyl + "radius = 0.5\nsegments = 32.5\n", {"wall[0].segments = 32.5", "expected an integer"}},
      {"too many elements", cyl + "radius = 0.5\nsegments = 1000\nrings = 2000\n",
       {"wall[0].segments = 1000", "2000000 elements (segments x rings)", "limit of 1000000"}},
      {"unknown key", cyl + "radius = 0.5\nradiuss = 0.5\n",
       {"scene.toml:13:11: wall[0].radiuss = 0.5", "unknown key", "allowed here: axis, base_centre, height"}},
      {"zero axis", cyl + "radius = 0.5\naxis = [0, 0, 0]\n", {"wall[0].axis = [...]", "non-zero"}},
      {"missing height", "type = \"cylinder\"\nbase_centre = [0, 0, 0]\nradius = 0.5\n", {"scene.toml:6: wall[0].height is missing"}},
      {"inner radius = radius", "type = \"disc\"\ncentre = [0, 0, 0]\nradius = 0.5\ninner_radius = 0.5\n",
       {"wall[0].inner_radius = 0.5", "allowed [0, radius) m, radius = 0.5 m"}},
      {"inner radius above the helix radius", helix + "pitch = 0.2\ninner_radius = 0.6\n", {"wall[0].inner_radius = 0.6", "[0, radius)"}},
      {"zero pitch", helix + "pitch = 0.0\n", {"wall[0].pitch = 0", "non-zero"}},
      {"huge helix", helix + "pitch = 0.2\nsegments_per_turn = 1000000\nradial_segments = 2\n",
       {"wall[0].turns = 1", "4000000 elements", "limit"}},
      {"cone without radii", "type = \"cone\"\nbase_centre = [0, 0, 0]\nradius_base = 0\nradius_top = 0.0\nheight = 1\n",
       {"wall[0].radius_top = 0", "both 0"}},
      {"negative cone radius", "type = \"cone\"\nbase_centre = [0, 0, 0]\nradius_base = -1\nradius_top = 0.0\nheight = 1\n",
       {"wall[0].radius_base = -1", "[0, inf) m"}},
      {"parallel rectangle edges", "type = \"rectangle\"\ncorner = [0, 0, 0]\nedge_u = [1, 0, 0]\nedge_v = [2, 0, 0]\n",
       {"wall[0].edge_v = [...]", "not be parallel"}},
      {"unknown element kind", "type = \"rectangle\"\ncorner = [0, 0, 0]\nedge_u = [1, 0, 0]\nedge_v = [0, 1, 0]\nelements = \"hexagons\"\n",
       {"wall[0].elements = \"hexagons\"", "\"quads\", \"triangles\""}},
      {"missing STL file", "type = \"stl\"\nfile = \"no_such.stl\"\n",
       {"scene.toml:10:8: wall[0].file = \"no_such.stl\"", "no_such.stl: cannot open the STL file"}},
      {"zero scale", "type = \"stl\"\nfile = \"x.stl\"\nscale = 0\n", {"wall[0].scale = 0", "(0, inf)"}},
      {"unknown rotate key", "type = \"stl\"\nfile = \"x.stl\"\nrotate = { axis = [0, 0, 1], angle = 90, scale = 2 }\n",
       {"wall[0].rotate.scale = 2", "unknown key"}},
      {"unknown type lists the types", "type = \"sphere\"\n",
       {"wall[0].type = \"sphere\"", "\"polygon\", \"box\", \"rectangle\", \"cylinder\", \"disc\", \"cone\", \"helix\", \"stl\""}},
  };
}

class MeshSceneRejects : public ::testing::TestWithParam<MeshBadCase> {};

TEST_P(MeshSceneRejects, WithAClearMessage) {
  const MeshBadCase& c = GetParam();
  expect_rejected({c.what, scene_with(c.wall), c.expect});
}

INSTANTIATE_TEST_SUITE_P(BadMeshWalls, MeshSceneRejects, ::testing::ValuesIn(mesh_bad_cases()));

TEST(MeshScene, NamesStayUniqueAndDotFree) {
  const std::string cyl = "type = \"cylinder\"\nbase_centre = [0, 0, 0]\nradius = 0.5\nheight = 1\nsegments = 8\n";
  try {
    parse_scene(scene_with(cyl, "[[wall]]\nname = \"drum\"\nmaterial = \"steel\"\ntype = \"box\"\nmin = [0, 0, 0]\nmax = [1, 1, 1]\n"), "scene.toml");
    FAIL() << "two walls named drum";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("wall[1].name = \"drum\": duplicate wall name \"drum\" (also wall[0])"), std::string::npos) << e.what();
  }
  std::string dotted = scene_with(cyl);
  dotted.replace(dotted.find("\"drum\""), 6, "\"drum.1\"");
  EXPECT_THROW(parse_scene(dotted, "scene.toml"), InputError);
}

}  // namespace
}  // namespace dem
