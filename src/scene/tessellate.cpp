#include "scene/tessellate.hpp"

#include <cmath>
#include <limits>

namespace holoray {
namespace {

struct P2 {
  double x, y;
};

// Twice the signed area of (a, b, c); > 0 when counter-clockwise.
double orient(const P2& a, const P2& b, const P2& c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

bool inside_or_on(const P2& p, const P2& a, const P2& b, const P2& c, double eps) {
  return orient(a, b, p) >= -eps && orient(b, c, p) >= -eps && orient(c, a, p) >= -eps;
}

}  // namespace

Vec3 polygon_normal(std::span<const Vec3> v) {
  Vec3 n;
  const size_t count = v.size();
  for (size_t i = 0; i < count; ++i) {
    const Vec3& a = v[i];
    const Vec3& b = v[(i + 1) % count];
    n.x += (a.y - b.y) * (a.z + b.z);
    n.y += (a.z - b.z) * (a.x + b.x);
    n.z += (a.x - b.x) * (a.y + b.y);
  }
  double scale = 0;
  for (const Vec3& p : v) scale = std::fmax(scale, std::fmax(std::fabs(p.x), std::fmax(std::fabs(p.y), std::fabs(p.z))));
  // Area below rounding noise of the coordinates: no plane to speak of.
  if (!(length(n) > 1e-13 * scale * scale)) return {};
  return normalize(n);
}

Tessellation tessellate_polygon(std::span<const Vec3> vertices) {
  Tessellation out;
  out.normal = polygon_normal(vertices);
  if (out.normal == Vec3{}) return out;

  // Basis (u, w) of the plane with u x w = normal, so winding stays counter-clockwise in 2D.
  const Vec3 n = out.normal;
  const Vec3 helper = std::fabs(n.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
  const Vec3 u = normalize(cross(helper, n));
  const Vec3 w = cross(n, u);
  std::vector<P2> p(vertices.size());
  double extent = 0;
  for (size_t i = 0; i < vertices.size(); ++i) {
    p[i] = {dot(vertices[i], u), dot(vertices[i], w)};
    extent = std::fmax(extent, std::fmax(std::fabs(p[i].x), std::fabs(p[i].y)));
  }
  const double eps = 1e-12 * extent * extent;

  std::vector<int> ring;  // remaining vertices, consecutive duplicates removed
  for (int i = 0; i < static_cast<int>(p.size()); ++i)
    if (ring.empty() || p[ring.back()].x != p[i].x || p[ring.back()].y != p[i].y) ring.push_back(i);
  while (ring.size() > 1 && p[ring.front()].x == p[ring.back()].x && p[ring.front()].y == p[ring.back()].y) ring.pop_back();

  auto emit = [&](int a, int b, int c) {
    if (orient(p[a], p[b], p[c]) > eps) out.triangles.push_back({a, b, c});
  };

  while (ring.size() > 3) {
    const size_t m = ring.size();
    size_t chosen = m;          // an ear
    size_t fallback = 0;        // the most convex corner, if no ear exists (self-intersection)
    double fallback_area = -std::numeric_limits<double>::infinity();
    for (size_t k = 0; k < m && chosen == m; ++k) {
      const int ia = ring[(k + m - 1) % m], ib = ring[k], ic = ring[(k + 1) % m];
      const double area = orient(p[ia], p[ib], p[ic]);
      if (area > fallback_area) { fallback_area = area; fallback = k; }
      if (area <= eps) {
        // Collinear corner: removing it changes nothing but the vertex list.
        if (std::fabs(area) <= eps) chosen = k;
        continue;
      }
      bool blocked = false;
      for (size_t j = 0; j < m && !blocked; ++j) {
        const int iv = ring[j];
        if (iv == ia || iv == ib || iv == ic) continue;
        const P2& q = p[iv];
        // A repeated vertex at a corner (polygon touching itself) does not block.
        if ((q.x == p[ia].x && q.y == p[ia].y) || (q.x == p[ib].x && q.y == p[ib].y) || (q.x == p[ic].x && q.y == p[ic].y)) continue;
        blocked = inside_or_on(q, p[ia], p[ib], p[ic], eps);
      }
      if (!blocked) chosen = k;
    }
    if (chosen == m) chosen = fallback;
    emit(ring[(chosen + m - 1) % m], ring[chosen], ring[(chosen + 1) % m]);
    ring.erase(ring.begin() + static_cast<long>(chosen));
  }
  if (ring.size() == 3) emit(ring[0], ring[1], ring[2]);
  return out;
}

Vec3 shading_normal_in_hemisphere(const Vec3& vertex_normal, const Vec3& winding_normal) {
  const double d = dot(vertex_normal, winding_normal);
  if (!(length(vertex_normal) > 0) || !is_finite(vertex_normal)) return winding_normal;
  return normalize(d < 0 ? -vertex_normal : vertex_normal);
}

}  // namespace holoray
