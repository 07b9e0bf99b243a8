// holoray public API: image sequences as video files, through FFmpeg's
// libraries (loaded on the first video only). The extension picks the codec:
//   .mkv  FFV1, lossless: decoded frames equal the 8-bit frames given;
//   .mp4  H.264 (libx264), 4:2:0, quality by CRF (0 best .. 51 worst).
// Written under a temporary name and renamed when complete: an interrupted
// run never leaves a broken video.
#pragma once

#include <memory>
#include <string>

#include "holoray/export.hpp"
#include "holoray/image.hpp"

namespace holoray::api {

struct VideoOptions {
  double fps = 24;  ///< frames per second (a shot file's fps)
  int crf = 18;     ///< H.264 only: constant rate factor, 0..51
};

/// True for the extensions VideoWriter writes (.mkv, .mp4, any case).
HOLORAY_API bool is_video_output(const std::string& path);
/// True for .mkv (FFV1, lossless), false for .mp4 (H.264).
HOLORAY_API bool is_lossless_video(const std::string& path);
/// "FFV1 (lossless)" or "H.264, CRF n", for summaries.
HOLORAY_API std::string video_codec_name(const std::string& path, const VideoOptions& options);

/// A video written frame by frame; the file gets its name on finish().
class HOLORAY_API VideoWriter {
 public:
  /// Opens `path`'s temporary file for width x height frames. Throws
  /// std::runtime_error naming the path and reason: an unsupported
  /// extension, odd sizes for H.264's 4:2:0, no encoder in this FFmpeg, a
  /// missing folder, a CRF outside 0..51, fps not positive.
  VideoWriter(const std::string& path, int width, int height, const VideoOptions& options = {});
  /// Removes the temporary file unless finish() completed.
  ~VideoWriter();
  VideoWriter(const VideoWriter&) = delete;
  VideoWriter& operator=(const VideoWriter&) = delete;
  /// One frame, the writer's size, at least 3 channels (R, G, B taken),
  /// each value made an 8-bit code as write_image makes it (`encoding`).
  /// Throws std::invalid_argument for another size or fewer channels.
  void add_frame(const Image& frame, Encoding encoding = Encoding::linear);
  /// Flushes the encoder, writes the trailer and renames the file into place.
  void finish();
  int frames() const;

 private:
  struct Open;
  std::unique_ptr<Open> open_;
};

}  // namespace holoray::api
