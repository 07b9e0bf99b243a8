#include "render/textures.hpp"

#include "image/image_io.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace holoray {

namespace {
int bit_count(int n) {
  int b = 0;
  for (; n; n >>= 1) ++b;
  return b;
}

// Tachyon's xyztocyl (unit height): u the angle about z in turns from +x,
// counter-clockwise seen from +z; v the height z.
void to_cylinder(const Vec3& p, double& u, double& v) {
  const double r = std::sqrt(p.x * p.x + p.y * p.y);
  v = p.z;
  const double a = r > 0 ? std::acos(std::clamp(p.x / r, -1.0, 1.0)) / (2 * std::numbers::pi) : 0;
  u = p.y < 0 ? 1 - a : a;
}

// Tachyon's xyztospr: v from the -y pole (0) to the +y pole (1), u the
// angle about y in turns.
void to_sphere(const Vec3& p, double& u, double& v) {
  const double r = length(p);
  if (!(r > 0)) {
    u = v = 0;
    return;
  }
  const double phi = std::acos(std::clamp(-p.y / r, -1.0, 1.0));
  v = phi / 3.1415926;  // Tachyon's own truncated pi, kept for pixel-for-pixel agreement
  const double s = std::sin(phi);
  const double theta = s > 0 ? std::acos(std::clamp(p.x / r / s, -1.0, 1.0)) / (2 * std::numbers::pi) : 0;
  u = p.z > 0 ? theta : 1 - theta;
}

// u - trunc(u), wrapped into [0, 1): Tachyon's repeat.
double wrap(double u) {
  u -= static_cast<double>(static_cast<long>(u));
  return u < 0 ? u + 1 : u;
}
}  // namespace

MipMap::MipMap(const ImageMap& image) : alpha_(image.alpha) {
  levels_.push_back({image.width, image.height, image.depth, image.rgb});
  const int count = image.depth > 1 ? 1 : std::max(bit_count(image.width), bit_count(image.height));
  while (static_cast<int>(levels_.size()) < count) {
    const Level& a = levels_.back();
    Level b{std::max(1, a.width >> 1), std::max(1, a.height >> 1), 1, {}};
    b.rgb.resize(size_t(b.width) * b.height * 3);
    if (image.srgb && a.width > 1 && a.height > 1) {
      // The general loop below for this, the usual case, without its edge
      // clamps: the same four sums in the same order, the same codes.
      const float* lin = decode_table(true);
      for (int y = 0; y < b.height; ++y) {
        const unsigned char* r0 = &a.rgb[size_t(std::min(2 * y, a.height - 1)) * a.width * 3];
        const unsigned char* r1 = &a.rgb[size_t(std::min(2 * y + 1, a.height - 1)) * a.width * 3];
        unsigned char* out = &b.rgb[size_t(y) * b.width * 3];
        for (int x = 0; x < b.width; ++x) {
          const size_t x0 = size_t(std::min(2 * x, a.width - 1)) * 3, x1 = size_t(std::min(2 * x + 1, a.width - 1)) * 3;
          for (int c = 0; c < 3; ++c) {
            float sum = 0;
            sum += lin[r0[x0 + c]];
            sum += lin[r0[x1 + c]];
            sum += lin[r1[x0 + c]];
            sum += lin[r1[x1 + c]];
            out[3 * x + c] = encode_8bit(sum / 4.0f, Encoding::srgb);
          }
        }
      }
      levels_.push_back(std::move(b));
      continue;
    }
    // Tachyon's DecimateImage: the mean of 2x2 texels, truncated to 8 bits
    // (a 1-texel-wide image averages pairs along its length).
    for (int y = 0; y < b.height; ++y)
      for (int x = 0; x < b.width; ++x)
        for (int c = 0; c < 3; ++c) {
          auto at = [&](int xx, int yy) {
            return int{a.rgb[(size_t(std::min(yy, a.height - 1)) * a.width + std::min(xx, a.width - 1)) * 3 + c]};
          };
          int v;
          if (image.srgb) {
            // A mesh texture's codes are sRGB: average the light they stand
            // for (a black and white checker is 0.5 linear, code 188).
            const float* lin = decode_table(true);
            const int n = (a.width > 1 ? 2 : 1) * (a.height > 1 ? 2 : 1);
            float sum = 0;
            for (int dy = 0; dy < (a.height > 1 ? 2 : 1); ++dy)
              for (int dx = 0; dx < (a.width > 1 ? 2 : 1); ++dx)
                sum += lin[at(a.width > 1 ? 2 * x + dx : 0, a.height > 1 ? 2 * y + dy : 0)];
            v = encode_8bit(sum / static_cast<float>(n), Encoding::srgb);
          } else if (a.width > 1 && a.height > 1) {
            v = (at(2 * x, 2 * y) + at(2 * x + 1, 2 * y) + at(2 * x, 2 * y + 1) + at(2 * x + 1, 2 * y + 1)) >> 2;
          } else if (a.width == 1) {
            v = (at(0, 2 * y) + at(0, 2 * y + 1)) >> 1;
          } else {
            v = (at(2 * x, 0) + at(2 * x + 1, 0)) >> 1;
          }
          b.rgb[(size_t(y) * b.width + x) * 3 + c] = static_cast<unsigned char>(v);
        }
    levels_.push_back(std::move(b));
  }
}

