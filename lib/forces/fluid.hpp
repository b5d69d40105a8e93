#pragma once
// The force of a prescribed, steady fluid flow on each particle (docs/physics.md, "Fluid drag",
// eq. P70-P75): the pressure field is given (a uniform gradient, or the radial flow to a well),
// the fluid's velocity at a particle follows from the pressure gradient through the same drag law
// at the particle's local void fraction (so that flow and drag are consistent: in a fixed bed the
// grains carry exactly the pressure drop), and the force is
//   F = V_p beta / (1 - eps) (u - v) - V_p grad p - rho_f V_p g
// with beta from Ergun below eps = 0.8 and from Wen & Yu at and above it.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "core/keep_items.hpp"
#include "core/types.hpp"
#include "simd/lanes.hpp"
#include "state/load_sum.hpp"
#include "state/particles.hpp"

namespace dem {

inline constexpr double kErgunWenYuSwitch = 0.8;  // Ergun below, Wen & Yu at and above (P72)
// A grain nearly alone is no porous medium: the flow's speed (P74) is solved at no more than this
// void fraction (the drag itself uses the grain's own).
inline constexpr double kFlowVoidMax = 0.95;

// Schiller & Naumann's drag coefficient of a sphere at particle Reynolds number re (P73).
inline double schiller_naumann_cd(double re) { return re < 1000 ? 24 / re * (1 + 0.15 * std::pow(re, 0.687)) : 0.44; }

// Ergun's slip speed per unit pressure gradient (P74): the root w of inertial w^2 + viscous w =
// share g, over g, written without cancellation as 2 share / (viscous + sqrt(viscous^2 + 4 inertial
// share g)), from its constants 2 share, viscous, viscous^2 and 4 inertial share. Written once over
// a lane type L (simd/lanes.hpp: Ergun::speed_per_gradient, and ergun_force one grain or four).
template <class L>
[[gnu::always_inline]] inline L ergun_speed_per_gradient(const L& twice_share, const L& viscous, const L& viscous2, const L& reach, const L& g) {
  return twice_share / (viscous + lanes::root(viscous2 + reach * g));
}

// Ergun's beta / (1 - eps) (P72, eps < 0.8) as viscous + inertial w, for void fraction eps, grain
// diameter d, fluid viscosity mu and density rho; and the slip speed at which it carries a given
// drag per unit particle volume (P74).
struct Ergun {
  Ergun(double eps, double d, double mu, double rho) : viscous(150 * (1 - eps) / eps * mu / (d * d)), inertial(1.75 * rho / d) {}
  double drag(double w) const { return viscous + inertial * w; }
  // The speed w at which drag(w) w = share g, divided by g > 0.
  double speed_per_gradient(double share, double g) const {
    return ergun_speed_per_gradient(2 * share, viscous, viscous * viscous, 4 * inertial * share, g);
  }
  double viscous, inertial;  // [kg/(m^3 s)], [kg/m^4]
};

// Wen & Yu's beta / (1 - eps) in the Stokes limit (Re -> 0, P72-P73): 18 mu eps^-2.65 / d^2.
inline double wen_yu_stokes(double eps, double d, double mu) { return 18 * mu / (d * d) * std::pow(eps, -2.65); }

// beta / (1 - eps) of Wen & Yu (P72-P73, eps >= 0.8), arguments as drag_per_volume's below.
inline double wen_yu_drag(double eps, double d, double w, double mu, double rho) {
  const double re = eps * rho * d * w / mu;
  if (re <= 0) return wen_yu_stokes(eps, d, mu);
  return 0.75 * schiller_naumann_cd(re) * eps * rho * w / d * std::pow(eps, -2.65);  // Wen & Yu
}

// beta / (1 - eps) [kg/(m^3 s)]: the drag per unit particle volume and unit slip velocity
// (P71, P72), for void fraction eps, grain diameter d, slip speed w = |u - v| (u interstitial),
// fluid viscosity mu and density rho. Finite as eps -> 1 (a lone sphere: Schiller & Naumann).
inline double drag_per_volume(double eps, double d, double w, double mu, double rho) {
  return eps < kErgunWenYuSwitch ? Ergun(eps, d, mu, rho).drag(w) : wen_yu_drag(eps, d, w, mu, rho);
}

// The drag's share of the pressure gradient in a fixed bed of void fraction eps (P74), eps / (1 - eps),
// at no more than kFlowVoidMax.
inline double flow_share(double eps) {
  eps = std::min(eps, kFlowVoidMax);
  return eps / (1 - eps);
}

// interstitial_speed's Wen & Yu side, eps >= 0.8. With a = 18 mu eps^-2.65 / d^2 and b = eps rho d
// / mu, P72-P73 make drag_per_volume(w) w = a w (1 + 0.15 (b w)^0.687) below Re = b w = 1000, a
// convex rising curve: Newton's steps from the Stokes speed (above the root, where a w alone
// carries it) fall to the root and stop where the next would not (one power a step, against a
// bisection's sixty). Above Re = 1000 (C_d 0.44) the drag is 0.33 rho eps^-1.65 w / d, a square
// in w; between the two the curve jumps up at Re = 1000, which is then the root.
inline double wen_yu_speed(double eps, double d, double g, double mu, double rho) {
  const double need = flow_share(eps) * g;  // drag_per_volume(w) w
  eps = std::min(eps, kFlowVoidMax);
  const double a = wen_yu_stokes(eps, d, mu), b = eps * rho * d / mu;
  double w = need / a;  // Stokes: above the root
  for (int k = 0; k < 200; ++k) {
    const double inertia = 0.15 * std::pow(b * w, 0.687);
    const double next = w - (a * w * (1 + inertia) - need) / (a * (1 + 1.687 * inertia));
    if (!(next < w)) break;
    w = next;
  }
  if (b * w < 1000) return w;
  const double fast = std::sqrt(need / (0.33 * rho * std::pow(eps, -1.65) / d));
  return b * fast >= 1000 ? fast : 1000 / b;
}

// The interstitial speed w at which a fixed bed of void fraction eps carries the pressure gradient
// g = |grad p| (P74): per unit bed volume the fluid's drag on the grains balances its share of the
// pressure gradient, beta(w) w = eps g, i.e. drag_per_volume(w) w = eps g / (1 - eps). Ergun: a
// quadratic, solved in closed form; Wen & Yu: wen_yu_speed.
inline double interstitial_speed(double eps, double d, double g, double mu, double rho) {
  if (g <= 0) return 0;
  if (eps < kErgunWenYuSwitch) return Ergun(eps, d, mu, rho).speed_per_gradient(flow_share(eps), g) * g;
  return wen_yu_speed(eps, d, g, mu, rho);
}

// What the fluid's force on a grain of Ergun's range (eps < 0.8, P71-P74) needs of its radius and
// void fraction alone, over a lane type L (simd/lanes.hpp: one grain, or four), worked out once per
// void-fraction update: a step's force then takes one division besides the pressure field's.
template <class L>
struct ErgunGrain {
  L viscous, inertial;          // Ergun's beta / (1 - eps) = viscous + inertial w (P72)
  L twice_share, viscous2, reach;  // 2 share, viscous^2, 4 inertial share: Ergun::speed_per_gradient's constants (P74)
  L volume, displaced;          // V_p [m^3], rho_f V_p [kg]
};

// The fluid's force on an Ergun grain g where the pressure gradient is gp, moving at v, under
// gravity [N] (P71): Ergun::speed_per_gradient's flow (P74; none where gp = 0), the drag at the slip
// from it. Written once over L: the same operations, so the same bits, one grain or four at a time.
template <class L>
[[gnu::always_inline]] inline lanes::Triple<L> ergun_force(const ErgunGrain<L>& g, const lanes::Triple<L>& gp, const lanes::Triple<L>& v,
                                                           const lanes::Triple<L>& gravity) {
  const L gn = lanes::root(lanes::dot(gp, gp));
  const L per_gradient = ergun_speed_per_gradient(g.twice_share, g.viscous, g.viscous2, g.reach, gn);
  const lanes::Triple<L> slip = lanes::only_where(lanes::less(L(0.0), gn), (-per_gradient) * gp) - v;
  const L drag = g.viscous + g.inertial * lanes::root(lanes::dot(slip, slip));
  return ((g.volume * drag) * slip - g.volume * gp) - g.displaced * gravity;
}

// What the fluid's force on one grain (P71-P74) needs of its radius a and void fraction eps alone,
// worked out once per void-fraction update: a step's force then takes no division but the pressure
// field's and the flow speed's.
struct FluidGrain {
  double eps = 1, d = 0;              // the void fraction and the diameter (Wen & Yu's path)
  double volume = 0, displaced = 0;   // V_p [m^3], rho_f V_p [kg]
  double share = 0;                   // flow_share(eps) (P74)
  Ergun ergun{0.5, 1, 0, 0};          // eps < 0.8: Ergun's terms at eps
  // Its constants for ergun_force (eps < 0.8), each as Ergun::speed_per_gradient rounds it.
  ErgunGrain<double> lane() const {
    return {ergun.viscous, ergun.inertial, 2 * share, ergun.viscous * ergun.viscous, 4 * ergun.inertial * share, volume, displaced};
  }
};

// Every particle's FluidGrain, by storage slot, one array per constant (the four-wide force loads
// four slots' at once; FluidField::add_forces).
struct FluidGrains {
  std::vector<double> eps, d, viscous, inertial, twice_share, viscous2, reach, volume, displaced;
  long size() const { return static_cast<long>(eps.size()); }
  void resize(long n) {
    for (auto* a : {&eps, &d, &viscous, &inertial, &twice_share, &viscous2, &reach, &volume, &displaced}) a->resize(n);
  }
  void clear() { resize(0); }
  void keep_only(const Kept& keep) {
    for (auto* a : {&eps, &d, &viscous, &inertial, &twice_share, &viscous2, &reach, &volume, &displaced}) keep_items(*a, keep);
  }
  void set(long i, const FluidGrain& g) {
    const ErgunGrain<double> e = g.lane();
    eps[i] = g.eps, d[i] = g.d, viscous[i] = e.viscous, inertial[i] = e.inertial, twice_share[i] = e.twice_share;
    viscous2[i] = e.viscous2, reach[i] = e.reach, volume[i] = e.volume, displaced[i] = e.displaced;
  }
  ErgunGrain<double> ergun(long i) const {
    return {viscous[i], inertial[i], twice_share[i], viscous2[i], reach[i], volume[i], displaced[i]};
  }
};

// The fluid of a stage ([stage.fluid], docs/scene.md): its properties, the pressure field and the
// void-fraction estimator's settings.
struct FluidParams {
  enum class Flow { None, Uniform, Well };
  Flow flow = Flow::None;  // None: no fluid (no force, no cost)
  double viscosity = 0;    // mu [Pa s]
  double density = 0;      // rho_f [kg/m^3]
  Vec3 gradient = Vec3::Zero();  // Uniform: grad p [Pa/m]
  // Well (P75): the well's axis (a point and a unit direction), its radius r_w, the drainage radius
  // r_e and the drawdown p_e - p_w [Pa] (> 0: flow towards the well).
  Vec3 well_centre = Vec3::Zero(), well_axis = Vec3(0, 0, 1);
  double well_radius = 0, drainage_radius = 0, drawdown = 0;
  double void_cutoff = 0;       // the void-fraction kernel's support radius c [m] (P70)
  long void_every = 100;        // steps between void-fraction updates (at multiples of it)

