// `holoray live` (issue 56) under Xvfb on the GPU path's device (lavapipe
// where there is no GPU): the frame shown (an EIA, a pinhole view, a
// display's or a Looking Glass's panel) is `holoray render --device gpu`'s
// PNG byte for byte, a replayed orbit and focus change shows what render
// gives from the moved viewpoint and plane, --record keeps every frame, and
// each fault ends with its message and status.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <regex>
#include <sstream>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include "holoray/errors.hpp"
#include "image/image_io.hpp"
#include "image/metrics.hpp"
#include "live/event_script.hpp"
#include "live/shown_codes.hpp"
#include "live/view_controls.hpp"
#include "test_util.hpp"

using namespace holoray;
using namespace holoray::test;

namespace {

const std::string kScene = source_dir() + "/examples/primitives.nff";
const std::string kArray = " --lenses 24x24 --pixels-per-lens 6";

bool have_xvfb() { return run_shell("command -v Xvfb").status == 0; }

// One Xvfb for this test process, on a display number Xvfb itself found
// free (-displayfd: no race between test processes running side by side,
// as two `xvfb-run -a` have), stopped when the process ends.
class Xvfb {
 public:
  static const std::string& display() {
    static Xvfb x;
    return x.name_;
  }
  ~Xvfb() {
    if (pid_ > 0) ::kill(pid_, SIGTERM), ::waitpid(pid_, nullptr, 0);
  }

 private:
  Xvfb() {
    int fds[2];
    if (::pipe(fds) != 0) return;
    pid_ = ::fork();
    if (pid_ == 0) {
      ::close(fds[0]);
      const int null = ::open("/dev/null", O_WRONLY);
      ::dup2(null, 1), ::dup2(null, 2);
      const std::string fd = std::to_string(fds[1]);
      ::execlp("Xvfb", "Xvfb", "-displayfd", fd.c_str(), "-screen", "0", "1280x1024x24", "-nolisten", "tcp",
               static_cast<char*>(nullptr));
      ::_exit(127);
    }
    ::close(fds[1]);
    std::string number;
    char c;
    while (::read(fds[0], &c, 1) == 1 && c != '\n') number += c;
    ::close(fds[0]);
    if (!number.empty()) name_ = ":" + number;
  }
  pid_t pid_ = -1;
  std::string name_;
};

// `command` with the test process's Xvfb as its display.
CommandResult with_xvfb(const std::string& command, const std::string& env = "") {
  return run_shell(env + " DISPLAY=" + Xvfb::display() + " " + command);
}

// `holoray ARGS` on the test process's Xvfb.
CommandResult on_xvfb(const std::string& args, const std::string& env = "") {
  return with_xvfb(std::string(HOLORAY_CLI) + " " + args, env);
}

#define NEED_XVFB() \
  if (!have_xvfb()) GTEST_SKIP() << "Xvfb is not installed (setup.sh installs xvfb)"

// The numbers of "eye X,Y,Z at X,Y,Z up X,Y,Z fov F [focus D] [lens-fov L]".
std::map<std::string, std::vector<double>> view_of(const std::string& output) {
  std::map<std::string, std::vector<double>> v;
  const auto at = output.find("view       ");
  if (at == std::string::npos) return v;
  std::istringstream in(output.substr(at + 11, output.find('\n', at) - at - 11));
  std::string key, value;
  while (in >> key >> value) {
    std::vector<double>& numbers = v[key];
    std::istringstream parts(value);
    for (std::string n; std::getline(parts, n, ',');) numbers.push_back(std::stod(n));
  }
  return v;
}

// The example scene with its eye, point looked at and up replaced.
std::string scene_from(const TempDir& dir, const std::map<std::string, std::vector<double>>& v) {
  std::string text = read_bytes(kScene);
  auto line = [&](const char* key, const std::vector<double>& p) {
    text = std::regex_replace(text, std::regex(std::string("\n") + key + " [^\n]*"),
                              fmt::format("\n{} {:.17g} {:.17g} {:.17g}", key, p[0], p[1], p[2]));
  };
  line("from", v.at("eye")), line("at", v.at("at")), line("up", v.at("up"));
  write_text(dir.file("moved.nff"), text);
  return dir.file("moved.nff");
}

}  // namespace