// Tachyon's ImageMap and VolImageMapTrilinear: bilinear in x and y, then
// linear between slices (a flat image has one, and w adds nothing).
Vec3 MipMap::trilinear(const Level& l, double u, double v, double w) {
  const double x = (l.width - 1.0) * u, y = (l.height - 1.0) * v, z = (l.depth - 1.0) * w;
  const int ix = static_cast<int>(x), iy = static_cast<int>(y), iz = static_cast<int>(z);
  const double px = x - ix, py = y - iy, pz = z - iz;
  // Tachyon reads one texel past the edge at u, v or w = 1 exactly; clamp instead.
  const int ix1 = std::min(ix + 1, l.width - 1), iy1 = std::min(iy + 1, l.height - 1),
            iz1 = std::min(iz + 1, l.depth - 1);
  auto texel = [&](int xx, int yy, int zz, int c) {
    return double(l.rgb[((size_t(zz) * l.height + yy) * l.width + xx) * 3 + c]);
  };
  auto slice = [&](int zz, int c) {
    const double lo = texel(ix, iy, zz, c) + px * (texel(ix1, iy, zz, c) - texel(ix, iy, zz, c));
    const double hi = texel(ix, iy1, zz, c) + px * (texel(ix1, iy1, zz, c) - texel(ix, iy1, zz, c));
    return lo + py * (hi - lo);
  };
  double out[3];
  for (int c = 0; c < 3; ++c) {
    const double near = slice(iz, c);
    out[c] = (l.depth > 1 ? near + pz * (slice(iz1, c) - near) : near) / 255.0;
  }
  return {out[0], out[1], out[2]};
}

template <class Lookup>
Vec3 MipMap::blend_levels(double d, Lookup lookup) const {
  d = std::clamp(d, 0.0, 1.0);
  const int n = levels();
  const double level = d * (n - 0.9999);
  const int i = static_cast<int>(level);
  const double frac = level - i;
  // Past the second-coarsest level Tachyon takes the coarsest, unblended.
  if (i < n - 2) {
    const Vec3 a = lookup(levels_[size_t(i)]), b = lookup(levels_[size_t(i) + 1]);
    return a + (b - a) * frac;
  }
  return lookup(levels_.back());
}

Vec3 MipMap::sample(double u, double v, double d) const {
  if (!(u >= 0 && u <= 1 && v >= 0 && v <= 1)) return {};
  return blend_levels(d, [&](const Level& l) { return trilinear(l, u, v, 0); });
}

Vec3 MipMap::sample_volume(double u, double v, double w, double d) const {
  if (!(u >= 0 && u <= 1 && v >= 0 && v <= 1 && w >= 0 && w <= 1)) return {};
  return blend_levels(d, [&](const Level& l) { return trilinear(l, u, v, w); });
}

