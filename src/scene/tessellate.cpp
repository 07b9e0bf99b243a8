#include "scene/tessellate.hpp"

#include <cmath>
#include <cstdint>
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

  // The ring as a linked list; each corner's ear status is kept and, after
  // a clip, recomputed only at the two corners next to it (removing an
  // ear's tip unblocks no other corner of a simple polygon), so the whole
  // clipping is O(n^2). Of the ears, the one whose world bounding box has
  // the least surface area goes first (the BVH's cost of the triangle): a
  // 144-vertex gear face becomes fat triangles, where clipping the first ear
  // found fans slivers across the whole face, whose long boxes the rays keep
  // entering.
  const size_t m0 = ring.size();
  std::vector<size_t> prev(m0), next(m0);
  for (size_t k = 0; k < m0; ++k) prev[k] = (k + m0 - 1) % m0, next[k] = (k + 1) % m0;
  enum class Corner : uint8_t { reflex, collinear, blocked, ear };
  std::vector<Corner> state(m0);
  std::vector<double> box(m0);  // an ear's bounding-box half surface area
  size_t left = m0;
  auto classify = [&](size_t k) {
    const int ia = ring[prev[k]], ib = ring[k], ic = ring[next[k]];
    const double area = orient(p[ia], p[ib], p[ic]);
    if (std::fabs(area) <= eps) return state[k] = Corner::collinear;
    if (area < 0) return state[k] = Corner::reflex;
    for (size_t j = next[next[k]]; j != prev[k]; j = next[j]) {
      const P2& q = p[ring[j]];
      // A repeated vertex at a corner (polygon touching itself) does not block.
      if ((q.x == p[ia].x && q.y == p[ia].y) || (q.x == p[ib].x && q.y == p[ib].y) || (q.x == p[ic].x && q.y == p[ic].y)) continue;
      if (inside_or_on(q, p[ia], p[ib], p[ic], eps)) return state[k] = Corner::blocked;
    }
    const Vec3 lo = min(vertices[ia], min(vertices[ib], vertices[ic]));
    const Vec3 e = max(vertices[ia], max(vertices[ib], vertices[ic])) - lo;
    box[k] = e.x * e.y + e.y * e.z + e.z * e.x;
    return state[k] = Corner::ear;
  };
  for (size_t k = 0; k < m0; ++k) classify(k);
  size_t at = 0;  // a corner still in the ring
  while (left > 3) {
    size_t chosen = m0;
    for (int pass = 0; pass < 2 && chosen == m0; ++pass) {
      if (pass == 1)  // none flagged: recheck all before giving up on ears
        for (size_t k = at, n = 0; n < left; k = next[k], ++n) classify(k);
      double best = std::numeric_limits<double>::infinity();
      for (size_t k = at, n = 0; n < left; k = next[k], ++n) {
        // Collinear corner: removing it changes nothing but the vertex list.
        if (state[k] == Corner::collinear) { chosen = k; break; }
        if (state[k] == Corner::ear && box[k] < best) best = box[k], chosen = k;
      }
    }
    if (chosen == m0) {  // no ear (self-intersection): the most convex corner
      double most = -std::numeric_limits<double>::infinity();
      for (size_t k = at, n = 0; n < left; k = next[k], ++n) {
        const double area = orient(p[ring[prev[k]]], p[ring[k]], p[ring[next[k]]]);
        if (area > most) most = area, chosen = k;
      }
    }
    emit(ring[prev[chosen]], ring[chosen], ring[next[chosen]]);
    const size_t a = prev[chosen], c = next[chosen];
    next[a] = c, prev[c] = a, at = a, --left;
    if (left > 3) classify(a), classify(c);
  }
  if (left == 3) {
    emit(ring[prev[at]], ring[at], ring[next[at]]);
    return out;
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
