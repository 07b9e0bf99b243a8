// Looking Glass panels as the device's own software makes them: the view
// value, cell and view blend of every subpixel against the fragment shader
// of npm @lookingglass/webxr 0.6.0 (dist/bundle/webxr.js, function Shader),
// written out below from that shader; interlacing a quilt of flat colours
// that encode the view index reads back those views and weights; tracing
// natively agrees with interlacing where every subpixel's view is a quilt
// view; what a calibration refuses; animate and interlace on the command line.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>

#include "camera/quilt_camera.hpp"
#include "display/looking_glass.hpp"
#include "image/image_io.hpp"
#include "image/metrics.hpp"
#include "render/display_renderer.hpp"
#include "render/render_scene.hpp"
#include "render/view_renderer.hpp"
#include "scene/nff_reader.hpp"
#include "test_util.hpp"

namespace holoray {
namespace {

// One calibration's fields as the shader takes them.
struct ShaderCalibration {
  double pitch, slope, center, dpi;
  int width, height;
  bool flip_x = false;
  std::vector<std::array<double, 6>> cells;  // ROffsetX, ROffsetY, GOffsetX, GOffsetY, BOffsetX, BOffsetY (pixels)
  int pattern = 1;                           // subpixelMode (cellPatternType)

  std::string json() const {
    std::string cell_list;
    for (const auto& c : cells)
      cell_list += fmt::format(R"({}{{"ROffsetX": {}, "ROffsetY": {}, "GOffsetX": {}, "GOffsetY": {}, "BOffsetX": {}, "BOffsetY": {}}})",
                               cell_list.empty() ? "" : ", ", c[0], c[1], c[2], c[3], c[4], c[5]);
    return fmt::format(R"({{"pitch": {{"value": {:.17g}}}, "slope": {{"value": {:.17g}}}, "center": {{"value": {:.17g}}},
        "viewCone": {{"value": 40}}, "invView": {{"value": 1}}, "DPI": {{"value": {:.17g}}}, "screenW": {{"value": {}}},
        "screenH": {{"value": {}}}, "flipImageX": {{"value": {}}}, "subpixelCells": [{}], "CellPatternMode": {{"value": {}}}}})",
                       pitch, slope, center, dpi, width, height, flip_x ? 1 : 0, cell_list, pattern);
  }
};

// GetCellForPixel(screen_uv): xPos = int(u W), yPos = int(v H), v up.
int shader_cell(const ShaderCalibration& c, double u, double v) {
  const int x = static_cast<int>(u * c.width), y = static_cast<int>(v * c.height);
  int cell = 0;
  if (c.pattern == 1) cell = ((y % 2 == 0 && x % 2 == 0) || (y % 2 != 0 && x % 2 != 0)) ? 0 : 1;
  else if (c.pattern == 2) cell = x % 2;
  else if (c.pattern == 3) cell = (y + (x % 2) * 2) % 4;
  else if (c.pattern == 4) cell = y % 2;
  return cell % static_cast<int>(c.cells.size());
}

// GetSubpixelViews(v_texcoord)[s] for pixel (i, j) of the image, j from the
// top: v_texcoord is the fragment's centre, v up. The config's getters:
// tilt = H / (W slope), subp = 1 / (3 W), both negated by flipImageX;
// pitch = pitch W / DPI cos(atan(1 / slope)); cells' offsets divided by W, H.
double shader_view(const ShaderCalibration& c, int i, int j, int s) {
  const double W = c.width, H = c.height;
  const double u = (i + 0.5) / W, v = (H - 1 - j + 0.5) / H;
  const double tilt = H / (W * c.slope) * (c.flip_x ? -1 : 1);
  const double subp = 1 / (W * 3) * (c.flip_x ? -1 : 1);
  const double pitch = c.pitch * W / c.dpi * std::cos(std::atan(1 / c.slope));
  double view;
  if (c.cells.empty()) {
    view = u + subp * s + v * tilt;
  } else {
    const auto& cell = c.cells[static_cast<size_t>(shader_cell(c, u, v))];
    view = (u + cell[2 * s] / W) + (v + cell[2 * s + 1] / H) * tilt;
  }
  view = view * pitch - c.center;
  view = 1 - (view - std::floor(view));
  return std::clamp(view, 0.00001, 0.999999);
}