Vec3 texture_colour(const TextureDesc& tex, const MipMap* mip, const Vec3& base, const Vec3& p, double optic_dist) {
  const Vec3 q = p - tex.centre;
  switch (tex.kind) {
    case TextureDesc::Kind::checker3d: {
      // Cells a third of a unit wide, mirrored about the centre (|x|).
      const long x = static_cast<long>(std::fabs(q.x) * 3 + 0.5) % 2, y = static_cast<long>(std::fabs(q.y) * 3 + 0.5) % 2,
                 z = static_cast<long>(std::fabs(q.z) * 3 + 0.5) % 2;
      return (x + y + z) % 2 == 1 ? Vec3{1, 0.2, 0} : Vec3{0, 0.2, 1};
    }
    case TextureDesc::Kind::cylinder_checker: {
      double u, v;
      to_cylinder(q, u, v);
      const long x = static_cast<long>(std::fabs(u) * 18.0) % 2, y = static_cast<long>(std::fabs(v) * 10.0) % 2;
      return (x + y) % 2 == 1 ? Vec3{1, 0.2, 0} : Vec3{0, 0.2, 1};
    }
    case TextureDesc::Kind::cylindrical_image:
    case TextureDesc::Kind::spherical_image: {
      if (mip == nullptr) return base;
      double u, v;
      // The cylinder's axis is the texture's y: Tachyon swaps y and z first.
      if (tex.kind == TextureDesc::Kind::cylindrical_image) to_cylinder({q.x, q.z, q.y}, u, v);
      else to_sphere(q, u, v);
      u = wrap(u * tex.scale.x + tex.rotate.x);
      v = wrap(v * tex.scale.y + tex.rotate.y);
      const double max_scale = std::fabs(tex.scale.x) > std::fabs(tex.scale.y) ? tex.scale.x : tex.scale.y;
      // MIP distance per unit of angle: divided by 8 radii (Tachyon's).
      return mip->sample(u, v, 0.05 * optic_dist * std::fabs(max_scale) / (1e-8 + 8 * length(q)));
    }
    case TextureDesc::Kind::wood: {
      const double x = q.x / tex.scale.x, y = q.y / tex.scale.y, z = q.z / tex.scale.z;
      double radius = std::sqrt(x * x + z * z);
      const double angle = z == 0 ? 3.1415926 / 2 : std::atan(x / z);
      radius += 3.0 * std::sin(20 * angle + y / 150.0);
      const int grain = static_cast<int>(radius + 0.5) % 60;
      return grain < 40 ? Vec3{0.8, 1.0, 0.2} : Vec3{0, 0, 0};
    }
    case TextureDesc::Kind::planar_image: {
      if (mip == nullptr) return base;
      const double u = wrap(dot(tex.uaxis, q) * tex.scale.x + tex.rotate.x);
      const double v = wrap(dot(tex.vaxis, q) * tex.scale.y + tex.rotate.y);
      const double max_scale = std::fabs(tex.scale.x) > std::fabs(tex.scale.y) ? tex.scale.x : tex.scale.y;
      return mip->sample(u, v, 0.05 * optic_dist * std::fabs(max_scale));
    }
    case TextureDesc::Kind::volume_image: {
      if (mip == nullptr) return base;
      const double u = wrap(dot(tex.uaxis, q) * tex.scale.x + tex.rotate.x);
      const double v = wrap(dot(tex.vaxis, q) * tex.scale.y + tex.rotate.y);
      const double w = wrap(dot(tex.waxis, q) * tex.scale.z + tex.rotate.z);
      double max_scale = std::fabs(tex.scale.x) > std::fabs(tex.scale.y) ? tex.scale.x : tex.scale.y;
      if (std::fabs(tex.scale.z) > std::fabs(max_scale)) max_scale = tex.scale.z;
      return mip->sample_volume(u, v, w, 0.05 * optic_dist * std::fabs(max_scale));
    }
    case TextureDesc::Kind::uv_image:
      // A mesh's map is read at the hit's texture coordinates, which a
      // world-space point does not give (RenderScene::texel_at).
      return base;
  }
  return base;
}

