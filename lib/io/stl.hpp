#pragma once
// STL triangle meshes (SPEC §3: walls "alone or as meshes"): read ASCII or binary STL, write
// either. Only the vertices are used; the facet normals stored in a file are ignored (a wall's
// normal comes from its vertices, and contact is on either side of a wall).
//
// Formats (the de-facto standard, little-endian binary):
//   ASCII:  solid NAME / facet normal nx ny nz / outer loop / vertex x y z (x3) / endloop /
//           endfacet / ... / endsolid NAME. Keywords are read case-insensitively; several
//           solid ... endsolid blocks in one file are read one after the other.
//   binary: 80-byte header, uint32 triangle count n, then n records of 50 bytes (normal and
//           three vertices as 12 float32, and a uint16 attribute count, ignored).
// Detection: a file whose size is exactly 84 + 50·n (n read at byte 80) is binary even if its
// header starts with "solid" (many exporters write such headers); otherwise a file starting with
// "solid" is ASCII; anything else is an error that says which size a binary file would need.
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "core/types.hpp"

namespace dem {

using Triangle = std::array<Vec3, 3>;

// Reads every triangle of an STL file, in file order, degenerate ones included (see
// count_degenerate). Throws IoError naming the path and what is wrong: missing or unreadable
// file, truncated binary, a triangle count that disagrees with the size, bad ASCII syntax (with
// the line number), a non-finite coordinate, no triangle at all.
std::vector<Triangle> read_stl(const std::string& path);

// Writes ASCII STL with 17 significant digits, enough for every double to read back exactly.
// Facet normals are computed from the vertices (right-hand rule; zero for a degenerate triangle).
void write_stl_ascii(const std::string& path, const std::vector<Triangle>& tris, const std::string& solid_name = "dem");

// Writes binary STL. Coordinates are stored as float32 (the format has no other), so they read
// back rounded to float precision (relative 2^-24 ≈ 6e-8). `header` (at most 80 bytes, padded
// with NULs) should not start with "solid" — readers that only look at the first bytes would take
// the file for ASCII — but may, to test readers like ours.
void write_stl_binary(const std::string& path, const std::vector<Triangle>& tris,
                      const std::string& header = "binary STL written by dem");

// A triangle of (practically) zero area cannot be a wall: the test is polygon_problem's (vertices
// collinear or coincident, relative to the longest edge from the first vertex).
bool is_degenerate(const Triangle& t);

// Removes the degenerate triangles in place; returns how many were removed and, if `first` is
// given, the 0-based file index of the first one removed (unchanged if none).
std::size_t remove_degenerate(std::vector<Triangle>& tris, std::size_t* first = nullptr);

}  // namespace dem