// A quilt of N = columns x rows views of w x h pixels, view k a flat k in
// every channel, view 0 bottom left.
ImageBuffer index_quilt(int columns, int rows, int w, int h) {
  ImageBuffer q(columns * w, rows * h, 3);
  for (int y = 0; y < q.height; ++y)
    for (int x = 0; x < q.width; ++x) {
      const int k = (rows - 1 - y / h) * columns + x / w;
      for (int ch = 0; ch < 3; ++ch) q.at(x, y)[ch] = static_cast<float>(k);
    }
  return q;
}

// Interlaces the index quilt (views the panel's size, so that each pixel
// reads its view at a texel centre) and checks every subpixel against the
// shader: OldViewFiltering mixes view int(x N) toward int((x + 1/N) N) by
// fract(x N), and reading tile N of the repeating quilt texture gives view 0.
void expect_shader_views(const ShaderCalibration& sc, int columns, int rows) {
  const LookingGlassCalibration c = parse_looking_glass(sc.json(), "lg.json");
  QuiltDesc q;
  q.columns = columns, q.rows = rows, q.view_width = sc.width, q.view_height = sc.height;
  const int n = columns * rows;
  const ImageBuffer panel = interlace_quilt(index_quilt(columns, rows, sc.width, sc.height), q, c);
  ASSERT_EQ(panel.width, sc.width);
  ASSERT_EQ(panel.height, sc.height);
  int wrapped = 0, blended = 0;
  for (int j = 0; j < sc.height; ++j)
    for (int i = 0; i < sc.width; ++i)
      for (int s = 0; s < 3; ++s) {
        const double x = shader_view(sc, i, j, s);
        ASSERT_DOUBLE_EQ(looking_glass_view(c, i, j, s), x) << i << "," << j << "," << s;
        const int left = static_cast<int>(x * n);
        int right = static_cast<int>((x + 1.0 / n) * n);
        if (right == n) right = 0, ++wrapped;
        const double w = x * n - std::floor(x * n);
        blended += w > 0.01 && w < 0.99;
        const ViewBlend b = looking_glass_blend(x, n);
        ASSERT_EQ(b.first, left);
        ASSERT_EQ(b.second, right);
        ASSERT_NEAR(b.w, w, 1e-12);
        // The read of the upper rows' tiles drifts by the shader's 0.00001
        // less a column: a few thousandths of a view index at most.
        EXPECT_NEAR(panel.at(i, j)[s], left * (1 - w) + right * w, 0.01) << i << "," << j << "," << s;
      }
  EXPECT_GT(wrapped, 0) << "no subpixel past the last view: the wrap to view 0 went unchecked";
  EXPECT_GT(blended, sc.width * sc.height) << "too few subpixels between two views";
}

TEST(LookingGlass, InterlacingReadsTheShadersViewsAndWeightsWithFlipImageX) {
  ShaderCalibration sc{47.3, -6.1, 0.37, 120, 60, 20};
  sc.flip_x = true;
  expect_shader_views(sc, 4, 3);
}

TEST(LookingGlass, InterlacingReadsTheShadersViewsAndWeightsWithSubpixelCells) {
  // Two cells in the default checkerboard, one with the stripe's offsets
  // and one shifted as a device with a BGR-ish cell would be.
  ShaderCalibration sc{52.6, 7.2, -0.2, 100, 48, 16};
  sc.cells = {{0, 0, 1.0 / 3, 0, 2.0 / 3, 0}, {2.0 / 3, 0.5, 1.0 / 3, 0.5, 0, 0.5}};
  expect_shader_views(sc, 5, 2);
  // Four cells in pattern 3: (yPos + 2 (xPos mod 2)) mod 4.
  sc.cells.push_back({0.1, -0.2, 0.4, 0.1, 0.7, -0.3});
  sc.cells.push_back({-0.3, 0.2, 0.2, 0.3, 0.5, 0.25});
  sc.pattern = 3;
  expect_shader_views(sc, 3, 3);
}

TEST(LookingGlass, CellPatternsFollowTheShader) {
  ShaderCalibration sc{50, 5, 0, 100, 8, 8};
  sc.cells.assign(4, {0, 0, 0, 0, 0, 0});
  for (int pattern = 0; pattern <= 4; ++pattern) {
    sc.pattern = pattern;
    const LookingGlassCalibration c = parse_looking_glass(sc.json(), "lg.json");
    for (int j = 0; j < 8; ++j)
      for (int i = 0; i < 8; ++i)
        ASSERT_EQ(looking_glass_cell(c, i, j), shader_cell(sc, (i + 0.5) / 8, (8 - 1 - j + 0.5) / 8))
            << "pattern " << pattern << " at " << i << "," << j;
  }
  sc.cells.clear();
  EXPECT_EQ(looking_glass_cell(parse_looking_glass(sc.json(), "lg.json"), 3, 1), 0);
}

