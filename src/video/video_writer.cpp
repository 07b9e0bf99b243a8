#include "video/video_writer.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "image/image_io.hpp"

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>
}

namespace holoray {

namespace fs = std::filesystem;

namespace {

std::string av_message(int err) {
  char buf[AV_ERROR_MAX_STRING_SIZE] = {};
  av_strerror(err, buf, sizeof buf);
  return buf;
}

}  // namespace

bool is_supported_video(const std::string& path) {
  const std::string e = lower_extension(path);
  return e == ".mkv" || e == ".mp4";
}

bool is_lossless_video(const std::string& path) { return lower_extension(path) == ".mkv"; }

std::string video_codec_name(const std::string& path, const VideoOptions& o) {
  return is_lossless_video(path) ? "FFV1 (lossless)" : fmt::format("H.264, CRF {}", o.crf);
}

struct VideoWriter::State {
  AVFormatContext* format = nullptr;
  AVCodecContext* codec = nullptr;
  AVStream* stream = nullptr;
  AVFrame* frame = nullptr;
  AVPacket* packet = nullptr;
  SwsContext* sws = nullptr;
  bool lossless = true;
  bool header_written = false;

  ~State() {
    sws_freeContext(sws);
    av_packet_free(&packet);
    av_frame_free(&frame);
    avcodec_free_context(&codec);
    if (format) {
      if (format->pb) avio_closep(&format->pb);
      avformat_free_context(format);
    }
  }
};

VideoWriter::VideoWriter(const std::string& path, int width, int height, const VideoOptions& o)
    : s_(std::make_unique<State>()), path_(path), width_(width), height_(height) {
  auto fail = [&](const std::string& why) { throw std::runtime_error(fmt::format("cannot write '{}': {}", path, why)); };
  if (!is_supported_video(path)) fail("a video is .mkv (FFV1, lossless) or .mp4 (H.264)");
  s_->lossless = lower_extension(path) == ".mkv";
  if (width < 1 || height < 1) fail(fmt::format("frames of {}x{} pixels", width, height));
  if (!s_->lossless && (width % 2 || height % 2))
    fail(fmt::format("H.264 in 4:2:0 needs even sizes, the frames are {}x{}; write .mkv (lossless) instead", width, height));
  if (!(o.fps > 0) || !std::isfinite(o.fps)) fail(fmt::format("expected a positive frame rate, got {}", o.fps));
  if (o.crf < 0 || o.crf > 51) fail(fmt::format("expected a CRF from 0 to 51, got {}", o.crf));
  const fs::path dest(path);
  const fs::path dir = dest.parent_path().empty() ? fs::path(".") : dest.parent_path();
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) fail(fmt::format("folder '{}' does not exist", dir.string()));
  tmp_ = (dir / fmt::format(".{}.tmp{}{}", dest.stem().string(), static_cast<long>(::getpid()), lower_extension(path))).string();

  av_log_set_level(AV_LOG_QUIET);  // failures come back as this message, not FFmpeg's log
  const AVCodec* enc = avcodec_find_encoder(s_->lossless ? AV_CODEC_ID_FFV1 : AV_CODEC_ID_H264);
  if (!enc) fail(fmt::format("this FFmpeg has no {} encoder", s_->lossless ? "FFV1" : "H.264"));
  int err = avformat_alloc_output_context2(&s_->format, nullptr, s_->lossless ? "matroska" : "mp4", tmp_.c_str());
  if (err < 0 || !s_->format) fail(av_message(err));
  s_->stream = avformat_new_stream(s_->format, nullptr);
  s_->codec = avcodec_alloc_context3(enc);
  if (!s_->stream || !s_->codec) fail("out of memory");
  AVCodecContext* c = s_->codec;
  c->width = width;
  c->height = height;
  const AVRational rate = av_d2q(o.fps, 100000);
  c->time_base = av_inv_q(rate);
  c->framerate = rate;
  c->gop_size = s_->lossless ? 1 : 12;
  // FFV1 codes 8-bit RGB as 32-bit words (B, G, R, 0 in memory).
  c->pix_fmt = s_->lossless ? AV_PIX_FMT_BGR0 : AV_PIX_FMT_YUV420P;
  if (s_->lossless) {
    av_opt_set_int(c->priv_data, "level", 3, 0);  // FFV1 version 3: slices, CRCs
  } else {
    av_opt_set(c->priv_data, "crf", fmt::format("{}", o.crf).c_str(), 0);
    av_opt_set(c->priv_data, "preset", "medium", 0);
  }
  if (s_->format->oformat->flags & AVFMT_GLOBALHEADER) c->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
  // The same frames make the same file (no random segment id, no version
  // strings): a resumed run's video is byte for byte an uninterrupted one's.
  c->flags |= AV_CODEC_FLAG_BITEXACT;
  s_->format->flags |= AVFMT_FLAG_BITEXACT;
  if ((err = avcodec_open2(c, enc, nullptr)) < 0) fail(av_message(err));
  if ((err = avcodec_parameters_from_context(s_->stream->codecpar, c)) < 0) fail(av_message(err));
  s_->stream->time_base = c->time_base;
  s_->stream->avg_frame_rate = rate;
  if ((err = avio_open(&s_->format->pb, tmp_.c_str(), AVIO_FLAG_WRITE)) < 0) fail(av_message(err));
  if ((err = avformat_write_header(s_->format, nullptr)) < 0) fail(av_message(err));
  s_->header_written = true;
  s_->frame = av_frame_alloc();
  s_->packet = av_packet_alloc();
  if (!s_->frame || !s_->packet) fail("out of memory");
  s_->frame->format = c->pix_fmt;
  s_->frame->width = width;
  s_->frame->height = height;
  if ((err = av_frame_get_buffer(s_->frame, 0)) < 0) fail(av_message(err));
  if (!s_->lossless) {
    s_->sws = sws_getContext(width, height, AV_PIX_FMT_RGB24, width, height, AV_PIX_FMT_YUV420P, SWS_BICUBIC, nullptr,
                             nullptr, nullptr);
    if (!s_->sws) fail("no RGB to YUV converter");
  }
}