namespace {

// Texel index i of an axis of n texels under a wrap mode (glTF 2.0 §5.26).
// Folded coordinates (fold) put i in [-1, 2n]: inside the texture every mode
// gives i itself, and one period on, repeat and mirror need no division (the
// general case's two integer divisions per index were most of a bilinear
// fetch: eight indices per level, two levels per MIP-blended sample).
inline int wrap_index(int i, int n, TextureWrap mode) {
  if (static_cast<unsigned>(i) < static_cast<unsigned>(n)) [[likely]] return i;
  if (i >= n && i < 2 * n && mode != TextureWrap::clamp) return mode == TextureWrap::repeat ? i - n : 2 * n - 1 - i;
  switch (mode) {
    case TextureWrap::clamp: return std::clamp(i, 0, n - 1);
    case TextureWrap::mirror: {
      const int m = ((i % (2 * n)) + 2 * n) % (2 * n);
      return m < n ? m : 2 * n - 1 - m;
    }
    case TextureWrap::repeat: break;
  }
  return ((i % n) + n) % n;
}

// u or v kept near the unit square: far outside it the float texel position
// loses its fraction (the period under repeat and mirror is 2).
double fold(double x, TextureWrap w) {
  return w == TextureWrap::clamp ? std::clamp(x, -1.0, 2.0) : x - 2 * std::floor(x / 2);
}

// Bilinear between the texel centres of a width x height grid at folded
// (u, v); fetch(ix, iy) reads a texel by wrapped indices.
template <class Fetch>
auto bilinear(double u, double v, int width, int height, TextureWrap wrap_u, TextureWrap wrap_v, Fetch fetch) {
  auto texel = [&](int x, int y) { return fetch(wrap_index(x, width, wrap_u), wrap_index(y, height, wrap_v)); };
  const double x = u * width, y = v * height;
  const double fx = x - 0.5 - std::floor(x - 0.5), fy = y - 0.5 - std::floor(y - 0.5);
  const int x0 = static_cast<int>(std::floor(x - 0.5)), y0 = static_cast<int>(std::floor(y - 0.5));
  return (texel(x0, y0) * (1 - fx) + texel(x0 + 1, y0) * fx) * (1 - fy) +
         (texel(x0, y0 + 1) * (1 - fx) + texel(x0 + 1, y0 + 1) * fx) * fy;
}

std::array<float, 256> make_table(bool srgb) {
  std::array<float, 256> t{};
  for (int c = 0; c < 256; ++c) {
    const double e = c / 255.0;
    t[static_cast<size_t>(c)] =
        static_cast<float>(!srgb ? e : e <= 0.04045 ? e / 12.92 : std::pow((e + 0.055) / 1.055, 2.4));
  }
  return t;
}

}  // namespace

const float* decode_table(bool srgb) {
  static const std::array<float, 256> linear = make_table(false), decoded = make_table(true);
  return srgb ? decoded.data() : linear.data();
}

double MipMap::alpha_uv(double u, double v, TextureWrap wrap_u, TextureWrap wrap_v) const {
  const Level& l = levels_.front();
  if (alpha_.size() != size_t(l.width) * l.height) return 1;
  if (!std::isfinite(u) || !std::isfinite(v)) return 0;
  return bilinear(fold(u, wrap_u), fold(v, wrap_v), l.width, l.height, wrap_u, wrap_v,
                  [&](int x, int y) { return alpha_[size_t(y) * l.width + x] / 255.0; });
}

Vec3 MipMap::sample_uv(double u, double v, double level, TextureWrap wrap_u, TextureWrap wrap_v, bool nearest,
                       const float decode[256]) const {
  if (!std::isfinite(u) || !std::isfinite(v)) return {};
  u = fold(u, wrap_u);
  v = fold(v, wrap_v);
  auto one_level = [&](int li, bool pick_nearest) {
    const Level& l = levels_[static_cast<size_t>(li)];
    auto texel = [&](int x, int y) {
      const unsigned char* p = &l.rgb[(size_t(y) * l.width + x) * 3];
      return Vec3{decode[p[0]], decode[p[1]], decode[p[2]]};
    };
    if (pick_nearest)
      return texel(wrap_index(static_cast<int>(std::floor(u * l.width)), l.width, wrap_u),
                   wrap_index(static_cast<int>(std::floor(v * l.height)), l.height, wrap_v));
    return bilinear(u, v, l.width, l.height, wrap_u, wrap_v, texel);
  };
  const double top = levels() - 1;
  const double lv = std::isfinite(level) ? std::clamp(level, 0.0, top) : 0.0;
  if (lv <= 0) return one_level(0, nearest);
  const int l0 = static_cast<int>(std::floor(lv));
  const double f = lv - l0;
  if (l0 >= top || f == 0) return one_level(l0, false);
  return one_level(l0, false) * (1 - f) + one_level(l0 + 1, false) * f;
}

}  // namespace holoray
