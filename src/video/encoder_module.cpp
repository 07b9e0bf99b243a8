// Finds and loads holoray_ffmpeg.so once per process (util/module_loader.hpp).
#include "util/module_loader.hpp"
#include "video/video_encoder.hpp"

namespace holoray {

namespace {

using OpenFn = decltype(&holoray_open_video_encoder);

OpenFn load_module() {
  return reinterpret_cast<OpenFn>(module_symbol("holoray_ffmpeg.so", HOLORAY_FFMPEG_MODULE, "holoray_open_video_encoder",
                                                "holoray's FFmpeg module is not installed"));
}

}  // namespace

std::unique_ptr<VideoEncoder> open_video_encoder(const std::string& path, int width, int height, bool lossless, double fps,
                                                 int crf) {
  return std::unique_ptr<VideoEncoder>(load_module()(path.c_str(), width, height, lossless, fps, crf));
}

}  // namespace holoray
