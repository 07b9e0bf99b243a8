// The public video writer (holoray/video.hpp) over video/video_writer.
#include "holoray/video.hpp"

#include <fmt/format.h>

#include <stdexcept>
#include <vector>

#include "image/image_io.hpp"
#include "video/video_writer.hpp"

namespace holoray::api {

namespace {

holoray::VideoOptions internal(const VideoOptions& o) { return {o.fps, o.crf}; }

}  // namespace

bool is_video_output(const std::string& path) { return holoray::is_supported_video(path); }

bool is_lossless_video(const std::string& path) { return holoray::is_lossless_video(path); }

std::string video_codec_name(const std::string& path, const VideoOptions& options) {
  return holoray::video_codec_name(path, internal(options));
}

struct VideoWriter::Open {
  holoray::VideoWriter writer;
  int width, height;
  std::vector<uint8_t> bytes;
};

VideoWriter::VideoWriter(const std::string& path, int width, int height, const VideoOptions& options)
    : open_(new Open{holoray::VideoWriter(path, width, height, internal(options)), width, height, {}}) {}

VideoWriter::~VideoWriter() = default;

void VideoWriter::add_frame(const Image& frame, Encoding encoding) {
  Open& o = *open_;
  if (frame.width() != o.width || frame.height() != o.height || frame.channels() < 3)
    throw std::invalid_argument(fmt::format("video frame {}: expected {}x{} pixels of RGB, got {}x{} of {} channel{}",
                                            o.writer.frames(), o.width, o.height, frame.width(), frame.height(),
                                            frame.channels(), frame.channels() == 1 ? "" : "s"));
  const size_t pixels = size_t(o.width) * o.height;
  o.bytes.resize(pixels * 3);
  const float* v = frame.data();
  const int c = frame.channels();
  for (size_t p = 0; p < pixels; ++p)
    for (int k = 0; k < 3; ++k) o.bytes[p * 3 + k] = api::encode_8bit(v[p * c + k], encoding);
  o.writer.add_frame(o.bytes.data());
}

void VideoWriter::finish() { open_->writer.finish(); }

int VideoWriter::frames() const { return open_->writer.frames(); }

}  // namespace holoray::api
