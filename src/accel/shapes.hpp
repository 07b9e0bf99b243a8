// holoray/accel: exact analytic intersection of the NFF curved primitives, in
// double precision (nff-notes §6, §7). Embree calls these from user-geometry
// callbacks; the renderer calls them again to refine a hit's t to double.
#pragma once

#include "math/vec.hpp"

namespace holoray {

/// NFF sphere; negative radius: only the inside surface is visible.
struct Sphere {
  Vec3 centre;
  double radius = 1;
  bool casts_shadow = true;  ///< false: occluded() queries pass through it
};

/// NFF open cone (no caps) from base to apex; radii of one sign, both
/// negative: only the inside surface is visible.
struct Cone {
  Vec3 base, apex;
  double base_radius = 1, apex_radius = 1;
};

/// A Cone with what every intersection test needs computed once: the unit
/// axis, its length and the radius change per unit height. Computed with
/// intersect_cone(Cone)'s own arithmetic, so both give the same bits; the
/// ray tracer tests cones through it (a square root and two divisions
/// fewer per candidate cone, which Embree's traversal asks many times).
struct PreparedCone {
  Cone cone;
  Vec3 a;              ///< unit axis, base to apex
  double len = 1;      ///< axis length
  double k = 0;        ///< (|apex radius| - |base radius|) / len
  double rb = 1;       ///< |base radius|
};
PreparedCone prepare_cone(const Cone& c);

/// Nearest hit of o + t*d with t in (tnear, tfar); d need not be unit.
/// On a hit, sets t and the outward geometric normal (unit) and returns true.
bool intersect_sphere(const Sphere& s, const Vec3& o, const Vec3& d, double tnear, double tfar, double& t, Vec3& n_outward);
bool intersect_cone(const Cone& c, const Vec3& o, const Vec3& d, double tnear, double tfar, double& t, Vec3& n_outward);
bool intersect_cone(const PreparedCone& c, const Vec3& o, const Vec3& d, double tnear, double tfar, double& t,
                    Vec3& n_outward);

/// Whether o + t*d meets the shape for some t in (tnear, tfar): the same
/// answer as intersect_sphere / intersect_cone, without the normal, which a
/// shadow ray does not need (an inside-only shape's test needs it and goes
/// through the full intersection).
bool meets_sphere(const Sphere& s, const Vec3& o, const Vec3& d, double tnear, double tfar);
bool meets_cone(const PreparedCone& c, const Vec3& o, const Vec3& d, double tnear, double tfar);

Bounds3 bounds_of(const Sphere& s);
Bounds3 bounds_of(const Cone& c);
inline Bounds3 bounds_of(const PreparedCone& c) { return bounds_of(c.cone); }

}  // namespace holoray
