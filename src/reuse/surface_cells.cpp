#include "reuse/surface_cells.hpp"

#include <fmt/format.h>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace holoray {

namespace {

constexpr double kQuarterTurn = 1.5707963267948966;  // a cube-map face spans a quarter circle

Vec3 vertex(const TriangleData& tri, uint32_t prim, int k) {
  const float* p = &tri.positions[3 * size_t{tri.indices[3 * size_t{prim} + k]}];
  return {p[0], p[1], p[2]};
}

int cells_for(double length, double cell_size) {
  const double n = std::ceil(length / cell_size);
  if (!(n >= 1)) return 1;  // also NaN
  return static_cast<int>(std::min<double>(n, SurfaceCells::kMaxCellsPerSide));
}

int cell_index(double s, int n) {  // s in [0, 1]; fmin/fmax also map NaN into range (no UB in the cast)
  const int i = static_cast<int>(std::fmax(0.0, std::fmin(s, 1.0)) * n);
  return std::clamp(i, 0, n - 1);
}

// The other two axes of a cube-map face whose major axis is `axis`.
void face_axes(int axis, int& a, int& b) {
  a = (axis + 1) % 3;
  b = (axis + 2) % 3;
}

Vec3 axis_vec(int axis, double s) { return {axis == 0 ? s : 0, axis == 1 ? s : 0, axis == 2 ? s : 0}; }

// Orthonormal axes around a cone's axis, fixed by the axis alone.
void cone_frame(const Cone& c, Vec3& a, double& len, Vec3& e1, Vec3& e2) {
  const Vec3 d = c.apex - c.base;
  len = length(d);
  a = len > 0 ? d / len : Vec3{0, 0, 1};
  const Vec3 helper = std::fabs(a.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
  e1 = normalize(cross(helper, a));
  e2 = cross(a, e1);
}

// The square map of a direction in a plane: face 0..3 (+x, -x, +y, -y) and
// the minor coordinate over the major one, in [-1, 1].
void square_map(double x, double y, int& face, double& s) {
  if (std::fabs(x) >= std::fabs(y)) {
    face = x >= 0 ? 0 : 1;
    s = x != 0 ? y / std::fabs(x) : 0;
  } else {
    face = y >= 0 ? 2 : 3;
    s = x / std::fabs(y);
  }
}

Vec3 square_unmap(int face, double s, const Vec3& e1, const Vec3& e2) {
  switch (face) {
    case 0: return normalize(e1 + e2 * s);
    case 1: return normalize(-e1 + e2 * s);
    case 2: return normalize(e2 + e1 * s);
    default: return normalize(-e2 + e1 * s);
  }
}

// Where cell `local` of an n x n (or, for cones, n x m) grid of square
// patches lies: its face and its lower corner (i, j).
struct PatchCell {
  int face, i, j;
};

PatchCell sphere_cell(uint32_t local, int n) {
  const int face = static_cast<int>(local) / (n * n), rest = static_cast<int>(local) % (n * n);
  return {face, rest / n, rest % n};
}

PatchCell cone_cell(uint32_t local, int m) {
  return {static_cast<int>(local) / m % 4, static_cast<int>(local) / (4 * m), static_cast<int>(local) % m};
}

// The point of a sphere's cube-map face at grid coordinates (fi, fj) of n.
CellSample sphere_at(const Sphere& s, int face, int n, double fi, double fj) {
  const int axis = face / 2;
  const double sign = face % 2 ? -1 : 1;
  int a, b;
  face_axes(axis, a, b);
  const double sa = -1 + 2 * fi / n, sb = -1 + 2 * fj / n;
  const Vec3 d = normalize(axis_vec(axis, sign) + axis_vec(a, sa) + axis_vec(b, sb));
  return {s.centre + d * std::fabs(s.radius), d};
}

// The point of a cone at grid coordinates (fh of n along the axis, fi of m
// across the square-map face).
CellSample cone_at(const Cone& cone, int face, int n, int m, double fh, double fi) {
  Vec3 ax, e1, e2;
  double len;
  cone_frame(cone, ax, len, e1, e2);
  const double h = fh / n;
  const Vec3 radial = square_unmap(face, -1 + 2 * fi / m, e1, e2);
  // Negative radii only turn which side is visible, not where the surface is.
  const double rb = std::fabs(cone.base_radius), ra = std::fabs(cone.apex_radius);
  const double r = rb + (ra - rb) * h;
  // Normal of the surface base + ax*h*len + radial*r(h): across the circle
  // and the slope both.
  const Vec3 nrm = normalize(radial * len - ax * (ra - rb));
  return {cone.base + ax * (h * len) + radial * r, nrm};
}

// Vertex (a, b), a + b <= n, of a triangle's barycentric grid, numbered row
// by row: row a holds n + 1 - a vertices.
uint64_t triangle_vertex(int n, int a, int b) {
  return uint64_t(a) * (n + 1) - uint64_t(a) * (a - 1) / 2 + b;
}

uint64_t triangle_vertices(int n) { return uint64_t(n + 1) * (n + 2) / 2; }

}  // namespace

SurfaceCells::SurfaceCells(const AccelScene& accel, double cell_size, uint64_t max_slots) : accel_(accel) {
  if (!(cell_size > 0) || !std::isfinite(cell_size))
    throw std::invalid_argument(fmt::format("the surface cell size must be positive, got {}", cell_size));
  // Cells are never grown to fit the bound: a coarser cell misses smaller
  // shadows (its samples decide "lit"); primitives past the bound trace.
  cell_size_ = cell_size;
  build(cell_size, max_slots);
}

uint64_t SurfaceCells::build(double c, uint64_t max_slots) {
  slots_ = vertices_ = uncovered_ = 0;
  for (auto& k : prims_) k.assign(accel_.group_count(), {});
  cone_frames_.assign(accel_.group_count(), {});
  auto place = [&](PrimCells& pc, uint64_t count, uint64_t vertices) {
    if (slots_ + vertices_ + count + vertices > max_slots) {
      ++uncovered_;
      return;
    }
    pc.first = slots_;
    pc.first_vertex = vertices_;
    slots_ += count;
    vertices_ += vertices;
  };
  for (uint32_t g = 0; g < accel_.group_count(); ++g) {
    const GeometryGroup& geo = accel_.geometry(g);
    const size_t tris = geo.triangles.indices.size() / 3;
    auto& tp = prims_[0][g];
    tp.resize(tris);
    for (uint32_t t = 0; t < tris; ++t) {
      const Vec3 v0 = vertex(geo.triangles, t, 0), v1 = vertex(geo.triangles, t, 1), v2 = vertex(geo.triangles, t, 2);
      // Sub-triangles of about c^2 / 2 each: slivers (fans of long polygons)
      // get few cells, not (longest edge / c)^2 of them.
      const double area = 0.5 * length(cross(v1 - v0, v2 - v0));
      tp[t].n = static_cast<uint16_t>(cells_for(std::sqrt(2 * area), c));
      place(tp[t], 2 * uint64_t{tp[t].n} * tp[t].n, triangle_vertices(tp[t].n));
    }
    auto& sp = prims_[1][g];
    sp.resize(geo.spheres.size());
    for (size_t k = 0; k < geo.spheres.size(); ++k) {
      sp[k].n = static_cast<uint16_t>(cells_for(std::fabs(geo.spheres[k].radius) * kQuarterTurn, c));
      place(sp[k], 6 * uint64_t{sp[k].n} * sp[k].n, 6 * uint64_t(sp[k].n + 1) * (sp[k].n + 1));
    }
    auto& cp = prims_[2][g];
    cp.resize(geo.cones.size());
    cone_frames_[g].resize(geo.cones.size());
    for (size_t k = 0; k < geo.cones.size(); ++k) {
      const Cone& cone = geo.cones[k];
      ConeFrame& cf = cone_frames_[g][k];
      cone_frame(cone, cf.axis, cf.length, cf.e1, cf.e2);
      const double r = std::max(std::fabs(cone.base_radius), std::fabs(cone.apex_radius));
      cp[k].n = static_cast<uint16_t>(cells_for(length(cone.apex - cone.base), c));
      cp[k].m = static_cast<uint16_t>(cells_for(r * kQuarterTurn, c));
      place(cp[k], 4 * uint64_t{cp[k].n} * cp[k].m, 4 * uint64_t(cp[k].n + 1) * (cp[k].m + 1));
    }
  }
  return slots_;
}

CellRef SurfaceCells::locate(uint32_t group, PrimKind kind, uint32_t prim, double u, double v,
                             const Vec3& p_object) const {
  const PrimCells& pc = prims_[static_cast<int>(kind)][group][prim];
  CellRef ref = CellRef::none();
  if (pc.first == CellRef::kNone) return ref;
  const GeometryGroup& geo = accel_.geometry(group);
  switch (kind) {
    case PrimKind::triangle: {
      const int n = pc.n;
      const double a = std::fmax(0.0, std::fmin(u, 1.0)) * n, b = std::fmax(0.0, std::fmin(v, 1.0)) * n;
      const int i = std::clamp(static_cast<int>(a), 0, n - 1);
      const int j = std::clamp(static_cast<int>(b), 0, n - 1 - i);
      const bool upper = (a - i) + (b - j) > 1 && i + j < n - 1;
      ref.local = static_cast<uint32_t>((i * n + j) * 2 + (upper ? 1 : 0));
      break;
    }
    case PrimKind::sphere: {
      const int n = pc.n;
      const Vec3 d = p_object - geo.spheres[prim].centre;
      const double ad[3] = {std::fabs(d.x), std::fabs(d.y), std::fabs(d.z)};
      const int axis = ad[0] >= ad[1] ? (ad[0] >= ad[2] ? 0 : 2) : (ad[1] >= ad[2] ? 1 : 2);
      int a, b;
      face_axes(axis, a, b);
      const double major = ad[axis] > 0 ? ad[axis] : 1;
      const int face = axis * 2 + (d[axis] < 0 ? 1 : 0);
      const int i = cell_index((d[a] / major + 1) * 0.5, n), j = cell_index((d[b] / major + 1) * 0.5, n);
      ref.local = static_cast<uint32_t>((face * n + i) * n + j);
      break;
    }
    case PrimKind::cone: {
      const Cone& cone = geo.cones[prim];
      const ConeFrame& cf = cone_frames_[group][prim];
      const Vec3 &ax = cf.axis, &e1 = cf.e1, &e2 = cf.e2;
      const double len = cf.length;
      const Vec3 r = p_object - cone.base;
      const double h = len > 0 ? dot(r, ax) / len : 0;
      int face;
      double s;
      square_map(dot(r, e1), dot(r, e2), face, s);
      const int hi = cell_index(h, pc.n), i = cell_index((s + 1) * 0.5, pc.m);
      ref.local = static_cast<uint32_t>((hi * 4 + face) * pc.m + i);
      break;
    }
  }
  ref.slot = pc.first + ref.local;
  return ref;
}

int SurfaceCells::corners(uint32_t group, PrimKind kind, uint32_t prim, uint32_t local,
                          CellCorner out[kMaxCorners]) const {
  const PrimCells& pc = prims_[static_cast<int>(kind)][group][prim];
  const GeometryGroup& geo = accel_.geometry(group);
  switch (kind) {
    case PrimKind::triangle: {
      const int n = pc.n;
      const bool upper = local & 1;
      const int ij = static_cast<int>(local >> 1), i = ij / n, j = ij % n;
      const Vec3 v0 = vertex(geo.triangles, prim, 0);
      const Vec3 e1 = vertex(geo.triangles, prim, 1) - v0, e2 = vertex(geo.triangles, prim, 2) - v0;
      const Vec3 normal = normalize(cross(e1, e2));
      auto at = [&](int a, int b) {
        return CellCorner{pc.first_vertex + triangle_vertex(n, a, b),
                          {v0 + e1 * (static_cast<double>(a) / n) + e2 * (static_cast<double>(b) / n), normal}};
      };
      if (upper) {
        out[0] = at(i + 1, j), out[1] = at(i, j + 1), out[2] = at(i + 1, j + 1);
      } else {
        out[0] = at(i, j), out[1] = at(i + 1, j), out[2] = at(i, j + 1);
      }
      return 3;
    }
    case PrimKind::sphere: {
      const int n = pc.n;
      const PatchCell c = sphere_cell(local, n);
      const uint64_t face_base = pc.first_vertex + uint64_t(c.face) * (n + 1) * (n + 1);
      for (int k = 0; k < 4; ++k) {
        const int a = c.i + (k & 1), b = c.j + (k >> 1);
        out[k] = {face_base + uint64_t(a) * (n + 1) + b, sphere_at(geo.spheres[prim], c.face, n, a, b)};
      }
      return 4;
    }
    case PrimKind::cone: {
      const int n = pc.n, m = pc.m;
      const PatchCell c = cone_cell(local, m);
      const uint64_t face_base = pc.first_vertex + uint64_t(c.face) * (n + 1) * (m + 1);
      for (int k = 0; k < 4; ++k) {
        const int a = c.i + (k & 1), b = c.j + (k >> 1);
        out[k] = {face_base + uint64_t(a) * (m + 1) + b, cone_at(geo.cones[prim], c.face, n, m, a, b)};
      }
      return 4;
    }
  }
  return 0;
}

CellSample SurfaceCells::centre(uint32_t group, PrimKind kind, uint32_t prim, uint32_t local) const {
  const PrimCells& pc = prims_[static_cast<int>(kind)][group][prim];
  const GeometryGroup& geo = accel_.geometry(group);
  switch (kind) {
    case PrimKind::triangle: {
      CellCorner c[kMaxCorners];
      corners(group, kind, prim, local, c);
      return {(c[0].sample.p_object + c[1].sample.p_object + c[2].sample.p_object) / 3.0, c[0].sample.n_object};
    }
    case PrimKind::sphere: {
      const PatchCell p = sphere_cell(local, pc.n);
      return sphere_at(geo.spheres[prim], p.face, pc.n, p.i + 0.5, p.j + 0.5);
    }
    case PrimKind::cone: {
      const PatchCell p = cone_cell(local, pc.m);
      return cone_at(geo.cones[prim], p.face, pc.n, pc.m, p.i + 0.5, p.j + 0.5);
    }
  }
  return {};
}

int SurfaceCells::samples(uint32_t group, PrimKind kind, uint32_t prim, uint32_t local,
                          CellSample out[kMaxSamples]) const {
  CellCorner c[kMaxCorners];
  const int n = corners(group, kind, prim, local, c);
  for (int k = 0; k < n; ++k) out[k] = c[k].sample;
  out[n] = centre(group, kind, prim, local);
  return n + 1;
}

}  // namespace holoray