// ---- the parts, without a window ----

TEST(Live, ShownCodesAreRendersCodes) {
  for (const Encoding e : {Encoding::linear, Encoding::srgb}) {
    const gpu::CodeThresholds t = live::code_thresholds(e);
    for (int k = 1; k <= 255; ++k) {
      const float at = t[size_t(k - 1)], below = std::nextafter(at, -1.0f);
      EXPECT_EQ(encode_8bit(at, e), k) << k;
      EXPECT_EQ(encode_8bit(below, e), k - 1) << k;
    }
    // And back: the image of the codes encodes to the codes.
    std::vector<uint8_t> rgb(256 * 3);
    for (int k = 0; k < 256 * 3; ++k) rgb[size_t(k)] = uint8_t(k / 3);
    const ImageBuffer image = live::image_of_codes(rgb, 256, 1, t);
    for (size_t k = 0; k < rgb.size(); ++k) ASSERT_EQ(encode_8bit(image.data[k], e), rgb[k]) << k;
  }
}

TEST(Live, OrbitTurnsAboutThePointLookedAtKeepingItsDistance) {
  live::LiveView v;
  v.viewpoint.from = {0, -10, 0}, v.viewpoint.at = {0, 0, 0}, v.viewpoint.up = {0, 0, 1}, v.viewpoint.angle_deg = 40;
  live::orbit(v, 100, 0, 400, 300);  // a quarter of the width: 45 degrees, the eye to the left
  EXPECT_NEAR(v.viewpoint.from.x, -10 * std::sin(std::numbers::pi / 4), 1e-12);
  EXPECT_NEAR(v.viewpoint.from.y, -10 * std::cos(std::numbers::pi / 4), 1e-12);
  EXPECT_NEAR(v.viewpoint.from.z, 0, 1e-12);
  live::orbit(v, 0, 150, 400, 300);  // half the height: 45 degrees up
  EXPECT_NEAR(length(v.viewpoint.from), 10, 1e-12);
  EXPECT_NEAR(v.viewpoint.from.z, 10 * std::sin(std::numbers::pi / 4), 1e-12);
  live::orbit(v, 0, 1e6, 400, 300);  // never over the pole
  EXPECT_NEAR(std::asin(v.viewpoint.from.z / 10) * 180 / std::numbers::pi, 89, 1e-9);
  live::dolly(v, 1);
  EXPECT_NEAR(length(v.viewpoint.from), 9, 1e-12);
  EXPECT_FALSE(v.focus_distance.has_value());  // still |eye - at|, as render's default
  live::move_plane(v, 1);
  EXPECT_NEAR(*v.focus_distance, 9 * 1.05, 1e-12);
}

TEST(Live, EventScriptErrorsSayWhereAndWhat) {
  TempDir dir;
  auto error_of_script = [&](const std::string& text) -> std::string {
    write_text(dir.file("e.txt"), text);
    try {
      live::read_event_script(dir.file("e.txt"));
    } catch (const api::SceneError& e) {
      return fmt::format("{}:{}: {}", e.line(), e.column(), e.message());
    }
    return "";
  };
  EXPECT_EQ(error_of_script("1 orbit 3 4\n2 jump 1\n"), "2:3: expected an event: orbit, pan, pointer, wheel or key, found 'jump'");
  EXPECT_EQ(error_of_script("0 wheel 1\n"), "1:1: expected a frame number (1 or more), found '0'");
  EXPECT_EQ(error_of_script("3 wheel 1\n2 wheel 1\n"), "2:1: expected a frame number of 3 or more (frames ascend), found '2'");
  EXPECT_EQ(error_of_script("1 pan 3\n"), "1:8: expected DY, pixels, found the line's end");
  EXPECT_EQ(error_of_script("1 key F1\n"),
            "1:7: expected a key: Up, Down, Left, Right, A, V, S, shift+S, Space, PageDown, PageUp, Home, Escape, Q, found "
            "'F1'");
  EXPECT_EQ(error_of_script("1 wheel 1 2 # comment\n"), "1:11: expected the line's end, found '2'");
  const std::vector<live::ScriptedEvent> ok = live::read_event_script((write_text(dir.file("ok.txt"), "# a comment\n\n2 key S\n"), dir.file("ok.txt")));
  ASSERT_EQ(ok.size(), 1u);
  EXPECT_EQ(ok[0].frame, 2);
  EXPECT_EQ(ok[0].event.key, "S");
}

