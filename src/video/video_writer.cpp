#include "video/video_writer.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "image/image_io.hpp"

#include "video/video_encoder.hpp"

namespace holoray {

namespace fs = std::filesystem;

bool is_supported_video(const std::string& path) {
  const std::string e = lower_extension(path);
  return e == ".mkv" || e == ".mp4";
}

bool is_lossless_video(const std::string& path) { return lower_extension(path) == ".mkv"; }

std::string video_codec_name(const std::string& path, const VideoOptions& o) {
  return is_lossless_video(path) ? "FFV1 (lossless)" : fmt::format("H.264, CRF {}", o.crf);
}

VideoWriter::VideoWriter(const std::string& path, int width, int height, const VideoOptions& o)
    : path_(path), width_(width), height_(height) {
  auto fail = [&](const std::string& why) { throw std::runtime_error(fmt::format("cannot write '{}': {}", path, why)); };
  if (!is_supported_video(path)) fail("a video is .mkv (FFV1, lossless) or .mp4 (H.264)");
  const bool lossless = lower_extension(path) == ".mkv";
  if (width < 1 || height < 1) fail(fmt::format("frames of {}x{} pixels", width, height));
  if (!lossless && (width % 2 || height % 2))
    fail(fmt::format("H.264 in 4:2:0 needs even sizes, the frames are {}x{}; write .mkv (lossless) instead", width, height));
  if (!(o.fps > 0) || !std::isfinite(o.fps)) fail(fmt::format("expected a positive frame rate, got {}", o.fps));
  if (o.crf < 0 || o.crf > 51) fail(fmt::format("expected a CRF from 0 to 51, got {}", o.crf));
  const fs::path dest(path);
  const fs::path dir = dest.parent_path().empty() ? fs::path(".") : dest.parent_path();
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) fail(fmt::format("folder '{}' does not exist", dir.string()));
  tmp_ = (dir / fmt::format(".{}.tmp{}{}", dest.stem().string(), static_cast<long>(::getpid()), lower_extension(path))).string();

  try {
    encoder_ = open_video_encoder(tmp_, width, height, lossless, o.fps, o.crf);
  } catch (const std::runtime_error& e) {
    std::error_code ec2;
    fs::remove(tmp_, ec2);
    fail(e.what());
  }
}

VideoWriter::~VideoWriter() {
  if (finished_) return;
  encoder_.reset();  // closes the file first
  std::error_code ec;
  if (!tmp_.empty()) fs::remove(tmp_, ec);
}

void VideoWriter::add_frame(const uint8_t* rgb) {
  if (finished_) throw std::logic_error("VideoWriter::add_frame after finish");
  try {
    encoder_->add_frame(rgb);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(fmt::format("cannot write '{}': {}", path_, e.what()));
  }
  ++frames_;
}

void VideoWriter::finish() {
  if (finished_) return;
  try {
    encoder_->finish();
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(fmt::format("cannot write '{}': {}", path_, e.what()));
  }
  encoder_.reset();
  std::error_code ec;
  fs::rename(tmp_, path_, ec);
  if (ec) {
    fs::remove(tmp_, ec);
    throw std::runtime_error(fmt::format("cannot write '{}': {}", path_, ec.message()));
  }
  finished_ = true;
}

}  // namespace holoray