std::string calibration_error(const std::string& json) {
  try {
    parse_looking_glass(json, "lg.json");
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "no error";
}

TEST(LookingGlass, CalibrationRefusesWhatTheShaderCannotTake) {
  const std::string base = R"("pitch": {"value": 50}, "slope": {"value": 3}, "center": {"value": 0}, "DPI": {"value": 100},
                              "screenW": {"value": 48}, "screenH": {"value": 8})";
  EXPECT_EQ(calibration_error(R"({"pitch": {"value": 50}})"), "lg.json: expected the field 'slope' ({\"value\": number}), found none");
  EXPECT_EQ(calibration_error(R"({"pitch": {"value": -1}, "slope": {"value": 3}, "center": {"value": 0}, "DPI": {"value": 100},
                                  "screenW": {"value": 48}, "screenH": {"value": 8}})"),
            "lg.json: expected a positive 'pitch' (lenticules per inch), found -1");
  EXPECT_EQ(calibration_error("{" + base + R"(, "subpixelCells": {"ROffsetX": 0}})"),
            "lg.json: expected 'subpixelCells' to be an array of cells, found {\"ROffsetX\":0}");
  EXPECT_EQ(calibration_error("{" + base + R"(, "subpixelCells": [{"ROffsetX": 0, "ROffsetY": 0, "GOffsetX": 0}]})"),
            "lg.json (subpixelCells[0]): expected the field 'GOffsetY' ({\"value\": number}), found none");
  std::string eleven;
  for (int k = 0; k < 11; ++k)
    eleven += std::string(k ? ", " : "") +
              R"({"ROffsetX": 0, "ROffsetY": 0, "GOffsetX": 0, "GOffsetY": 0, "BOffsetX": 0, "BOffsetY": 0})";
  EXPECT_EQ(calibration_error("{" + base + ", \"subpixelCells\": [" + eleven + "]}"),
            "lg.json: expected at most 10 'subpixelCells' (the device shader holds 60 floats), found 11");
  EXPECT_EQ(calibration_error("{" + base + R"(, "CellPatternMode": {"value": 5}})"),
            "lg.json: expected 'CellPatternMode' to be 0, 1, 2, 3 or 4, found 5");
}

SceneDesc small_scene() {
  return parse_nff(test::kSmallViewpointScene, "s.nff");
}

// 48 x 8 pixels, 12 lenticules across (4 pixels, 12 subpixels each), slope
// 3 (a row moves the phase by a twelfth too), center 1/24: every view value
// is an odd multiple of 1/24, so x N is a whole number for N = 24 views.
ShaderCalibration twenty_fourths() {
  return ShaderCalibration{12 / ((48 / 100.0) * std::cos(std::atan(1.0 / 3))), 3, 1.0 / 24, 100, 48, 8};
}

// Where x N = k for every subpixel, the native panel traced as the
// continuous version of an N-view quilt is the interlaced N-view quilt;
// a quilt of another N is not.
TEST(LookingGlass, TracingNativelyAgreesWithInterlacingAQuiltWhereViewsCoincide) {
  const SceneDesc desc = small_scene();
  const RenderScene scene(desc);
  const ShaderCalibration sc = twenty_fourths();
  const LookingGlassCalibration c = parse_looking_glass(sc.json(), "lg.json");
  for (int j = 0; j < 8; ++j)
    for (int i = 0; i < 48; ++i)
      for (int s = 0; s < 3; ++s) {
        const double k = shader_view(sc, i, j, s) * 24;
        ASSERT_NEAR(k, std::round(k), 1e-6);
      }
  const PinholeDesc centre = view_of(*desc.viewpoint, 48, 8);
  RenderOptions ro;
  RenderStats stats;
  const FrameBuffers native = render_looking_glass(scene, LookingGlassCamera(c, centre, 24), ro, stats);
  QuiltDesc q;
  q.columns = 6, q.rows = 4, q.view_width = 48, q.view_height = 8, q.view_cone_deg = 40;
  const ImageBuffer interlaced = interlace_quilt(render_quilt(scene, QuiltCamera(q, centre), ro, stats).colour, q, c);
  ASSERT_EQ(native.colour.width, 48);
  const double psnr = compare_images(native.colour, interlaced).psnr_all();
  EXPECT_GT(psnr, 60);
  QuiltDesc q8 = q;
  q8.columns = 4, q8.rows = 2;
  const ImageBuffer coarse = interlace_quilt(render_quilt(scene, QuiltCamera(q8, centre), ro, stats).colour, q8, c);
  EXPECT_LT(compare_images(native.colour, coarse).psnr_all(), psnr - 10);
  EXPECT_THROW(LookingGlassCamera(c, centre, 0), std::invalid_argument);
}