// ---- offscreen: no display at all ----

// Offscreen (the GPU machines have no display): no window, each frame
// traced, packed and copied on the device as a shown one is. With neither
// DISPLAY nor WAYLAND_DISPLAY set, the frame shown is the GPU render, byte
// for byte, for a lens array and a display panel; replayed input moves the
// view as it does in a window (the same screenshot as under Xvfb, below);
// without --exit-after it is refused, there being no window to close.
TEST(Live, OffscreenTheFrameShownIsTheGpuRenderByteForByte) {
  TempDir dir;
  write_text(dir.file("d.toml"), "[panel]\nresolution = [120, 80]\npixel_pitch_mm = 0.1\nsubpixels = \"bgr\"\n"
                                 "[lens]\ngrid = \"lenticular\"\npitch_mm = 0.4317\nslant_deg = 9.46\nfocal_length_mm = 1.2\n");
  const std::string headless = "env -u DISPLAY -u WAYLAND_DISPLAY ";
  for (const std::string& camera : {kArray, " --display " + dir.file("d.toml")}) {
    const CommandResult live = run_shell(headless + std::string(HOLORAY_CLI) + " live " + kScene + camera +
                                         " --offscreen --exit-after 3 --screenshot " + dir.file("shown.png"));
    ASSERT_EQ(live.status, 0) << camera << "\n" << live.output;
    EXPECT_NE(live.output.find("frames     3 shown"), std::string::npos) << live.output;
    EXPECT_NE(live.output.find(" fps)"), std::string::npos) << live.output;
    const CommandResult render = run_cli("render " + kScene + camera + " --device gpu -q -o " + dir.file("render.png"));
    ASSERT_EQ(render.status, 0) << render.output;
    EXPECT_TRUE(read_bytes(dir.file("shown.png")) == read_bytes(dir.file("render.png"))) << camera;
  }
  const CommandResult forever = run_shell(headless + std::string(HOLORAY_CLI) + " live " + kScene + " --offscreen");
  EXPECT_EQ(forever.status, 2) << forever.output;  // a usage error
  EXPECT_NE(forever.output.find("--offscreen requires --exit-after"), std::string::npos) << forever.output;
  if (!have_xvfb()) return;
  write_text(dir.file("events.txt"), "1 orbit 36 0\n1 orbit 0 -10\n2 wheel 1\n2 key Up\n3 key Right\n");
  const std::string moved = "live " + kScene + kArray + " --exit-after 4 --events " + dir.file("events.txt") + " --screenshot ";
  ASSERT_EQ(run_shell(headless + std::string(HOLORAY_CLI) + " " + moved + dir.file("offscreen.png") + " --offscreen").status, 0);
  ASSERT_EQ(on_xvfb(moved + dir.file("window.png") + " --windowed").status, 0);
  EXPECT_TRUE(read_bytes(dir.file("offscreen.png")) == read_bytes(dir.file("window.png")));
}

// ---- the window, under Xvfb ----

