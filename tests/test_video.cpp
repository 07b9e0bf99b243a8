// Video output (issue 14, item 3): FFV1 frames decode equal to the 8-bit
// frames bit for bit and the frame count is right; H.264 decodes close to
// them; `animate --video` writes the video of its frames, none when the run
// is refused, and a resumed run rebuilds it. Decoding goes through FFmpeg's
// libraries directly, not through holoray's writer.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "image/image_io.hpp"
#include "image/metrics.hpp"
#include "test_util.hpp"
#include "video/video_writer.hpp"

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libswscale/swscale.h>
}

namespace holoray {
namespace {

// Every frame of the file's video stream as 8-bit RGB rows (width*height*3).
std::vector<std::vector<uint8_t>> decode_rgb(const std::string& path, int& width, int& height) {
  std::vector<std::vector<uint8_t>> frames;
  AVFormatContext* fmt = nullptr;
  if (avformat_open_input(&fmt, path.c_str(), nullptr, nullptr) < 0) return frames;
  avformat_find_stream_info(fmt, nullptr);
  const int s = av_find_best_stream(fmt, AVMEDIA_TYPE_VIDEO, -1, -1, nullptr, 0);
  const AVCodec* dec = avcodec_find_decoder(fmt->streams[s]->codecpar->codec_id);
  AVCodecContext* c = avcodec_alloc_context3(dec);
  avcodec_parameters_to_context(c, fmt->streams[s]->codecpar);
  avcodec_open2(c, dec, nullptr);
  AVPacket* pkt = av_packet_alloc();
  AVFrame* fr = av_frame_alloc();
  SwsContext* sws = nullptr;
  auto take = [&] {
    while (avcodec_receive_frame(c, fr) >= 0) {
      width = fr->width, height = fr->height;
      if (!sws)
        sws = sws_getContext(width, height, static_cast<AVPixelFormat>(fr->format), width, height, AV_PIX_FMT_RGB24,
                             SWS_POINT | SWS_ACCURATE_RND | SWS_BITEXACT, nullptr, nullptr, nullptr);
      std::vector<uint8_t> rgb(size_t(width) * height * 3);
      uint8_t* dst[1] = {rgb.data()};
      const int stride[1] = {width * 3};
      sws_scale(sws, fr->data, fr->linesize, 0, height, dst, stride);
      frames.push_back(std::move(rgb));
    }
  };
  while (av_read_frame(fmt, pkt) >= 0) {
    if (pkt->stream_index == s) {
      avcodec_send_packet(c, pkt);
      take();
    }
    av_packet_unref(pkt);
  }
  avcodec_send_packet(c, nullptr);
  take();
  sws_freeContext(sws);
  av_frame_free(&fr);
  av_packet_free(&pkt);
  avcodec_free_context(&c);
  avformat_close_input(&fmt);
  return frames;
}

std::vector<std::vector<uint8_t>> random_frames(int n, int w, int h) {
  std::mt19937 rng(3);
  std::vector<std::vector<uint8_t>> frames(n, std::vector<uint8_t>(size_t(w) * h * 3));
  for (auto& f : frames)
    for (auto& b : f) b = static_cast<uint8_t>(rng());
  return frames;
}

TEST(Video, FfvOneFramesDecodeEqualBitForBit) {
  test::TempDir dir;
  const auto frames = random_frames(5, 33, 17);  // odd sizes: FFV1 takes any
  {
    VideoWriter v(dir.file("v.mkv"), 33, 17, VideoOptions{24, 18});
    for (const auto& f : frames) v.add_frame(f.data());
    v.finish();
  }
  int w = 0, h = 0;
  const auto got = decode_rgb(dir.file("v.mkv"), w, h);
  ASSERT_EQ(got.size(), 5u);
  EXPECT_EQ(w, 33);
  EXPECT_EQ(h, 17);
  for (size_t k = 0; k < got.size(); ++k) EXPECT_EQ(got[k], frames[k]) << "frame " << k;
}

TEST(Video, H264DecodesCloseToItsFramesAndRefusesOddSizes) {
  test::TempDir dir;
  // A smooth gradient that moves: what an encoder is made for.
  std::vector<std::vector<uint8_t>> frames(4, std::vector<uint8_t>(64 * 48 * 3));
  for (int k = 0; k < 4; ++k)
    for (int y = 0; y < 48; ++y)
      for (int x = 0; x < 64; ++x)
        for (int c = 0; c < 3; ++c) frames[k][(y * 64 + x) * 3 + c] = static_cast<uint8_t>(20 + x * 2 + y + k * 3 + c * 10);
  {
    VideoWriter v(dir.file("v.mp4"), 64, 48, VideoOptions{30, 10});
    for (const auto& f : frames) v.add_frame(f.data());
    v.finish();
  }
  int w = 0, h = 0;
  const auto got = decode_rgb(dir.file("v.mp4"), w, h);
  ASSERT_EQ(got.size(), 4u);
  for (size_t k = 0; k < got.size(); ++k) {
    double se = 0;
    for (size_t i = 0; i < got[k].size(); ++i) se += std::pow(got[k][i] - frames[k][i], 2);
    const double psnr = 10 * std::log10(255.0 * 255.0 / (se / got[k].size()));
    EXPECT_GT(psnr, 30) << "frame " << k;
  }
  EXPECT_THROW(VideoWriter(dir.file("odd.mp4"), 33, 17, VideoOptions{}), std::runtime_error);
  EXPECT_THROW(VideoWriter(dir.file("v.avi"), 32, 16, VideoOptions{}), std::runtime_error);
}

TEST(Video, AnUnfinishedVideoLeavesNoFile) {
  test::TempDir dir;
  {
    VideoWriter v(dir.file("v.mkv"), 8, 8, VideoOptions{});
    const auto f = random_frames(1, 8, 8);
    v.add_frame(f[0].data());
  }  // destroyed without finish(): an interrupted run
  EXPECT_TRUE(std::filesystem::is_empty(dir.path));
}

// animate --video: the FFV1 video of a shot is its PNG frames, bit for bit
// and in order; a resumed run (frames already there) rebuilds it whole.
TEST(Video, AnimateWritesTheVideoOfItsFrames) {
  test::TempDir dir;
  const std::string shot = test::source_dir() + "/examples/shots/swinging_box.toml";
  const auto r = test::run_cli("animate " + shot + " -o " + dir.file("out") + " --video " + dir.file("out/v.mkv") + " -q");
  ASSERT_EQ(r.status, 0) << r.output;
  int w = 0, h = 0;
  const auto got = decode_rgb(dir.file("out/v.mkv"), w, h);
  ASSERT_EQ(got.size(), 48u);
  for (int f : {0, 17, 47}) {
    const ImageBuffer png = read_image(dir.file(fmt::format("out/frame_{:04}.png", f)));
    ASSERT_EQ(png.width, w);
    std::vector<uint8_t> bytes(png.data.size());
    for (size_t i = 0; i < bytes.size(); ++i) bytes[i] = encode_8bit(png.data[i], Encoding::linear);
    EXPECT_EQ(got[static_cast<size_t>(f)], bytes) << "frame " << f;
  }
  std::filesystem::remove(dir.file("out/v.mkv"));
  std::filesystem::remove(dir.file("out/frame_0010.png"));
  const auto again = test::run_cli("animate " + shot + " -o " + dir.file("out") + " --resume --video " + dir.file("out/v.mkv") + " -q");
  ASSERT_EQ(again.status, 0) << again.output;
  EXPECT_EQ(decode_rgb(dir.file("out/v.mkv"), w, h).size(), 48u);
  // A refused option writes nothing.
  const auto bad = test::run_cli("animate " + shot + " -o " + dir.file("out2") + " --video " + dir.file("v.mkv") + " --crf 20 -q");
  EXPECT_EQ(bad.status, 1);
  EXPECT_NE(bad.output.find("--crf: goes with an .mp4 video (FFV1 is lossless)"), std::string::npos) << bad.output;
  EXPECT_FALSE(std::filesystem::exists(dir.file("v.mkv")));
}

}  // namespace
}  // namespace holoray
