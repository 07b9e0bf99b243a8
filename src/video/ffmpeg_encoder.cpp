// The FFmpeg half of VideoWriter, built as a module of its own
// (holoray_ffmpeg.so) and loaded only when a video is written: FFmpeg's
// libraries bring about 130 shared libraries that would otherwise cost every
// holoray process some 55 ms at start-up.
#include <fmt/format.h>

#include <stdexcept>
#include <string>

#include "video/video_encoder.hpp"

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>
}

namespace holoray {

namespace {

std::string av_message(int err) {
  char buf[AV_ERROR_MAX_STRING_SIZE] = {};
  av_strerror(err, buf, sizeof buf);
  return buf;
}

struct State {
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

// Sends `frame` (null: flush) and writes every packet the encoder returns.
void drain(AVCodecContext* c, AVFormatContext* f, AVStream* st, AVFrame* frame, AVPacket* pkt) {
  int err = avcodec_send_frame(c, frame);
  if (err < 0) throw std::runtime_error(av_message(err));
  while ((err = avcodec_receive_packet(c, pkt)) >= 0) {
    av_packet_rescale_ts(pkt, c->time_base, st->time_base);
    pkt->stream_index = st->index;
    err = av_interleaved_write_frame(f, pkt);
    if (err < 0) throw std::runtime_error(av_message(err));
  }
  if (err != AVERROR(EAGAIN) && err != AVERROR_EOF)
    throw std::runtime_error(av_message(err));
}

class FfmpegEncoder final : public VideoEncoder {
 public:
  FfmpegEncoder(const std::string& path, int width, int height, bool lossless, double fps, int crf)
      : width_(width), height_(height) {
    auto fail = [](const std::string& why) { throw std::runtime_error(why); };
    s_.lossless = lossless;
    av_log_set_level(AV_LOG_QUIET);  // failures come back as this message, not FFmpeg's log
    const AVCodec* enc = avcodec_find_encoder(s_.lossless ? AV_CODEC_ID_FFV1 : AV_CODEC_ID_H264);
    if (!enc) fail(fmt::format("this FFmpeg has no {} encoder", s_.lossless ? "FFV1" : "H.264"));
    int err = avformat_alloc_output_context2(&s_.format, nullptr, s_.lossless ? "matroska" : "mp4", path.c_str());
    if (err < 0 || !s_.format) fail(av_message(err));
    s_.stream = avformat_new_stream(s_.format, nullptr);
    s_.codec = avcodec_alloc_context3(enc);
    if (!s_.stream || !s_.codec) fail("out of memory");
    AVCodecContext* c = s_.codec;
    c->width = width;
    c->height = height;
    const AVRational rate = av_d2q(fps, 100000);
    c->time_base = av_inv_q(rate);
    c->framerate = rate;
    c->gop_size = s_.lossless ? 1 : 12;
    // FFV1 codes 8-bit RGB as 32-bit words (B, G, R, 0 in memory).
    c->pix_fmt = s_.lossless ? AV_PIX_FMT_BGR0 : AV_PIX_FMT_YUV420P;
    if (s_.lossless) {
      av_opt_set_int(c->priv_data, "level", 3, 0);  // FFV1 version 3: slices, CRCs
    } else {
      av_opt_set(c->priv_data, "crf", fmt::format("{}", crf).c_str(), 0);
      av_opt_set(c->priv_data, "preset", "medium", 0);
    }
    if (s_.format->oformat->flags & AVFMT_GLOBALHEADER) c->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
    // The same frames make the same file (no random segment id, no version
    // strings): a resumed run's video is byte for byte an uninterrupted one's.
    c->flags |= AV_CODEC_FLAG_BITEXACT;
    s_.format->flags |= AVFMT_FLAG_BITEXACT;
    if ((err = avcodec_open2(c, enc, nullptr)) < 0) fail(av_message(err));
    if ((err = avcodec_parameters_from_context(s_.stream->codecpar, c)) < 0) fail(av_message(err));
    s_.stream->time_base = c->time_base;
    s_.stream->avg_frame_rate = rate;
    if ((err = avio_open(&s_.format->pb, path.c_str(), AVIO_FLAG_WRITE)) < 0) fail(av_message(err));
    if ((err = avformat_write_header(s_.format, nullptr)) < 0) fail(av_message(err));
    s_.header_written = true;
    s_.frame = av_frame_alloc();
    s_.packet = av_packet_alloc();
    if (!s_.frame || !s_.packet) fail("out of memory");
    s_.frame->format = c->pix_fmt;
    s_.frame->width = width;
    s_.frame->height = height;
    if ((err = av_frame_get_buffer(s_.frame, 0)) < 0) fail(av_message(err));
    if (!s_.lossless) {
      s_.sws = sws_getContext(width, height, AV_PIX_FMT_RGB24, width, height, AV_PIX_FMT_YUV420P, SWS_BICUBIC, nullptr,
                               nullptr, nullptr);
      if (!s_.sws) fail("no RGB to YUV converter");
    }
  }

  void add_frame(const uint8_t* rgb) override {
    AVFrame* fr = s_.frame;
    int err = av_frame_make_writable(fr);
    if (err < 0) throw std::runtime_error(av_message(err));
    if (s_.lossless) {
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
      sws_scale(s_.sws, src, stride, 0, height_, fr->data, fr->linesize);
    }
    fr->pts = frames_++;
    drain(s_.codec, s_.format, s_.stream, fr, s_.packet);
  }

  void finish() override {
    drain(s_.codec, s_.format, s_.stream, nullptr, s_.packet);
    const int err = av_write_trailer(s_.format);
    if (err < 0) throw std::runtime_error(av_message(err));
    if (s_.format->pb && (avio_closep(&s_.format->pb)) < 0) throw std::runtime_error("cannot close the file");
  }

 private:
  State s_;
  int width_, height_, frames_ = 0;
};

}  // namespace

}  // namespace holoray

extern "C" __attribute__((visibility("default"))) holoray::VideoEncoder* holoray_open_video_encoder(
    const char* path, int width, int height, bool lossless,
                                                             double fps, int crf) {
  return new holoray::FfmpegEncoder(path, width, height, lossless, fps, crf);
}