// animate --looking-glass: each frame is render --looking-glass of the
// frame's viewpoint (here the scene's own), bit for bit; interlace -q is quiet.
TEST(LookingGlass, AnimatedNativeFramesAreRenderLookingGlassAndInterlaceTakesQ) {
  test::TempDir dir;
  test::write_text(dir.file("s.nff"), "v\nfrom 0 -8 3\nat 0 0 0\nup 0 0 1\nangle 40\nhither 1\nresolution 64 64\n"
                                      "l 4 -5 8\nf 0.9 0.3 0.2 1 0 0 0 0\ns 0 0 0 1\n");
  ShaderCalibration sc{52.6, -7.2, 0.55, 100, 30, 20};
  test::write_text(dir.file("lg.json"), sc.json());
  test::write_text(dir.file("shot.toml"), "frames = 2\n[[object]]\nscene = \"s.nff\"\n");
  const auto still = test::run_cli("render " + dir.file("s.nff") + " --looking-glass " + dir.file("lg.json") +
                                   " --views 12 -o " + dir.file("still.exr") + " -q");
  ASSERT_EQ(still.status, 0) << still.output;
  const auto anim = test::run_cli("animate " + dir.file("shot.toml") + " --looking-glass " + dir.file("lg.json") +
                                  " --views 12 --format exr -o " + dir.file("frames") + " -q");
  ASSERT_EQ(anim.status, 0) << anim.output;
  EXPECT_EQ(anim.output, "");
  const ImageBuffer a = read_image(dir.file("still.exr"));
  for (const char* f : {"frames/frame_0000.exr", "frames/frame_0001.exr"}) {
    const ImageBuffer b = read_image(dir.file(f));
    ASSERT_EQ(b.width, 30);
    EXPECT_TRUE(std::equal(a.data.begin(), a.data.end(), b.data.begin(), b.data.end())) << f;
  }
  const auto other = test::run_cli("render " + dir.file("s.nff") + " --looking-glass " + dir.file("lg.json") +
                                   " -o " + dir.file("other.exr") + " -q");
  ASSERT_EQ(other.status, 0) << other.output;
  EXPECT_NE(read_image(dir.file("other.exr")).data, a.data) << "--views changed nothing";
  const auto views_alone = test::run_cli("render " + dir.file("s.nff") + " --views 12 -o " + dir.file("x.png"));
  EXPECT_NE(views_alone.status, 0);
  EXPECT_NE(views_alone.output.find("--views requires --looking-glass"), std::string::npos) << views_alone.output;
  const auto reuse = test::run_cli("animate " + dir.file("shot.toml") + " --looking-glass " + dir.file("lg.json") +
                                   " --method reverse -o " + dir.file("f2"));
  EXPECT_NE(reuse.status, 0);
  EXPECT_NE(reuse.output.find("--looking-glass: goes with --method full"), std::string::npos) << reuse.output;

  const auto quilt = test::run_cli("render " + dir.file("s.nff") + " --quilt 3x2 --resolution 30x20 -o " + dir.file("q.png") + " -q");
  ASSERT_EQ(quilt.status, 0) << quilt.output;
  const auto quiet = test::run_cli("interlace " + dir.file("q_qs3x2a1.5.png") + " --looking-glass " + dir.file("lg.json") +
                                   " -o " + dir.file("panel.png") + " -q");
  ASSERT_EQ(quiet.status, 0) << quiet.output;
  EXPECT_EQ(quiet.output, "");
  const auto loud = test::run_cli("interlace " + dir.file("q_qs3x2a1.5.png") + " --looking-glass " + dir.file("lg.json") +
                                  " -o " + dir.file("panel.png"));
  ASSERT_EQ(loud.status, 0) << loud.output;
  EXPECT_NE(loud.output.find("from a 3x2 quilt of 30x20 views"), std::string::npos) << loud.output;
}

}  // namespace
}  // namespace holoray
