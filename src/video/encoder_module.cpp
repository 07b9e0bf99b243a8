// Finds and loads holoray_ffmpeg.so once per process: beside an installed
// binary in ../lib/holoray, else where the build put it.
#include <dlfcn.h>
#include <fmt/format.h>

#include <filesystem>
#include <mutex>
#include <stdexcept>
#include <vector>

#include "video/video_encoder.hpp"

namespace holoray {

namespace {

using OpenFn = decltype(&holoray_open_video_encoder);

OpenFn load_module() {
  static std::once_flag once;
  static OpenFn open = nullptr;
  static std::string why;
  std::call_once(once, [] {
    std::vector<std::string> candidates;
    std::error_code ec;
    const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (!ec) candidates.push_back((exe.parent_path().parent_path() / "lib/holoray/holoray_ffmpeg.so").string());
    candidates.push_back(HOLORAY_FFMPEG_MODULE);
    for (const std::string& path : candidates) {
      if (!std::filesystem::exists(path, ec)) continue;
      // RTLD_LOCAL: FFmpeg's symbols stay inside the module.
      void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
      if (!handle) {
        why = dlerror();
        return;
      }
      open = reinterpret_cast<OpenFn>(dlsym(handle, "holoray_open_video_encoder"));
      if (!open) why = fmt::format("'{}' has no holoray_open_video_encoder", path);
      return;
    }
    why = fmt::format("holoray's FFmpeg module is not installed (looked for {})", fmt::join(candidates, ", "));
  });
  if (!open) throw std::runtime_error(why);
  return open;
}

}  // namespace

std::unique_ptr<VideoEncoder> open_video_encoder(const std::string& path, int width, int height, bool lossless, double fps,
                                                 int crf) {
  return std::unique_ptr<VideoEncoder>(load_module()(path.c_str(), width, height, lossless, fps, crf));
}

}  // namespace holoray
