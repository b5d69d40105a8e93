#pragma once
// Lane types, so that a law is written once and runs one contact at a time or four at a time:
// code written over a lane type L (double, or Lanes4: four doubles in an AVX2 register) with its
// mask type (bool, or Mask4) and selections in place of branches is the plain path with
// L = double and the four-wide path with L = Lanes4 (or Two<Lanes4>, two sets of four). Each
// operation rounds alike in a lane and in a scalar register (IEEE 754; no fused multiply-add is
// contracted), so both give the same bits.
//
// A four-wide caller is a [[gnu::target("avx2")]] function (DEM_AVX2, simd.hpp); the law and the
// operations below are always inlined into it, where they become AVX2 instructions. What needs
// AVX2 instructions of its own is in lanes_avx2.hpp, memory.hpp and layout.hpp.
#include <cmath>

#include "core/types.hpp"
#include "simd/simd.hpp"

namespace dem::lanes {

// One lane: plain doubles, masks are bools. (Bitwise & on bools: no branch.)
inline bool less(double a, double b) { return a < b; }
inline bool less_or_equal(double a, double b) { return a <= b; }
inline bool equal(double a, double b) { return a == b; }
inline bool both(bool a, bool b) { return a & b; }
inline bool either(bool a, bool b) { return a | b; }
inline bool but_not(bool a, bool b) { return a & !b; }  // a and not b
inline double select(bool where, double a, double b) { return where ? a : b; }
inline double only_where(bool where, double a) { return where ? a : 0.0; }  // where ? a : +0
inline double zero_where(bool where, double a) { return where ? 0.0 : a; }  // where ? +0 : a
inline double root(double a) { return std::sqrt(a); }
inline double exp_where(bool where, double a) { return where ? std::exp(a) : 0.0; }  // where ? exp(a) : +0
inline bool all(bool where) { return where; }

// A vector of three lanes each: x, y and z of one contact, or of four.
template <class L>
struct Triple {
  L x, y, z;
};
template <class L> [[gnu::always_inline]] inline Triple<L> operator+(const Triple<L>& a, const Triple<L>& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
template <class L> [[gnu::always_inline]] inline Triple<L> operator-(const Triple<L>& a, const Triple<L>& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
template <class L> [[gnu::always_inline]] inline Triple<L> operator*(const L& s, const Triple<L>& a) { return {s * a.x, s * a.y, s * a.z}; }
template <class L> [[gnu::always_inline]] inline Triple<L> operator*(const Triple<L>& a, const L& s) { return {a.x * s, a.y * s, a.z * s}; }
// Eigen's order for 3-vectors: (a0 b0 + a1 b1) + a2 b2, and the cross product's usual terms.
template <class L> [[gnu::always_inline]] inline L dot(const Triple<L>& a, const Triple<L>& b) { return (a.x * b.x + a.y * b.y) + a.z * b.z; }
template <class L> [[gnu::always_inline]] inline Triple<L> cross(const Triple<L>& a, const Triple<L>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <class L, class M> [[gnu::always_inline]] inline Triple<L> select(const M& where, const Triple<L>& a, const Triple<L>& b) {
  return {select(where, a.x, b.x), select(where, a.y, b.y), select(where, a.z, b.z)};
}
template <class L, class M> [[gnu::always_inline]] inline Triple<L> only_where(const M& where, const Triple<L>& a) {
  return {only_where(where, a.x), only_where(where, a.y), only_where(where, a.z)};
}
inline Triple<double> triple(const Vec3& v) { return {v.x(), v.y(), v.z()}; }
inline Vec3 vec3(const Triple<double>& t) { return Vec3(t.x, t.y, t.z); }

#ifdef DEM_SIMD_LOOPS
// Four lanes of doubles, and a mask per lane (all bits set or none), in GCC's vector types: their
// operations need no target attribute, so the law (compiled for the default target) inlines
// them, and inlined into a four-wide caller they become AVX2 instructions (vaddpd, vcmppd,
// vblendvpd, vsqrtpd). always_inline: passed by value between functions of different targets,
// 32-byte vectors would change calling convention (GCC's psABI note), so none may stay a call.
typedef double f64x4 __attribute__((vector_size(32)));
typedef long i64x4 __attribute__((vector_size(32)));
#define DEM_LANE [[gnu::always_inline]] inline

struct Lanes4 {
  f64x4 v;
  Lanes4() = default;
  DEM_LANE Lanes4(const f64x4& a) : v(a) {}  // by reference: a vector by value across targets changes the ABI
  // The same value in every lane: its bits ORed into zeros, which GCC 12 builds with one broadcast
  // and hoists out of a loop (f64x4{a, a, a, a} it rebuilds from 16-byte halves at every use).
  DEM_LANE Lanes4(double a) : v((f64x4)(i64x4{} | __builtin_bit_cast(long, a))) {}
};
struct Mask4 {
  i64x4 v = i64x4{0, 0, 0, 0};  // no lane
};
DEM_LANE Lanes4 operator+(Lanes4 a, Lanes4 b) { return a.v + b.v; }
DEM_LANE Lanes4 operator-(Lanes4 a, Lanes4 b) { return a.v - b.v; }
DEM_LANE Lanes4 operator*(Lanes4 a, Lanes4 b) { return a.v * b.v; }
DEM_LANE Lanes4 operator/(Lanes4 a, Lanes4 b) { return a.v / b.v; }
DEM_LANE Lanes4 operator-(Lanes4 a) { return -a.v; }  // exact, as a scalar's -a
DEM_LANE Mask4 less(Lanes4 a, Lanes4 b) { return {a.v < b.v}; }
DEM_LANE Mask4 less_or_equal(Lanes4 a, Lanes4 b) { return {a.v <= b.v}; }
DEM_LANE Mask4 equal(Lanes4 a, Lanes4 b) { return {a.v == b.v}; }
DEM_LANE Mask4 both(Mask4 a, Mask4 b) { return {a.v & b.v}; }
DEM_LANE Mask4 either(Mask4 a, Mask4 b) { return {a.v | b.v}; }
DEM_LANE Mask4 but_not(Mask4 a, Mask4 b) { return {a.v & ~b.v}; }
DEM_LANE Lanes4 select(Mask4 where, Lanes4 a, Lanes4 b) { return where.v ? a.v : b.v; }
DEM_LANE Lanes4 only_where(Mask4 where, Lanes4 a) { return (f64x4)((i64x4)a.v & where.v); }
DEM_LANE Lanes4 zero_where(Mask4 where, Lanes4 a) { return (f64x4)((i64x4)a.v & ~where.v); }
DEM_LANE Lanes4 root(Lanes4 a) {
  return f64x4{__builtin_sqrt(a.v[0]), __builtin_sqrt(a.v[1]), __builtin_sqrt(a.v[2]), __builtin_sqrt(a.v[3])};
}
// std::exp lane by lane where asked (libm's bits, as one lane's; a vector exp rounds otherwise),
// for lanes that are few (a mendes bond in tension): the others cost a test each.
DEM_LANE Lanes4 exp_where(Mask4 where, Lanes4 a) {
  f64x4 e{};
  for (int l = 0; l < 4; ++l)
    if (where.v[l]) e[l] = std::exp(a.v[l]);
  return e;
}
DEM_LANE bool all(Mask4 where) { return (where.v[0] & where.v[1] & where.v[2] & where.v[3]) != 0; }
// A mask from four flags, and four values.
DEM_LANE Mask4 mask4(bool a, bool b, bool c, bool d) { return {i64x4{-long{a}, -long{b}, -long{c}, -long{d}}}; }
DEM_LANE Lanes4 lanes4(double a, double b, double c, double d) { return f64x4{a, b, c, d}; }
// Four consecutive doubles read or written at any address (copied bytes: no alignment or aliasing
// assumed): one unaligned load or store in a four-wide caller.
DEM_LANE Lanes4 load4(const double* p) {
  f64x4 v;
  __builtin_memcpy(&v, p, sizeof v);
  return v;
}
DEM_LANE void store4(double* p, Lanes4 a) { __builtin_memcpy(p, &a.v, sizeof a.v); }
// Lanes 1, 2, 3 moved down to 0, 1, 2 (lane 3 keeps its own).
DEM_LANE Lanes4 shift_down(Lanes4 a) { return __builtin_shufflevector(a.v, a.v, 1, 2, 3, 3); }

// Two sets of lanes side by side (Two<Lanes4>: eight contacts in two registers), each operation
// done on both halves one after the other. The law is a long chain of dependent square roots and
// divisions; two independent halves interleaved keep the divider busy with one while the other
// waits (bench/results/design.md). Each lane rounds as in Lanes4, so the bits are the same.
template <class L>
struct Two {
  L lo, hi;
  Two() = default;
  DEM_LANE Two(const L& a, const L& b) : lo(a), hi(b) {}
  DEM_LANE Two(double a) : lo(a), hi(a) {}
};
template <class L> DEM_LANE Two<L> operator+(const Two<L>& a, const Two<L>& b) { return {a.lo + b.lo, a.hi + b.hi}; }
template <class L> DEM_LANE Two<L> operator-(const Two<L>& a, const Two<L>& b) { return {a.lo - b.lo, a.hi - b.hi}; }
template <class L> DEM_LANE Two<L> operator*(const Two<L>& a, const Two<L>& b) { return {a.lo * b.lo, a.hi * b.hi}; }
template <class L> DEM_LANE Two<L> operator/(const Two<L>& a, const Two<L>& b) { return {a.lo / b.lo, a.hi / b.hi}; }
template <class L> DEM_LANE Two<L> operator-(const Two<L>& a) { return {-a.lo, -a.hi}; }
DEM_LANE Two<Mask4> less(const Two<Lanes4>& a, const Two<Lanes4>& b) { return {less(a.lo, b.lo), less(a.hi, b.hi)}; }
DEM_LANE Two<Mask4> less_or_equal(const Two<Lanes4>& a, const Two<Lanes4>& b) {
  return {less_or_equal(a.lo, b.lo), less_or_equal(a.hi, b.hi)};
}
DEM_LANE Two<Mask4> equal(const Two<Lanes4>& a, const Two<Lanes4>& b) { return {equal(a.lo, b.lo), equal(a.hi, b.hi)}; }
DEM_LANE Two<Mask4> both(const Two<Mask4>& a, const Two<Mask4>& b) { return {both(a.lo, b.lo), both(a.hi, b.hi)}; }
DEM_LANE Two<Mask4> either(const Two<Mask4>& a, const Two<Mask4>& b) { return {either(a.lo, b.lo), either(a.hi, b.hi)}; }
DEM_LANE Two<Mask4> but_not(const Two<Mask4>& a, const Two<Mask4>& b) { return {but_not(a.lo, b.lo), but_not(a.hi, b.hi)}; }
DEM_LANE Two<Lanes4> select(const Two<Mask4>& w, const Two<Lanes4>& a, const Two<Lanes4>& b) {
  return {select(w.lo, a.lo, b.lo), select(w.hi, a.hi, b.hi)};
}
DEM_LANE Two<Lanes4> only_where(const Two<Mask4>& w, const Two<Lanes4>& a) { return {only_where(w.lo, a.lo), only_where(w.hi, a.hi)}; }
DEM_LANE Two<Lanes4> zero_where(const Two<Mask4>& w, const Two<Lanes4>& a) { return {zero_where(w.lo, a.lo), zero_where(w.hi, a.hi)}; }
DEM_LANE Two<Lanes4> root(const Two<Lanes4>& a) { return {root(a.lo), root(a.hi)}; }
DEM_LANE Two<Lanes4> exp_where(const Two<Mask4>& w, const Two<Lanes4>& a) { return {exp_where(w.lo, a.lo), exp_where(w.hi, a.hi)}; }
DEM_LANE bool all(const Two<Mask4>& w) { return all(w.lo) && all(w.hi); }

template <class L> DEM_LANE Triple<Two<L>> two(const Triple<L>& a, const Triple<L>& b) { return {{a.x, b.x}, {a.y, b.y}, {a.z, b.z}}; }
template <class L> DEM_LANE Triple<L> low(const Triple<Two<L>>& a) { return {a.x.lo, a.y.lo, a.z.lo}; }
template <class L> DEM_LANE Triple<L> high(const Triple<Two<L>>& a) { return {a.x.hi, a.y.hi, a.z.hi}; }

#undef DEM_LANE
#endif

}  // namespace dem::lanes
