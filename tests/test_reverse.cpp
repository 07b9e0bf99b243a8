// Reverse reprojection (temporal/reverse.hpp, issue 12): exact visibility,
// the mapping of a hit back into a keyframe (camera and object motion), what
// is reused, and what is refused.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <tuple>

#include "camera/placement.hpp"
#include "image/metrics.hpp"
#include "render/renderer.hpp"
#include "scene/nff_reader.hpp"
#include "temporal/reverse.hpp"
#include "test_util.hpp"

namespace holoray {
namespace {
using test::camera_at;
using test::source_dir;
using test::trace_full;

size_t hits_of(const PointImage& key) {
  size_t n = 0;
  for (const PrimaryHit& h : key.hits) n += h.status == PrimaryHit::kHit;
  return n;
}

// The keyframe's object id per pixel, as a frame holds them.
std::vector<int32_t> objects_of(const PointImage& key) {
  std::vector<int32_t> ids;
  for (const PointImage::Seen& s : key.seen) ids.push_back(s.object);
  return ids;
}

float max_difference(const FloatSamples& a, const FloatSamples& b) {
  float d = 0;
  for (size_t k = 0; k < a.size(); ++k) d = std::fmax(d, std::fabs(a[k] - b[k]));
  return d;
}

double psnr(const ImageBuffer& truth, const ImageBuffer& test) {
  return compare_images(quantize_8bit(truth, Encoding::linear), quantize_8bit(test, Encoding::linear)).psnr_all();
}

// primitives.nff: mirrors, highlights, a transmitter and two lights.
TEST(ReverseReprojection, KeyframeTracingEqualsFullRayTracing) {
  const SceneDesc desc = read_nff_file(source_dir() + "/examples/primitives.nff");
  const RenderScene scene(desc);
  const LensArrayDesc cam = camera_at(desc, {});
  RenderStats stats;
  const PointImage key = trace_point_image(scene, LensArray(cam), 0, ReverseReuse::visibility, 0, stats);
  EXPECT_EQ(key.colour.data, trace_full(scene, cam).colour.data);
  EXPECT_EQ(key.parts.size(), key.hits.size());
  EXPECT_EQ(key.to_world.size(), scene.accel().group_count());
}

// At the keyframe's own camera every hit projects back onto its own pixel:
// colour reuse returns the keyframe exactly; visibility reuse recomputes the
// local terms and adds the recorded secondary light, the same sum to float
// rounding.
TEST(ReverseReprojection, AtTheKeyframesCameraEveryHitFindsItsOwnPixel) {
  const SceneDesc desc = read_nff_file(source_dir() + "/examples/primitives.nff");
  const RenderScene scene(desc);
  const LensArrayDesc cam = camera_at(desc, {});
  for (ReverseReuse reuse : {ReverseReuse::color, ReverseReuse::visibility}) {
    RenderStats stats;
    const PointImage key = trace_point_image(scene, LensArray(cam), 0, reuse, 0, stats);
    ReverseOptions opt;
    opt.reuse = reuse;
    opt.copy_unchanged = false;  // the lookups, not the copy of a hold
    const ReprojectedFrame rf = reverse_reproject(scene, LensArray(cam), 1, &key, nullptr, opt);
    EXPECT_GT(rf.count(PixelStatus::reprojected), hits_of(key) * 95 / 100);
    if (reuse == ReverseReuse::color) EXPECT_EQ(rf.colour.data, key.colour.data);
    else EXPECT_LT(max_difference(rf.colour.data, key.colour.data), 1e-5f);
  }
}

// Eye rays are traced: which surface each pixel shows is exactly full
// tracing's, background included, and shaded pixels are full tracing's.
TEST(ReverseReprojection, VisibilityAndShadedPixelsAreFullRayTracings) {
  const SceneDesc desc = read_nff_file(source_dir() + "/examples/primitives.nff");
  const RenderScene scene(desc);
  RenderStats stats;
  const PointImage key = trace_point_image(scene, LensArray(camera_at(desc, {})), 0, ReverseReuse::color, 0, stats);
  const LensArrayDesc moved = camera_at(desc, {0.4, 0, 0.2});
  const FrameBuffers full = trace_full(scene, moved);
  const ReprojectedFrame rf = reverse_reproject(scene, LensArray(moved), 1, &key, nullptr, ReverseOptions{ReverseReuse::color});
  size_t wrong_object = 0, wrong_shaded = 0, shaded = 0;
  for (size_t p = 0; p < rf.object.size(); ++p) {
    wrong_object += rf.object[p] != static_cast<int>(full.id.data[p]);
    if (rf.status[p] != PixelStatus::traced) continue;
    ++shaded;
    for (int c = 0; c < 3; ++c) wrong_shaded += std::fabs(rf.colour.data[3 * p + c] - full.colour.data[3 * p + c]) > 1e-6f;
  }
  EXPECT_EQ(wrong_object, 0u);
  EXPECT_EQ(wrong_shaded, 0u);
  EXPECT_GT(shaded, 0u);
  EXPECT_GT(rf.count(PixelStatus::reprojected), rf.object.size() / 4);
  EXPECT_EQ(rf.count(PixelStatus::missed), 0u);
}

// Under camera motion, visibility reuse (local shading exact, shadow and
// mirror edges traced) is near exact and better than colour reuse.
TEST(ReverseReprojection, CameraMotionVisibilityReuseReaches40dB) {
  const SceneDesc desc = read_nff_file(source_dir() + "/examples/primitives.nff");
  const RenderScene scene(desc);
  const LensArrayDesc moved = camera_at(desc, {0.5, 0, 0.25});
  const FrameBuffers full = trace_full(scene, moved);
  double quality[2];
  for (ReverseReuse reuse : {ReverseReuse::color, ReverseReuse::visibility}) {
    RenderStats stats;
    const PointImage key = trace_point_image(scene, LensArray(camera_at(desc, {})), 0, reuse, 0, stats);
    const ReprojectedFrame rf = reverse_reproject(scene, LensArray(moved), 1, &key, nullptr, ReverseOptions{reuse});
    EXPECT_GT(rf.count(PixelStatus::reprojected), rf.object.size() / 4);
    quality[static_cast<int>(reuse)] = psnr(full.colour, rf.colour);
  }
  EXPECT_GE(quality[1], 40.0);
  EXPECT_GT(quality[1], quality[0]);
}

// A keyframe traced for visibility reuse carries each pixel's edges: the
// lights seen differently, and secondary light differing by more than an
// 8-bit step, among its 8 neighbours in its elemental image that hit the
// same primitive (recomputed here from the keyframe's records). They mark
// shadow and mirror edges of primitives.nff, not every hit; a keyframe
// without them is refused for visibility reuse.
TEST(ReverseReprojection, KeyframeEdgesMarkWhereNeighboursOnThePrimitiveDisagree) {
  const SceneDesc desc = read_nff_file(source_dir() + "/examples/primitives.nff");
  const RenderScene scene(desc);
  RenderStats stats;
  const PointImage key = trace_point_image(scene, LensArray(camera_at(desc, {})), 3, ReverseReuse::visibility, 0, stats);
  ASSERT_EQ(key.edges.size(), key.hits.size());
  const LensArray& cam = key.camera;
  const int W = cam.width(), H = cam.height();
  size_t shadow = 0, secondary = 0;
  for (int j = 0; j < H; ++j)
    for (int i = 0; i < W; ++i) {
      const size_t p = static_cast<size_t>(j) * W + i;
      const PrimaryHit& own = key.hits[p];
      if (own.status != PrimaryHit::kHit) continue;
      uint32_t lights = 0;
      bool light_changes = false;
      for (int nj = std::max(0, j - 1); nj <= std::min(H - 1, j + 1); ++nj)
        for (int ni = std::max(0, i - 1); ni <= std::min(W - 1, i + 1); ++ni) {
          const size_t q = static_cast<size_t>(nj) * W + ni;
          const PrimaryHit& h = key.hits[q];
          if (q == p || !(cam.lens_of_pixel(ni, nj) == cam.lens_of_pixel(i, j)) || h.status != PrimaryHit::kHit ||
              h.prim != own.prim || h.group != own.group || h.kind != own.kind)
            continue;
          lights |= key.parts[q].lit ^ key.parts[p].lit;
          for (int c = 0; c < 3; ++c)
            light_changes |= std::fabs(key.parts[q].secondary[c] - key.parts[p].secondary[c]) > 1.0f / 255;
        }
      ASSERT_EQ(key.edges[p].shadow, lights) << "pixel " << i << "," << j;
      ASSERT_EQ(key.edges[p].secondary, light_changes) << "pixel " << i << "," << j;
      shadow += lights != 0, secondary += light_changes;
    }
  EXPECT_GT(shadow, 0u);
  EXPECT_GT(secondary, 0u);
  EXPECT_LT(shadow + secondary, hits_of(key));
  PointImage bare = key;
  bare.edges.clear();
  try {
    reverse_reproject(scene, cam, 4, &bare, nullptr, ReverseOptions{ReverseReuse::visibility});
    FAIL() << "a keyframe without edge records was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(e.what(),
              fmt::format("the point image of frame 3 has 0 edge records for {} pixels: trace it for visibility reuse", W * H));
  }
}

// An object and the camera translated together see the object as the
// keyframe did: colour reuse maps every hit back through the object's
// transforms onto its own keyframe pixel. Visibility reuse refuses (a moved
// object may have moved a shadow) and shades every hit.
TEST(ReverseReprojection, HitsFollowTheirObjectsMotion) {
  const SceneDesc ball = parse_nff("l 0 -3 8\nf 0.9 0.2 0.2 1 0 0 0 1\ns 0 0 1 1\n", "ball.nff");
  RenderScene scene({{&ball, true}});
  ArraySettings s;
  s.lenses_x = s.lenses_y = 24;
  s.pixels_per_lens = 8;
  auto camera = [&](double x) {
    Viewpoint vp;
    vp.from = {x, -6, 3};
    vp.at = {x, 0, 1};
    vp.up = {0, 0, 1};
    vp.angle_deg = 40;
    return LensArray(place_array(s, vp));
  };
  for (ReverseReuse reuse : {ReverseReuse::color, ReverseReuse::visibility}) {
    scene.set_transforms({Affine{}});
    RenderStats stats;
    const PointImage key = trace_point_image(scene, camera(0), 0, reuse, 0, stats);
    scene.set_transforms({Affine::translate({1.5, 0, 0})});
    const ReprojectedFrame rf = reverse_reproject(scene, camera(1.5), 1, &key, nullptr, ReverseOptions{reuse});
    if (reuse == ReverseReuse::color) {
      EXPECT_GT(rf.count(PixelStatus::reprojected), hits_of(key) * 95 / 100);
      EXPECT_LT(max_difference(rf.colour.data, key.colour.data), 1e-6f);
    } else {
      EXPECT_EQ(rf.count(PixelStatus::reprojected), 0u);
    }
  }
}

// The reprojected frame looks up Embree's unrefined hits and refines only
// those it shades: resolving a raw hit must give intersect()'s hit bit for
// bit, so shaded pixels stay full tracing's.
TEST(AccelRawHits, ResolvedRawHitsAreIntersectsHits) {
  const SceneDesc desc = read_nff_file(source_dir() + "/examples/primitives.nff");
  const RenderScene scene(desc);
  const LensArray cam(camera_at(desc, {}));
  size_t compared = 0;
  for (int j = 0; j < cam.height(); j += 3)
    for (int i0 = 0; i0 + kPacketSize <= cam.width(); i0 += 4 * kPacketSize) {
      PixelXY px[kPacketSize];
      for (int l = 0; l < kPacketSize; ++l) px[l] = {i0 + l, j};
      PrimaryRay primary[kPacketSize];
      bool ok[kPacketSize];
      primary_rays(cam, scene.bounds(), scene.epsilon(), px, kPacketSize, 0, primary, ok);
      RayPacket rays;
      for (int l = 0; l < kPacketSize; ++l) rays.active[l] = ok[l], rays.rays[l] = primary[l].ray;
      Hit hits[kPacketSize];
      RawHit raw[kPacketSize];
      bool found[kPacketSize], found_raw[kPacketSize];
      scene.accel().intersect(rays, hits, found);
      scene.accel().intersect_raw(rays, raw, found_raw);
      for (int l = 0; l < kPacketSize; ++l) {
        ASSERT_EQ(found[l], found_raw[l]);
        if (!found[l]) continue;
        Hit h;
        scene.accel().resolve(rays.rays[l], raw[l], h);
        EXPECT_EQ(std::memcmp(&h.t, &hits[l].t, sizeof h.t), 0);
        EXPECT_EQ(h.prim, hits[l].prim);
        EXPECT_EQ(h.group, hits[l].group);
        EXPECT_EQ(h.kind, hits[l].kind);
        EXPECT_EQ(std::memcmp(&h.ng, &hits[l].ng, sizeof h.ng), 0);
        EXPECT_EQ(std::memcmp(&h.p_object, &hits[l].p_object, sizeof h.p_object), 0);
        // The float answer is within 1e-5 of its distance of the refined one.
        EXPECT_NEAR(raw[l].t, h.t, 1e-5 * h.t);
        ++compared;
      }
    }
  EXPECT_GT(compared, 1000u);
}

// The keyframe's object ids and depths (what the same-surface tests read)
// are the objects its records hit, -1 for background, at the records' t.
TEST(ReverseReprojection, KeyframeObjectIdsAreTheObjectsItsRecordsHit) {
  const SceneDesc desc = read_nff_file(source_dir() + "/examples/primitives.nff");
  const RenderScene scene(desc);
  RenderStats stats;
  const PointImage key = trace_point_image(scene, LensArray(camera_at(desc, {})), 0, ReverseReuse::color, 0, stats);
  ASSERT_EQ(key.seen.size(), key.hits.size());
  size_t background = 0;
  for (size_t p = 0; p < key.hits.size(); ++p) {
    const PrimaryHit& h = key.hits[p];
    if (h.status != PrimaryHit::kHit) {
      EXPECT_EQ(key.seen[p].object, -1);
      ++background;
      continue;
    }
    EXPECT_EQ(key.seen[p].object, scene.object_of(h.group, static_cast<PrimKind>(h.kind), h.prim));
    EXPECT_EQ(key.seen[p].t, h.t);
  }
  EXPECT_GT(background, 0u);
  EXPECT_LT(background, key.hits.size());
}

// A hold: the keyframe's camera and nothing moved. The frame is the
// keyframe's full trace, copied without a ray; a camera moved by a hair, or
// an object moved out of sight (visibility reuse), are not holds and trace
// their eye rays.
TEST(ReverseReprojection, AHoldIsItsKeyframeExactlyAndTracesNothing) {
  const SceneDesc desc = read_nff_file(source_dir() + "/examples/primitives.nff");
  const SceneDesc far_ball = parse_nff("f 1 1 1 1 0 0 0 1\ns 100 100 100 1\n", "far.nff");
  RenderScene scene({{&desc, false}, {&far_ball, true}});
  scene.set_transforms({Affine{}, Affine{}});
  const LensArrayDesc cam = camera_at(desc, {});
  for (ReverseReuse reuse : {ReverseReuse::color, ReverseReuse::visibility}) {
    RenderStats stats;
    const PointImage key = trace_point_image(scene, LensArray(cam), 0, reuse, 0, stats);
    const ReprojectedFrame hold = reverse_reproject(scene, LensArray(cam), 1, &key, nullptr, ReverseOptions{reuse});
    EXPECT_EQ(hold.colour.data, key.colour.data);
    EXPECT_EQ(hold.object, objects_of(key));
    EXPECT_EQ(hold.rays.total(), 0u);
    // A copy of the keyframe: every pixel taken from it, the background too.
    EXPECT_EQ(hold.copied_from, 0);
    EXPECT_EQ(hold.count(PixelStatus::reprojected), hold.status.size());
    EXPECT_GT(hold.status.size(), hits_of(key));

    const ReprojectedFrame nudged =
        reverse_reproject(scene, LensArray(camera_at(desc, {1e-9, 0, 0})), 1, &key, nullptr, ReverseOptions{reuse});
    EXPECT_GT(nudged.rays.eye, 0u);
    // Colour reuse copies the elemental images no moved object can reach
    // (LockedOffShot... below): with the ball far out of sight, all of them.
    scene.set_transforms({Affine{}, Affine::translate({0, 0, 1})});
    const ReprojectedFrame moved = reverse_reproject(scene, LensArray(cam), 1, &key, nullptr, ReverseOptions{reuse});
    if (reuse == ReverseReuse::visibility) EXPECT_GT(moved.rays.eye, 0u);
    else EXPECT_EQ(moved.colour.data, key.colour.data);
    scene.set_transforms({Affine{}, Affine{}});
  }
}

// A locked-off shot with a small ball moving at one side: elemental images
// none of whose lines can reach the ball (where it is or where the keyframe
// saw it) are copied from the keyframe without a ray, and the frame equals
// the one built with every pixel through the lookups.
// Per-lens packets (32x32 lenses x 8 px) and sub-aperture packets, which
// span 16 lenses (64x64 x 4 px, where the array prefers them).
TEST(ReverseReprojection, LockedOffShotCopiesTheElementalImagesNoMovingObjectReaches) {
  const SceneDesc desc = read_nff_file(source_dir() + "/examples/primitives.nff");
  const SceneDesc ball = parse_nff("f 0.9 0.2 0.2 1 0 0 0 1\ns 0 0 0 0.15\n", "ball.nff");
  for (const auto& [lenses, ppl, style] : {std::tuple{32, 8, TraceStyle::packet}, std::tuple{64, 4, TraceStyle::subaperture}}) {
  SCOPED_TRACE(fmt::format("{} lenses x {} px", lenses, ppl));
  RenderScene scene({{&desc, false}, {&ball, true}});
  const LensArrayDesc cam = camera_at(desc, {}, lenses, ppl);
  ASSERT_EQ(preferred_style(cam), style);
  // At the array's left edge, in front of it (seen by a few lenses there).
  const Frame& f = cam.frame;
  const Vec3 left = f.to_world_point({-0.4 * cam.lenses_x * cam.pitch, 0, 1.5});
  scene.set_transforms({Affine{}, Affine::translate(left)});
  RenderStats stats;
  const PointImage key = trace_point_image(scene, LensArray(cam), 0, ReverseReuse::color, 0, stats);
  scene.set_transforms({Affine{}, Affine::translate(left + f.y * 0.2)});
  ReverseOptions copy, lookups;
  lookups.copy_unchanged = false;
  const ReprojectedFrame fast = reverse_reproject(scene, LensArray(cam), 1, &key, nullptr, copy);
  const ReprojectedFrame slow = reverse_reproject(scene, LensArray(cam), 1, &key, nullptr, lookups);
  EXPECT_LT(max_difference(fast.colour.data, slow.colour.data), 1e-6f);
  EXPECT_EQ(fast.object, slow.object);
  EXPECT_GT(fast.rays.eye, 0u);                   // the lenses that see the ball trace
  EXPECT_LT(fast.rays.eye, slow.rays.eye / 2);    // most are copied
  EXPECT_NE(fast.object, objects_of(key));            // and the ball moved in the image
  }
}

TEST(ReverseReprojection, RefusesKeyframesItCannotUse) {
  const SceneDesc desc = read_nff_file(source_dir() + "/examples/primitives.nff");
  const RenderScene scene(desc);
  const LensArray cam(camera_at(desc, {}, 8, 4));
  RenderStats stats;
  const PointImage key = trace_point_image(scene, cam, 3, ReverseReuse::color, 0, stats);
  try {
    reverse_reproject(scene, cam, 4, &key, nullptr, ReverseOptions{ReverseReuse::visibility});
    FAIL() << "a keyframe without shading records was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(),
                 "the point image of frame 3 has 0 shading records for 1024 pixels: trace it for visibility reuse");
  }
  EXPECT_THROW(reverse_reproject(scene, cam, 4, nullptr, nullptr, ReverseOptions{}), std::invalid_argument);
}

}  // namespace
}  // namespace holoray