TEST(Live, TheFrameShownIsTheGpuRenderByteForByte) {
  NEED_XVFB();
  TempDir dir;
  // A small slanted-lenticular panel over BGR subpixels, and a Looking
  // Glass calibration shrunk to 96x128 (as tests/test_gpu_path.cpp does).
  write_text(dir.file("d.toml"), "[panel]\nresolution = [120, 80]\npixel_pitch_mm = 0.1\nsubpixels = \"bgr\"\n"
                                 "[lens]\ngrid = \"lenticular\"\npitch_mm = 0.4317\nslant_deg = 9.46\nfocal_length_mm = 1.2\n");
  std::string glass = read_bytes(source_dir() + "/examples/displays/looking_glass_example_calibration.json");
  for (const auto& [from, to] : {std::pair<std::string, std::string>{"\"screenW\": {\"value\": 1536.0}", "\"screenW\": {\"value\": 96.0}"},
                                 {"\"screenH\": {\"value\": 2048.0}", "\"screenH\": {\"value\": 128.0}"},
                                 {"\"DPI\": {\"value\": 324.0}", "\"DPI\": {\"value\": 20.25}"}})
    glass.replace(glass.find(from), from.size(), to);
  write_text(dir.file("lg.json"), glass);
  const struct {
    const char* what;
    std::string camera;
  } cases[] = {{"lens array", kArray},
               {"hex lens array", kArray + " --grid hex"},
               {"pinhole, sRGB", " --camera pinhole --resolution 96x64 --encoding srgb"},
               {"display panel, BGR subpixels", " --display " + dir.file("d.toml")},
               {"Looking Glass panel", " --looking-glass " + dir.file("lg.json")}};
  for (const auto& c : cases) {
    const CommandResult live = on_xvfb("live " + kScene + c.camera + " --windowed --exit-after 2 --screenshot " + dir.file("shown.png"));
    ASSERT_EQ(live.status, 0) << c.what << "\n" << live.output;
    EXPECT_NE(live.output.find("wrote      " + dir.file("shown.png")), std::string::npos) << live.output;
    EXPECT_NE(live.output.find("frames     2 shown"), std::string::npos) << live.output;
    const CommandResult render = run_cli("render " + kScene + c.camera + " --device gpu -q -o " + dir.file("render.png"));
    ASSERT_EQ(render.status, 0) << render.output;
    EXPECT_TRUE(read_bytes(dir.file("shown.png")) == read_bytes(dir.file("render.png"))) << c.what;
  }
}

// Path traced live: each frame of a still view adds --spp samples to the
// last (the samples after its own, as a render of more samples draws them),
// so the view after 4 frames is a 16-sample render's to float rounding (the
// mean kept between frames is its sum rounded again); the first frame
// alone is the 4-sample render's, and past --max-spp the view is kept.
TEST(Live, APathTracedViewRefinesToTheRenderOfAllItsSamples) {
  NEED_XVFB();
  TempDir dir;
  const std::string light = " --camera pinhole --resolution 48x48 --integrator path --lights " + source_dir() +
                            "/examples/lights/cornell_box.toml";
  const std::string scene = source_dir() + "/examples/lights/cornell_box.nff";
  for (const int frames : {1, 4, 6}) {
    const CommandResult live = on_xvfb("live " + scene + light + " --spp 4 --max-spp 16 --windowed --exit-after " +
                                       std::to_string(frames) + " --screenshot " + dir.file("shown.exr"));
    ASSERT_EQ(live.status, 0) << live.output;
    const int samples = std::min(4 * frames, 16);
    const CommandResult render = run_cli("render " + scene + light + " --spp " + std::to_string(samples) +
                                         " --device gpu -q -o " + dir.file("render.exr"));
    ASSERT_EQ(render.status, 0) << render.output;
    const ImageBuffer shown = read_image(dir.file("shown.exr")), rendered = read_image(dir.file("render.exr"));
    const double psnr = compare_images(shown, rendered).psnr_all();
    if (frames == 1) EXPECT_TRUE(std::isinf(psnr)) << "one frame: the 4-sample render itself, " << psnr << " dB";
    else EXPECT_GE(psnr, 60) << frames << " frames";
    if (frames == 4) {  // and not the 4-sample image any more
      run_cli("render " + scene + light + " --spp 4 --device gpu -q -o " + dir.file("four.exr"));
      EXPECT_LT(compare_images(shown, read_image(dir.file("four.exr"))).psnr_all(), 45);
    }
  }
  const CommandResult shot = on_xvfb("live --shot " + source_dir() + "/examples/shots/sliding_primitives.toml --integrator path");
  EXPECT_EQ(shot.status, 1);
  EXPECT_NE(shot.output.find("--integrator path: live path traces a still scene; a shot path traces with "
                             "`holoray animate --integrator path`"),
            std::string::npos)
      << shot.output;
}

