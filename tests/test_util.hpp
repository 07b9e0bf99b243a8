// Helpers shared by the tests: paths, running the CLI, small scenes.
#pragma once

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <fstream>
#include <iterator>
#include <map>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include "camera/lens_array.hpp"
#include "camera/placement.hpp"
#include "image/image_io.hpp"
#include "render/renderer.hpp"
#include "scene/scene_desc.hpp"

namespace holoray::test {

inline std::string shared_dir() { return HOLORAY_SHARED_DIR; }
inline std::string source_dir() { return HOLORAY_SOURCE_DIR; }

/// Standard base64 (RFC 4648, padded) of `b`: glTF data URIs.
inline std::string base64(const std::vector<uint8_t>& b) {
  static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < b.size(); i += 3) {
    const uint32_t v = uint32_t{b[i]} << 16 | (i + 1 < b.size() ? uint32_t{b[i + 1]} << 8 : 0) |
                       (i + 2 < b.size() ? uint32_t{b[i + 2]} : 0);
    out += k[v >> 18 & 63];
    out += k[v >> 12 & 63];
    out += i + 1 < b.size() ? k[v >> 6 & 63] : '=';
    out += i + 2 < b.size() ? k[v & 63] : '=';
  }
  return out;
}
/// A width x height RGB image whose channel c of texel (x, y) (row 0 at the
/// top, as files store them) is texel(x, y, c), written to `path`.
inline void write_image_of(const std::string& path, int width, int height,
                           const std::function<float(int x, int y, int c)>& texel) {
  ImageBuffer img(width, height, 3);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < 3; ++c) img.at(x, y)[c] = texel(x, y, c);
  write_image(path, img);
}

/// What `f` throws (std::exception::what()), "" when it throws nothing.
inline std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

inline bool have_shared_scenes() { return std::filesystem::is_directory(shared_dir() + "/scenes/nff"); }

/// Two spheres on a floor under one light, with a viewpoint (NFF text), for
/// placing and rendering the display cameras.
inline constexpr const char* kSmallViewpointScene =
    "v\nfrom 0 -8 3\nat 0 0 0\nup 0 0 1\nangle 40\nhither 1\nresolution 64 64\n"
    "l 4 -5 8\nf 0.9 0.3 0.2 1 0 0 0 0\ns 0 0 0 1\nf 0.2 0.8 0.3 1 0 0 0 0\ns 1.5 1 0.5 0.6\n"
    "f 0.8 0.8 0.8 1 0 0 0 0\np 4\n-4 -4 -1\n4 -4 -1\n4 4 -1\n-4 4 -1\n";

/// The array a scene's NFF viewpoint places (lenses x lenses, ppl pixels
/// per lens), with the viewpoint and its look-at point moved by `shift` (world).
inline LensArrayDesc camera_at(const SceneDesc& desc, const Vec3& shift, int lenses = 32, int ppl = 8) {
  ArraySettings s;
  s.lenses_x = s.lenses_y = lenses;
  s.pixels_per_lens = ppl;
  Viewpoint vp = *desc.viewpoint;
  vp.from += shift;
  vp.at += shift;
  return place_array(s, vp);
}

/// Full ray tracing of the EIA `desc` sees, with the object-id AOV.
inline FrameBuffers trace_full(const RenderScene& scene, const LensArrayDesc& desc) {
  RenderOptions ro;
  ro.aovs.id = true;
  RenderStats stats;
  return render_frame(scene, LensArray(desc), ro, stats);
}

/// A fresh empty folder under the system temp dir, removed by the destructor.
// An environment variable set for a scope (the GPU path's measuring knobs,
// HOLORAY_GPU_*, read as a renderer is made), restored after.
struct ScopedEnv {
  std::string name;
  std::optional<std::string> old;
  ScopedEnv(const char* n, const char* value) : name(n) {
    if (const char* v = std::getenv(n)) old = v;
    ::setenv(n, value, 1);
  }
  ~ScopedEnv() {
    if (old) ::setenv(name.c_str(), old->c_str(), 1);
    else ::unsetenv(name.c_str());
  }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;
};

struct TempDir {
  std::filesystem::path path;
  TempDir() {
    path = std::filesystem::temp_directory_path() /
           ("holoray-test-" + std::to_string(::getpid()) + "-" + std::to_string(counter()++));
    std::filesystem::remove_all(path);
    std::filesystem::create_directories(path);
  }
  ~TempDir() { std::filesystem::remove_all(path); }
  std::string file(const std::string& name) const { return (path / name).string(); }
  static int& counter() {
    static int c = 0;
    return c;
  }
};

struct CommandResult {
  int status = -1;
  std::string output;  // stdout and stderr together
};

/// Runs a /bin/sh command line, capturing stdout and stderr together.
/// status is -1 when it did not exit normally (a crash).
inline CommandResult run_shell(const std::string& command) {
  CommandResult r;
  const std::string cmd = command + " 2>&1";
  FILE* p = ::popen(cmd.c_str(), "r");
  if (!p) return r;
  char buf[4096];
  size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, p)) > 0) r.output.append(buf, n);
  const int st = ::pclose(p);
  r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  return r;
}

/// Runs the holoray CLI with `args` (shell-quoted by the caller).
inline CommandResult run_cli(const std::string& args) { return run_shell(std::string(HOLORAY_CLI) + " " + args); }

/// The file's bytes; empty when it cannot be read.
inline std::string read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

inline void write_text(const std::string& path, const std::string& text) {
  FILE* f = std::fopen(path.c_str(), "wb");
  std::fwrite(text.data(), 1, text.size(), f);
  std::fclose(f);
}

/// Every file of a folder (not its subfolders): name -> bytes.
inline std::map<std::string, std::string> folder_bytes(const std::string& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    files[e.path().filename().string()] = read_bytes(e.path().string());
  return files;
}

/// The number of finished frames (frame_*) in a folder; 0 when it is missing.
inline size_t frame_count(const std::string& dir) {
  size_t n = 0;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(dir, ec))
    if (e.path().filename().string().starts_with("frame_")) ++n;
  return n;
}

/// Starts argv[0] (a path) with argv, stdout and stderr into `log`; the pid, or -1.
inline pid_t spawn(std::vector<std::string> argv, const std::string& log) {
  std::vector<char*> args;
  for (auto& a : argv) args.push_back(a.data());
  args.push_back(nullptr);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&fa, 1, 2);
  pid_t pid = -1;
  const int rc = posix_spawn(&pid, args[0], &fa, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  return rc == 0 ? pid : -1;
}

/// Waits for `pid`: its exit status, or -1 when a signal ended it.
inline int wait_exit(pid_t pid) {
  int st = 0;
  ::waitpid(pid, &st, 0);
  return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

/// Test name for a (Grid, RecordingMode) parameter, e.g. "hex_orthoscopic".
inline std::string grid_mode_name(const ::testing::TestParamInfo<std::tuple<Grid, RecordingMode>>& info) {
  return std::string(to_string(std::get<0>(info.param))) + "_" + to_string(std::get<1>(info.param));
}

}  // namespace holoray::test
