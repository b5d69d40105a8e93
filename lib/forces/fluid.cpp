#include "forces/fluid.hpp"

#include "simd/lanes_avx2.hpp"
#include "simd/layout.hpp"
#include "simd/memory.hpp"
#include "simd/simd.hpp"

namespace dem {

namespace {

// The fluid's force on slot i (P71), by FluidField::force's operations from the grains' arrays.
inline Vec3 force_at(const FluidField& field, const FluidGrains& g, const Particles& p, const Vec3& gravity, long i) {
  const Vec3 gp = field.pressure_gradient(p.x[i]);
  if (g.eps[i] < kErgunWenYuSwitch) return lanes::vec3(ergun_force(g.ergun(i), lanes::triple(gp), lanes::triple(p.v[i]), lanes::triple(gravity)));
  return field.wen_yu_force(g.eps[i], g.d[i], g.volume[i], g.displaced[i], gp, p.v[i], gravity);
}

#ifdef DEM_SIMD_LOOPS
// add_forces four slots at a time (ergun_force over Lanes4) where the four are all of Ergun's
// range, one at a time elsewhere: the same operations on each grain, so the same bits.
DEM_AVX2 void add_forces_four(const FluidField& field, const FluidParams::Flow flow, const Vec3& uniform, const FluidGrains& g, const Particles& p,
                              const Vec3& gravity, long lo, long hi, LoadSum* force) {
  using lanes::Lanes4;
  using V3 = lanes::Triple<Lanes4>;
  const V3 down{simd::broadcast(gravity.x()), simd::broadcast(gravity.y()), simd::broadcast(gravity.z())};
  const V3 fixed{simd::broadcast(uniform.x()), simd::broadcast(uniform.y()), simd::broadcast(uniform.z())};
  const Lanes4 ergun_below = simd::broadcast(kErgunWenYuSwitch);
  long i = lo;
  for (; i + 4 <= hi; i += 4) {
    if (simd::bits(lanes::less(simd::load(g.eps.data() + i), ergun_below)) != 0b1111) {
      for (long k = i; k < i + 4; ++k) force[k].v += force_at(field, g, p, gravity, k);
      continue;
    }
    const double* x = p.x[i].data();
    const double* v = p.v[i].data();
    const Lanes4 xs[3] = {simd::load(x), simd::load(x + 4), simd::load(x + 8)}, vs[3] = {simd::load(v), simd::load(v + 4), simd::load(v + 8)};
    const V3 gp = flow == FluidParams::Flow::Well ? field.well_gradient(simd::unpack(xs)) : fixed;
    const ErgunGrain<Lanes4> e{simd::load(g.viscous.data() + i),     simd::load(g.inertial.data() + i), simd::load(g.twice_share.data() + i),
                               simd::load(g.viscous2.data() + i),    simd::load(g.reach.data() + i),    simd::load(g.volume.data() + i),
                               simd::load(g.displaced.data() + i)};
    Lanes4 f[4];
    simd::per_lane(ergun_force(e, gp, simd::unpack(vs), down), f);
    for (int k = 0; k < 4; ++k) {
      double* sum = force[i + k].v.data();  // a LoadSum: 32-byte aligned, its fourth double never read
      simd::store_aligned(sum, simd::load(sum) + f[k]);
    }
  }
  for (; i < hi; ++i) force[i].v += force_at(field, g, p, gravity, i);
}
#endif

}  // namespace

void FluidField::add_forces(const FluidGrains& g, const Particles& p, const Vec3& gravity, long lo, long hi, LoadSum* force, bool simd) const {
#ifdef DEM_SIMD_LOOPS
  if (simd) return add_forces_four(*this, f_.flow, f_.flow == FluidParams::Flow::Uniform ? f_.gradient : Vec3::Zero(), g, p, gravity, lo, hi, force);
#endif
  for (long i = lo; i < hi; ++i) force[i].v += force_at(*this, g, p, gravity, i);
}

}  // namespace dem