TEST(Live, AReplayedOrbitAndFocusChangeShowTheRenderFromTheMovedViewpointAndPlane) {
  NEED_XVFB();
  TempDir dir;
  // 36 px of the 144-px-wide window: the eye turns 45 degrees about `at`;
  // then up a little, a wheel click nearer, the plane farther, wider lenses.
  write_text(dir.file("events.txt"), "1 orbit 36 0\n1 orbit 0 -10\n2 wheel 1\n2 key Up\n3 key Right\n");
  const CommandResult live = on_xvfb("live " + kScene + kArray + " --exit-after 4 --events " + dir.file("events.txt") +
                                     " --screenshot " + dir.file("shown.png") + " --record " + dir.file("frames"));
  ASSERT_EQ(live.status, 0) << live.output;
  const auto v = view_of(live.output);
  ASSERT_EQ(v.count("eye") + v.count("focus") + v.count("lens-fov"), 3u) << live.output;
  // Where the eye went, independently: the file's eye (0,-10,5.5) about at
  // (0,0,1.2) turned 45 degrees about z, raised, then 0.9 as far.
  const double horizontal = std::hypot(v.at("eye")[0], v.at("eye")[1]);
  EXPECT_NEAR(std::atan2(v.at("eye")[0], -v.at("eye")[1]) * 180 / std::numbers::pi, -45, 1e-9);
  const double distance = std::hypot(10.0, 4.3);
  EXPECT_NEAR(std::hypot(horizontal, v.at("eye")[2] - 1.2), 0.9 * distance, 1e-9);
  EXPECT_NEAR(v.at("focus")[0], 0.9 * distance * 1.05, 1e-9);
  EXPECT_EQ(v.at("lens-fov")[0], 21);
  // render from there: the same bytes.
  const CommandResult render = run_cli("render " + scene_from(dir, v) + kArray + fmt::format(" --focus-distance {:.17g} --fov-lens 21", v.at("focus")[0]) +
                                       " --device gpu -q -o " + dir.file("render.png"));
  ASSERT_EQ(render.status, 0) << render.output;
  EXPECT_TRUE(read_bytes(dir.file("shown.png")) == read_bytes(dir.file("render.png")));
  // --record: every frame shown, the last the screenshot; the first is the file's view.
  EXPECT_EQ(frame_count(dir.file("frames")), 4u);
  EXPECT_TRUE(read_bytes(dir.file("frames/frame_0003.png")) == read_bytes(dir.file("shown.png")));
  ASSERT_EQ(run_cli("render " + kScene + kArray + " --device gpu -q -o " + dir.file("start.png")).status, 0);
  EXPECT_TRUE(read_bytes(dir.file("frames/frame_0000.png")) == read_bytes(dir.file("start.png")));
  EXPECT_TRUE(read_bytes(dir.file("frames/frame_0001.png")) != read_bytes(dir.file("start.png")));
}