VideoWriter::~VideoWriter() {
  if (finished_) return;
  s_.reset();  // closes the file first
  std::error_code ec;
  if (!tmp_.empty()) fs::remove(tmp_, ec);
}

namespace {
// Sends `frame` (null: flush) and writes every packet the encoder returns.
void drain(AVCodecContext* c, AVFormatContext* f, AVStream* st, AVFrame* frame, AVPacket* pkt, const std::string& path) {
  int err = avcodec_send_frame(c, frame);
  if (err < 0) throw std::runtime_error(fmt::format("cannot write '{}': {}", path, av_message(err)));
  while ((err = avcodec_receive_packet(c, pkt)) >= 0) {
    av_packet_rescale_ts(pkt, c->time_base, st->time_base);
    pkt->stream_index = st->index;
    err = av_interleaved_write_frame(f, pkt);
    if (err < 0) throw std::runtime_error(fmt::format("cannot write '{}': {}", path, av_message(err)));
  }
  if (err != AVERROR(EAGAIN) && err != AVERROR_EOF)
    throw std::runtime_error(fmt::format("cannot write '{}': {}", path, av_message(err)));
}
}  // namespace

void VideoWriter::add_frame(const uint8_t* rgb) {
  if (finished_) throw std::logic_error("VideoWriter::add_frame after finish");
  AVFrame* fr = s_->frame;
  int err = av_frame_make_writable(fr);
  if (err < 0) throw std::runtime_error(fmt::format("cannot write '{}': {}", path_, av_message(err)));
  if (s_->lossless) {
    // B, G, R, 0 per pixel: the bytes as given, reordered.
    for (int y = 0; y < height_; ++y) {
      const uint8_t* row = rgb + static_cast<size_t>(y) * width_ * 3;
      uint8_t* out = fr->data[0] + static_cast<ptrdiff_t>(y) * fr->linesize[0];
      for (int x = 0; x < width_; ++x)
        out[4 * x] = row[3 * x + 2], out[4 * x + 1] = row[3 * x + 1], out[4 * x + 2] = row[3 * x], out[4 * x + 3] = 0;
    }
  } else {
    const uint8_t* src[1] = {rgb};
    const int stride[1] = {width_ * 3};
    sws_scale(s_->sws, src, stride, 0, height_, fr->data, fr->linesize);
  }
  fr->pts = frames_++;
  drain(s_->codec, s_->format, s_->stream, fr, s_->packet, path_);
}

void VideoWriter::finish() {
  if (finished_) return;
  drain(s_->codec, s_->format, s_->stream, nullptr, s_->packet, path_);
  int err = av_write_trailer(s_->format);
  if (err < 0) throw std::runtime_error(fmt::format("cannot write '{}': {}", path_, av_message(err)));
  s_.reset();  // closes the file
  std::error_code ec;
  fs::rename(tmp_, path_, ec);
  if (ec) {
    fs::remove(tmp_, ec);
    throw std::runtime_error(fmt::format("cannot write '{}': {}", path_, ec.message()));
  }
  finished_ = true;
}

}  // namespace holoray