  bool on() const { return flow != Flow::None; }

  // grad p at x [Pa/m] (P75), and the fluid's force on a grain (P71): FluidField's, below.
  Vec3 pressure_gradient(const Vec3& x) const;
  Vec3 force(double a, double eps, const Vec3& x, const Vec3& v, const Vec3& g) const;
};

// A stage's fluid as the force loop uses it: the constants of the pressure field worked out once
// per step rather than once per grain (the well's logarithm).
class FluidField {
 public:
  explicit FluidField(const FluidParams& f)
      : f_(f), well_scale_(f.flow == FluidParams::Flow::Well ? f.drawdown / std::log(f.drainage_radius / f.well_radius) : 0) {}

  // grad p at x [Pa/m] (P75): zero inside the well (open hole, at the well pressure).
  Vec3 pressure_gradient(const Vec3& x) const {
    if (f_.flow == FluidParams::Flow::Uniform) return f_.gradient;
    if (f_.flow != FluidParams::Flow::Well) return Vec3::Zero();
    return lanes::vec3(well_gradient(lanes::triple(x)));
  }
  // The well's grad p (P75) at x, over a lane type L: dp/dr r_hat, dp/dr = dp / (ln(re/rw) r).
  template <class L>
  [[gnu::always_inline]] lanes::Triple<L> well_gradient(const lanes::Triple<L>& x) const {
    const Vec3 &c = f_.well_centre, &e = f_.well_axis;
    const lanes::Triple<L> axis{L(e.x()), L(e.y()), L(e.z())};
    lanes::Triple<L> r = x - lanes::Triple<L>{L(c.x()), L(c.y()), L(c.z())};
    r = r - lanes::dot(r, axis) * axis;
    const L r2 = lanes::dot(r, r), zero(0.0);
    return lanes::select(lanes::less(r2, L(f_.well_radius * f_.well_radius)), lanes::Triple<L>{zero, zero, zero}, (L(well_scale_) / r2) * r);
  }