// A shot stepped to its frame 3 (PageDown three times) shows what
// `holoray animate --device gpu` writes for that frame; playing, it moves.
TEST(Live, AShotSteppedToAFrameShowsAnimatesFrame) {
  NEED_XVFB();
  TempDir dir;
  write_text(dir.file("s.nff"), read_bytes(kScene));
  write_text(dir.file("shot.toml"), "frames = 6\nfps = 24\n[array]\nlenses = [20, 20]\npixels_per_lens = 6\n"
                                    "[[object]]\nscene = \"s.nff\"\n"
                                    "[[object.key]]\nframe = 0\ntranslate = [0, 0, 0]\n"
                                    "[[object.key]]\nframe = 5\ntranslate = [0.5, 0.2, 0]\nrotate = [0, 20, 0]\n");
  write_text(dir.file("events.txt"), "1 key PageDown\n2 key PageDown\n3 key PageDown\n");
  const CommandResult live = on_xvfb("live --shot " + dir.file("shot.toml") + " --events " + dir.file("events.txt") +
                                     " --exit-after 4 --screenshot " + dir.file("shown.png"));
  ASSERT_EQ(live.status, 0) << live.output;
  EXPECT_NE(live.output.find("shot       frame 3\n"), std::string::npos) << live.output;
  const CommandResult animate =
      run_cli("animate " + dir.file("shot.toml") + " --device gpu --frames 3 -q -o " + dir.file("frames"));
  ASSERT_EQ(animate.status, 0) << animate.output;
  EXPECT_TRUE(read_bytes(dir.file("shown.png")) == read_bytes(dir.file("frames/frame_0003.png")));
  // Playing from the start: frames advance with the clock (at least one
  // frame differs from the first), and it loops rather than ending.
  const auto start = std::chrono::steady_clock::now();
  const CommandResult played = on_xvfb("live --shot " + dir.file("shot.toml") + " --play --exit-after 6 --record " + dir.file("played"));
  const double run_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_EQ(played.status, 0) << played.output;
  // Where a frame's time went: each part timed once, so the six frames'
  // parts add up to less than the whole run (the window, the device and the
  // kernels' compile besides); a playing shot is laid out again as it moves.
  std::smatch split;
  ASSERT_TRUE(std::regex_search(played.output, split,
                                std::regex("a frame    layout ([0-9.]+) ms, trace ([0-9.]+) ms, show ([0-9.]+) ms \\(means\\)\n")))
      << played.output;
  const double layout_ms = std::stod(split[1]), trace_ms = std::stod(split[2]), show_ms = std::stod(split[3]);
  EXPECT_GE(layout_ms, 0) << played.output;
  EXPECT_GT(trace_ms, 0) << played.output;
  EXPECT_GT(show_ms, 0) << played.output;
  EXPECT_LT(6 * (layout_ms + trace_ms + show_ms) / 1e3, run_seconds) << played.output;
  const auto frames = folder_bytes(dir.file("played"));
  ASSERT_EQ(frames.size(), 6u);
  bool moved = false;
  for (const auto& [name, bytes] : frames) moved |= bytes != frames.begin()->second;
  // Past 2/24 s from the first frame to the last, the clock moved the shot on.
  const auto shown = played.output.find(" shown in ");
  ASSERT_NE(shown, std::string::npos) << played.output;
  if (std::stod(played.output.substr(shown + 10)) > 2.0 / 24) EXPECT_TRUE(moved) << played.output;
  const CommandResult lens = on_xvfb("live --shot " + dir.file("shot.toml") + " --lenses 8x8");
  EXPECT_EQ(lens.status, 2) << lens.output;
}

// --simulate: what an eye where the pointer is sees through the display,
// exactly as `holoray simulate` computes it from render's float panel image.
TEST(Live, SimulateShowsWhatHoloraySimulateComputesFromThePointersEye) {
  NEED_XVFB();
  TempDir dir;
  write_text(dir.file("d.toml"), "[panel]\nresolution = [120, 80]\npixel_pitch_mm = 0.1\nsubpixels = \"rgb\"\n"
                                 "[lens]\ngrid = \"lenticular\"\npitch_mm = 0.4317\nslant_deg = 9.46\nfocal_length_mm = 1.2\n");
  write_text(dir.file("events.txt"), "1 pointer 90 20\n2 wheel 2\n");
  const std::string display = " --display " + dir.file("d.toml");
  const CommandResult live = on_xvfb("live " + kScene + display + " --simulate --events " + dir.file("events.txt") +
                                     " --exit-after 3 --screenshot " + dir.file("shown.png"));
  ASSERT_EQ(live.status, 0) << live.output;
  // The eye, independently: the pointer 3/4 across the 120x80 window and
  // 1/4 down puts it 3 mm right and 2 mm up of the 12x8 mm panel's centre;
  // two wheel clicks take 600 mm to 0.81 of it.
  const auto at = live.output.find("simulate   eye ");
  ASSERT_NE(at, std::string::npos) << live.output;
  std::istringstream in(live.output.substr(at + 15));
  double x = 0, y = 0, z = 0;
  char comma;
  std::string mm, px;
  int width = 0;
  in >> x >> comma >> y >> comma >> z >> mm >> width;
  EXPECT_NEAR(x, 3, 1e-12);
  EXPECT_NEAR(y, 2, 1e-12);
  EXPECT_NEAR(z, 486, 1e-9);
  EXPECT_EQ(width, 120);
  ASSERT_EQ(run_cli("render " + kScene + display + " --device gpu -q -o " + dir.file("panel.exr")).status, 0);
  const std::string eye = live.output.substr(at + 15, live.output.find(' ', at + 15) - at - 15);
  const CommandResult simulate = run_cli("simulate " + dir.file("panel.exr") + display + " --eye " + eye + " --width 120 -o " + dir.file("simulated.png"));
  ASSERT_EQ(simulate.status, 0) << simulate.output;
  EXPECT_TRUE(read_bytes(dir.file("shown.png")) == read_bytes(dir.file("simulated.png")));
  const CommandResult lens_array = on_xvfb("live " + kScene + " --simulate");
  EXPECT_EQ(lens_array.status, 2) << lens_array.output;  // --simulate needs --display
}

