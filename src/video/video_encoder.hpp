// holoray/video, internal: the interface between VideoWriter and the FFmpeg
// module that implements it (ffmpeg_encoder.cpp, built as holoray_ffmpeg.so
// and loaded by encoder_module.cpp on the first video).
#pragma once

#include <cstdint>
#include <memory>
#include <string>

namespace holoray {

/// One open video file. Errors are std::runtime_error carrying FFmpeg's
/// reason only; VideoWriter names the file.
class VideoEncoder {
 public:
  virtual ~VideoEncoder() = default;
  /// width*height*3 bytes, RGB, rows from the top.
  virtual void add_frame(const uint8_t* rgb) = 0;
  /// Flushes the encoder, writes the trailer and closes the file.
  virtual void finish() = 0;
};

/// Opens `path` for an FFV1 Matroska (lossless) or H.264 MP4 stream through
/// the FFmpeg module. Throws std::runtime_error when the module cannot be
/// loaded (saying where it was looked for) or FFmpeg refuses.
std::unique_ptr<VideoEncoder> open_video_encoder(const std::string& path, int width, int height, bool lossless, double fps,
                                                 int crf);

}  // namespace holoray

/// The module's one entry point (C linkage, so dlsym finds it by name).
extern "C" holoray::VideoEncoder* holoray_open_video_encoder(const char* path, int width, int height, bool lossless,
                                                             double fps, int crf);
