#pragma once
// Mesh primitives for walls (SPEC §3: "a cylinder with a helical ramp is a quad mesh", fig. 4.4).
// Each function returns polygons of 3 or 4 vertices, each a convex planar polygon that passes
// polygon_problem, i.e. one wall element; the scene parser names them NAME.0, NAME.1, ...
//
// Curved shapes are inscribed polygons: their vertices lie exactly on the curve (to round-off)
// and their faces are chords. The sagitta (largest gap between chord and circle) of n segments
// on a circle of radius r is r·(1 − cos(π/n)): 1.2e-3·r for the default n = 64 (kDefaultSegments),
// and the inscribed area falls short of the true one by a factor sin(π/n)/(π/n) (0.04 % for 64).
// Keep the sagitta well below the smallest particle radius.
//
// Neighbouring elements share vertices exactly: every vertex (a point of a ring, a grid node) is
// computed once and reused by all elements that touch it, and a closed ring reuses its first
// vertex instead of recomputing the angle 2π, so no gaps or overlaps appear between elements.
//
// Angles about an axis a are measured from e1, the unit projection of the x axis on the plane
// normal to a (of the y axis when a is within about 25° of x), towards e2 = a × e1; so for
// a = +z, angle 0 is +x and angle 90° is +y (counter-clockwise seen from +z).
//
// Preconditions (the scene parser checks them first, with file and line): finite inputs,
// non-zero axis/normal, radii and heights as documented, counts >= 1 (>= 3 around a circle).
// A violated precondition throws std::invalid_argument (a caller's bug, not a user's).
#include <vector>

#include "core/types.hpp"

namespace dem {

using Polygon = std::vector<Vec3>;

constexpr int kDefaultSegments = 64;

// A parallelogram (a rectangle when edge_u ⟂ edge_v) with corners corner, corner + edge_u,
// corner + edge_u + edge_v, corner + edge_v, split into nu × nv quads, or 2·nu·nv triangles when
// `triangles` (each quad cut along its diagonal from its corner nearest `corner`). Element order:
// cell (i, j) at index j·nu + i (i along edge_u); its quad is (P(i,j), P(i+1,j), P(i+1,j+1), P(i,j+1)).
std::vector<Polygon> rectangle_mesh(const Vec3& corner, const Vec3& edge_u, const Vec3& edge_v, int nu, int nv,
                                    bool triangles = false);

// Open tube (no end caps) of radius r about `axis` from base_centre over `height`: segments
// around × rings along the axis, each a planar rectangle. Element index ring·segments + segment.
std::vector<Polygon> cylinder_mesh(const Vec3& base_centre, const Vec3& axis, double radius, double height,
                                   int segments = kDefaultSegments, int rings = 1);

// Flat disc in the plane through `centre` normal to `normal`: `segments` triangles fanning from
// the centre when inner_radius = 0, else an annulus of `segments` planar trapezoids.
std::vector<Polygon> disc_mesh(const Vec3& centre, const Vec3& normal, double radius, double inner_radius = 0,
                               int segments = kDefaultSegments);

// Lateral surface of a cone frustum (a funnel or hopper): radius radius_base at base_centre,
// radius_top at base_centre + height·axis. Each segment is a planar trapezoid; where one radius is
// 0 it is a triangle with its apex on the axis (both 0 is an error). Open at both ends.
std::vector<Polygon> cone_mesh(const Vec3& base_centre, const Vec3& axis, double radius_base, double radius_top,
                               double height, int segments = kDefaultSegments);

// Helicoid strip (a helical ramp or screw flight) between inner_radius (>= 0) and outer_radius
// about `axis`: the point at angle θ (from 0 to 2π·turns) and radius r lies at height
// pitch·θ/(2π) above base_centre (pitch < 0: left-handed). The strip is cut into
// N = ceil(turns·segments_per_turn) equal angular steps and `radial_segments` equal radial bands.
// A helicoid is twisted, so each cell's quad (r_j θ_k, r_j+1 θ_k, r_j+1 θ_k+1, r_j θ_k+1) is not
// planar: it is split along (r_j θ_k, r_j+1 θ_k+1) into two triangles, elements 2c and 2c+1 of
// cell c = k·radial_segments + j. The flat triangles stray from the surface by roughly
// b·Δθ·Δr/(2·(r_j + r_j+1)) (b = |pitch|/(2π), Δθ = 2π·turns/N, Δr the band width; up to 1.4
// times that in a band reaching the axis; sampled numerically), less than one step's rise b·Δθ:
// first order in Δθ. Only more bands make the tilt of the triangles follow the tilt of the
// surface, which grows towards the axis (one band across a wide strip gives the area of the
// trapezoid rule across r).
std::vector<Polygon> helical_ramp_mesh(const Vec3& base_centre, const Vec3& axis, double inner_radius,
                                       double outer_radius, double pitch, double turns,
                                       int segments_per_turn = kDefaultSegments, int radial_segments = 1);

// Number of elements helical_ramp_mesh returns (so that a caller can refuse a huge mesh before
// building it); saturates at 1e15 instead of overflowing.
long long helical_ramp_elements(double turns, int segments_per_turn, int radial_segments = 1);

}  // namespace dem