TEST(Live, FaultsEndWithTheirMessages) {
  NEED_XVFB();
  const CommandResult no_display = run_shell("env -u DISPLAY -u WAYLAND_DISPLAY " + std::string(HOLORAY_CLI) + " live " + kScene);
  EXPECT_EQ(no_display.status, 1);
  EXPECT_EQ(no_display.output,
            "holoray: error: holoray live needs a display, and neither DISPLAY nor WAYLAND_DISPLAY is set: run it on a "
            "desktop, under xvfb-run, or offscreen (--offscreen)\n");
  const CommandResult no_device = on_xvfb("live " + kScene, "VK_ICD_FILENAMES=/nonexistent.json");
  EXPECT_EQ(no_device.status, 1);
  EXPECT_EQ(no_device.output.rfind("holoray: error: the Vulkan loader found no driver", 0), 0u) << no_device.output;
  const CommandResult monitor = on_xvfb("live " + kScene + " --monitor projector");
  EXPECT_EQ(monitor.status, 1);
  EXPECT_EQ(monitor.output, "holoray: error: --monitor projector: no such monitor; this display has 0 'screen' 1280x1024\n");
  const CommandResult cpu = on_xvfb("live " + kScene + " --device cpu");
  EXPECT_EQ(cpu.status, 1);
  EXPECT_EQ(cpu.output, "holoray: error: --device: holoray live renders on the GPU path: gpu or gpu:N\n");
}

// The window closed by the user while frames render back to back (as a
// window manager's close button asks): exit 0, every frame complete.
TEST(Live, ClosingTheWindowMidRenderExitsCleanly) {
  NEED_XVFB();
  TempDir dir;
  write_text(dir.file("run.sh"),
             fmt::format("{} live {}{} --exit-after 1000000 --record {} > {} 2>&1 &\n"
                         "pid=$!\n"
                         "/usr/bin/python3 {}/scripts/xwindow.py close 'holoray live' 60 || {{ kill $pid; exit 3; }}\n"
                         "wait $pid\n",
                         HOLORAY_CLI, kScene, kArray, dir.file("frames"), dir.file("log"), source_dir()));
  const CommandResult r = with_xvfb("sh " + dir.file("run.sh"));
  EXPECT_EQ(r.status, 0) << r.output << read_bytes(dir.file("log"));
  const std::string log = read_bytes(dir.file("log"));
  EXPECT_NE(log.find("frames     "), std::string::npos) << log;
  // Every frame written is whole (written under a temporary name, renamed).
  for (const auto& [name, bytes] : folder_bytes(dir.file("frames"))) EXPECT_TRUE(name.ends_with(".png")) << name;
}

// Ctrl-C (SIGINT) ends the run between frames, rendering or idle: status 130.
TEST(Live, AnInterruptEndsTheRunWith130) {
  NEED_XVFB();
  TempDir dir;
  for (const char* exit_after : {" --exit-after 1000000", ""}) {
    write_text(dir.file("run.sh"), fmt::format("{} live {}{}{} -q &\npid=$!\n"
                                               "/usr/bin/python3 {}/scripts/xwindow.py wait 'holoray live:' 60 > /dev/null\n"
                                               "kill -INT $pid\nwait $pid\n",
                                               HOLORAY_CLI, kScene, kArray, exit_after, source_dir()));
    const CommandResult r = with_xvfb("sh " + dir.file("run.sh"));
    EXPECT_EQ(r.status, 130) << (*exit_after ? "rendering" : "idle") << "\n" << r.output;
  }
}
