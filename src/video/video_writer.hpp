// holoray/video: sequences as video files through FFmpeg's libraries
// (libavcodec, libavformat), loaded on the first video only (video_encoder.hpp). The container and codec
// follow the extension:
//   .mkv  FFV1, lossless RGB (8-bit B, G, R, 0 words): decoded frames equal
//         the 8-bit frames given, bit for bit;
//   .mp4  H.264 (libx264), 4:2:0, quality by CRF (0 best .. 51 worst).
// The file is written under a temporary name in the same folder and renamed
// when complete, so an interrupted or failed run never leaves a broken video.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace holoray {

struct VideoOptions {
  double fps = 24;  ///< frames per second (shot files' fps)
  int crf = 18;     ///< H.264 only: constant rate factor, 0..51
};

/// True for the extensions VideoWriter writes (.mkv, .mp4, any case).
bool is_supported_video(const std::string& path);
/// True for .mkv (FFV1, lossless), false for .mp4 (H.264).
bool is_lossless_video(const std::string& path);
/// "FFV1 (lossless)" or "H.264, CRF n", for messages.
std::string video_codec_name(const std::string& path, const VideoOptions& options);

class VideoEncoder;

/// A video written frame by frame; the file appears under its name on finish().
class VideoWriter {
 public:
  /// Opens `path`'s temporary file for width x height frames. Throws
  /// std::runtime_error naming the path and reason: an unsupported
  /// extension, odd sizes for H.264's 4:2:0, no encoder in this FFmpeg, a
  /// folder that does not exist, a CRF outside 0..51, fps not positive.
  VideoWriter(const std::string& path, int width, int height, const VideoOptions& options);
  /// Removes the temporary file unless finish() completed.
  ~VideoWriter();
  VideoWriter(const VideoWriter&) = delete;
  VideoWriter& operator=(const VideoWriter&) = delete;

  /// One frame: width*height*3 bytes, RGB, rows from the top.
  void add_frame(const uint8_t* rgb);
  /// Flushes the encoder, writes the trailer and renames the file into place.
  void finish();
  int frames() const { return frames_; }

 private:
  std::unique_ptr<VideoEncoder> encoder_;
  std::string path_, tmp_;
  int width_, height_, frames_ = 0;
  bool finished_ = false;
};

}  // namespace holoray