  // The constants of grain of radius a and void fraction eps.
  FluidGrain grain(double a, double eps) const {
    FluidGrain g;
    g.eps = eps, g.d = 2 * a;
    g.volume = 4.0 / 3.0 * std::numbers::pi * a * a * a, g.displaced = f_.density * g.volume;
    g.share = flow_share(eps);
    g.ergun = Ergun(eps, g.d, f_.viscosity, f_.density);
    return g;
  }

  // The fluid's interstitial velocity u at grain g where the pressure gradient is gp (P74).
  Vec3 flow(const FluidGrain& g, const Vec3& gp) const {
    const double gn = gp.norm();
    if (!(gn > 0)) return Vec3::Zero();
    if (g.eps < kErgunWenYuSwitch) return -g.ergun.speed_per_gradient(g.share, gn) * gp;
    return wen_yu_flow(g.eps, g.d, gp);
  }
  // flow() of Wen & Yu's range (eps >= 0.8), grain diameter d.
  Vec3 wen_yu_flow(double eps, double d, const Vec3& gp) const {
    const double gn = gp.norm();
    return gn > 0 ? Vec3(-(interstitial_speed(eps, d, gn, f_.viscosity, f_.density) / gn) * gp) : Vec3::Zero();
  }

  // The fluid's force on grain g at x moving at v, under gravity [N] (P71): the drag at the slip
  // from the flow at x.
  Vec3 force(const FluidGrain& g, const Vec3& x, const Vec3& v, const Vec3& gravity) const {
    const Vec3 gp = pressure_gradient(x);
    if (g.eps < kErgunWenYuSwitch) return lanes::vec3(ergun_force(g.lane(), lanes::triple(gp), lanes::triple(v), lanes::triple(gravity)));
    return wen_yu_force(g.eps, g.d, g.volume, g.displaced, gp, v, gravity);
  }
  // force() of Wen & Yu's range (eps >= 0.8), where the pressure gradient is gp.
  Vec3 wen_yu_force(double eps, double d, double volume, double displaced, const Vec3& gp, const Vec3& v, const Vec3& gravity) const {
    const Vec3 slip = wen_yu_flow(eps, d, gp) - v;
    const double drag = drag_per_volume(eps, d, slip.norm(), f_.viscosity, f_.density);
    return volume * drag * slip - volume * gp - displaced * gravity;
  }
  // Adds the fluid's force on slots [lo, hi) of p, grains g by slot, to force [N]: four at a time
  // where simd (simd_loops_on()) and four neighbours are all of Ergun's range, the same bits.
  void add_forces(const FluidGrains& g, const Particles& p, const Vec3& gravity, long lo, long hi, LoadSum* force, bool simd) const;
  // The same for a grain of radius a with local void fraction eps.
  Vec3 force(double a, double eps, const Vec3& x, const Vec3& v, const Vec3& gravity) const { return force(grain(a, eps), x, v, gravity); }

 private:
  const FluidParams& f_;
  double well_scale_;  // Well: dp / ln(r_e / r_w) [Pa]
};

inline Vec3 FluidParams::pressure_gradient(const Vec3& x) const { return FluidField(*this).pressure_gradient(x); }
inline Vec3 FluidParams::force(double a, double eps, const Vec3& x, const Vec3& v, const Vec3& g) const {
  return FluidField(*this).force(a, eps, x, v, g);
}

}  // namespace dem
