#include "accel/shapes.hpp"

#include <cmath>
#include <utility>

namespace holoray {
namespace {

// Roots of a*t^2 + 2*b*t + c = 0, ascending; false when none are real.
bool solve_quadratic(double a, double b, double c, double& t0, double& t1) {
  if (a == 0) {
    if (b == 0) return false;
    t0 = t1 = -c / (2 * b);
    return true;
  }
  const double disc = b * b - a * c;
  if (disc < 0) return false;
  // Citardauq form: no cancellation between b and sqrt(disc).
  const double q = -(b + std::copysign(std::sqrt(disc), b));
  if (q == 0) {
    t0 = t1 = 0;
    return true;
  }
  t0 = q / a;
  t1 = c / q;
  if (t0 > t1) std::swap(t0, t1);
  return true;
}

// The nearest hit of o + t*d with t in (tnear, tfar), as intersect_sphere()
// documents. Without `Normal` (a shadow ray's question: is there a hit?)
// neither t nor n is set, and the normal is computed only where an
// inside-only sphere's test needs it; the answer is the same.
template <bool Normal>
bool sphere_hit(const Sphere& s, const Vec3& o, const Vec3& d, double tnear, double tfar, double& t, Vec3& n) {
  const double r = std::fabs(s.radius);
  const double a = dot(d, d);
  const Vec3 oc = o - s.centre;
  const double b = dot(oc, d), r2 = r * r, cc = dot(oc, oc);
  // Most of Embree's calls are rays that enter the sphere's box and miss it
  // (balls_s4: 83 %). a times the h2 below is b^2 + a (r^2 - |oc|^2),
  // here without the division's latency; the rounding errors of this sum
  // and of a h2 are each below about 25 epsilon a (r^2 + |oc|^2), so past
  // a margin of 1e-13 (about 450 epsilon) it rejects only lines that the
  // exact test below rejects too: the answers are the same.
  if (b * b + a * (r2 - cc) < -1e-13 * a * (r2 + cc)) return false;
  // Project the centre onto the line first: keeps precision when the origin is far away.
  const double tc = -b / a;
  const Vec3 q = oc + d * tc;
  const double h2 = r2 - dot(q, q);
  if (h2 < 0) return false;
  const double h = std::sqrt(h2 / a);
  const double roots[2] = {tc - h, tc + h};
  for (double root : roots) {
    if (!(root > tnear && root < tfar)) continue;
    if constexpr (!Normal)
      if (s.radius >= 0) return true;
    const Vec3 nn = (oc + d * root) / r;
    if (s.radius < 0 && dot(nn, d) <= 0) continue;  // inside-only: the hit must face away from the ray
    if constexpr (Normal) t = root, n = nn;
    return true;
  }
  return false;
}

// intersect_cone()'s test, with `Normal` as sphere_hit's.
template <bool Normal>
bool cone_hit(const PreparedCone& pc, const Vec3& o, const Vec3& d, double tnear, double tfar, double& t, Vec3& n) {
  const Vec3& a = pc.a;
  const double len = pc.len, k = pc.k, rb = pc.rb;
  const Vec3 w = o - pc.cone.base;
  const double hw = dot(w, a), hd = dot(d, a);
  const Vec3 wp = w - a * hw, dp = d - a * hd;
  const double r0 = rb + k * hw;  // radius at the origin's height
  const double qa = dot(dp, dp) - k * k * hd * hd;
  const double qb = dot(wp, dp) - k * hd * r0;
  const double qc = dot(wp, wp) - r0 * r0;
  double t0, t1;
  if (!solve_quadratic(qa, qb, qc, t0, t1)) return false;
  const double roots[2] = {t0, t1};
  for (double root : roots) {
    if (!(root > tnear && root < tfar)) continue;
    const double h = hw + root * hd;
    if (h < 0 || h > len) continue;
    if (rb + k * h < 0) continue;  // the mirrored nappe beyond a cone's tip
    if constexpr (!Normal)
      if (pc.cone.base_radius >= 0) return true;
    const Vec3 radial = normalize(wp + dp * root);
    const Vec3 nn = normalize(radial - a * k);
    if (pc.cone.base_radius < 0 && dot(nn, d) <= 0) continue;  // inside-only
    if constexpr (Normal) t = root, n = nn;
    return true;
  }
  return false;
}

}  // namespace

bool intersect_sphere(const Sphere& s, const Vec3& o, const Vec3& d, double tnear, double tfar, double& t, Vec3& n) {
  return sphere_hit<true>(s, o, d, tnear, tfar, t, n);
}

bool meets_sphere(const Sphere& s, const Vec3& o, const Vec3& d, double tnear, double tfar) {
  double t;
  Vec3 n;
  return sphere_hit<false>(s, o, d, tnear, tfar, t, n);
}

PreparedCone prepare_cone(const Cone& c) {
  PreparedCone p;
  p.cone = c;
  const Vec3 axis_full = c.apex - c.base;
  p.len = length(axis_full);
  p.a = axis_full / p.len;
  p.rb = std::fabs(c.base_radius);
  p.k = (std::fabs(c.apex_radius) - p.rb) / p.len;  // radius change per unit height
  return p;
}

bool intersect_cone(const Cone& c, const Vec3& o, const Vec3& d, double tnear, double tfar, double& t, Vec3& n) {
  return intersect_cone(prepare_cone(c), o, d, tnear, tfar, t, n);
}

bool intersect_cone(const PreparedCone& pc, const Vec3& o, const Vec3& d, double tnear, double tfar, double& t,
                    Vec3& n) {
  return cone_hit<true>(pc, o, d, tnear, tfar, t, n);
}

bool meets_cone(const PreparedCone& pc, const Vec3& o, const Vec3& d, double tnear, double tfar) {
  double t;
  Vec3 n;
  return cone_hit<false>(pc, o, d, tnear, tfar, t, n);
}

Bounds3 bounds_of(const Sphere& s) {
  const double r = std::fabs(s.radius);
  Bounds3 b;
  b.extend(s.centre - Vec3{r, r, r});
  b.extend(s.centre + Vec3{r, r, r});
  return b;
}

Bounds3 bounds_of(const Cone& c) {
  // A disc of radius r with unit normal a spans r*sqrt(1 - a_e^2) along axis e.
  const Vec3 a = normalize(c.apex - c.base);
  const Vec3 e{std::sqrt(std::fmax(0, 1 - a.x * a.x)), std::sqrt(std::fmax(0, 1 - a.y * a.y)), std::sqrt(std::fmax(0, 1 - a.z * a.z))};
  Bounds3 b;
  const double rb = std::fabs(c.base_radius), ra = std::fabs(c.apex_radius);
  b.extend(c.base - e * rb);
  b.extend(c.base + e * rb);
  b.extend(c.apex - e * ra);
  b.extend(c.apex + e * ra);
  return b;
}

}  // namespace holoray
