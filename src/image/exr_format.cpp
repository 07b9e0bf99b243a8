// OpenEXR through the OpenEXR library (scanline files, float channels).
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStdIO.h>
#include <OpenEXR/ImfThreading.h>

#include <cerrno>
#include <cstring>

#include <algorithm>
#include <array>
#include <fstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "image/formats.hpp"

namespace holoray::formats {

namespace {

// OpenImageIO's default names, which holoray's files have always carried.
std::string channel_name(int c, int channels) {
  if (channels == 1) return "Y";
  static constexpr std::array<const char*, 4> kRgba = {"R", "G", "B", "A"};
  return c < 4 ? kRgba[size_t(c)] : "channel" + std::to_string(c);
}

// ZIP blocks compress and decompress in parallel on OpenEXR's own thread
// pool, started on the first EXR (a 2048x2048 EIA with two AOVs: 1.29 s
// written on one thread, 0.66 s on two).
int exr_threads() {
  static const int n = [] {
    const int cores = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
    Imf::setGlobalThreadCount(cores);
    return cores;
  }();
  return n;
}

Imf::Compression imf_compression(ExrCompression c) {
  switch (c) {
    case ExrCompression::none: return Imf::NO_COMPRESSION;
    case ExrCompression::rle: return Imf::RLE_COMPRESSION;
    case ExrCompression::zips: return Imf::ZIPS_COMPRESSION;
    case ExrCompression::zip: return Imf::ZIP_COMPRESSION;
    case ExrCompression::piz: return Imf::PIZ_COMPRESSION;
  }
  return Imf::ZIP_COMPRESSION;
}

template <class F>
auto rethrow(F&& f) {
  try {
    return f();
  } catch (const std::runtime_error&) {
    throw;
  } catch (const std::exception& e) {  // Iex::BaseExc and the standard library's
    throw std::runtime_error(e.what());
  }
}

class ExrOutput final : public ScanlineOutput {
 public:
  ExrOutput(const std::string& path, int w, int h, int channels, ExrCompression compression)
      : width_(w), channels_(channels), out_(path, std::ios::binary | std::ios::trunc) {
    if (!out_) throw std::runtime_error(std::strerror(errno));
    stream_ = std::make_unique<Imf::StdOFStream>(out_, path.c_str());
    Imf::Header header(w, h);
    header.compression() = imf_compression(compression);
    for (int c = 0; c < channels; ++c) header.channels().insert(channel_name(c, channels), Imf::Channel(Imf::FLOAT));
    file_ = std::make_unique<Imf::OutputFile>(*stream_, header, exr_threads());
  }

  void write_rows(const float* values, int count) override {
    rethrow([&] {
      // OpenEXR addresses a frame buffer by absolute row: shift the base so
      // that row next_row_ is values' first.
      const size_t xs = sizeof(float) * size_t(channels_), ys = xs * size_t(width_);
      char* base = const_cast<char*>(reinterpret_cast<const char*>(values)) - ptrdiff_t(ys) * next_row_;
      Imf::FrameBuffer fb;
      for (int c = 0; c < channels_; ++c)
        fb.insert(channel_name(c, channels_), Imf::Slice(Imf::FLOAT, base + sizeof(float) * size_t(c), xs, ys));
      file_->setFrameBuffer(fb);
      file_->writePixels(count);
      next_row_ += count;
      return 0;
    });
  }

  void close() override {
    rethrow([&] {
      // The destructor writes the line offset table and swallows its errors:
      // the stream's state says whether everything reached the disk.
      file_.reset();
      out_.close();
      if (out_.fail()) throw std::runtime_error(errno ? std::strerror(errno) : "write error");
      return 0;
    });
  }

 private:
  int width_, channels_, next_row_ = 0;
  std::ofstream out_;
  std::unique_ptr<Imf::StdOFStream> stream_;
  std::unique_ptr<Imf::OutputFile> file_;  // destroyed first
};

// R, G, B, A in that order when present, then the rest as the file lists them.
std::vector<std::string> ordered_channels(const Imf::ChannelList& list) {
  std::vector<std::string> names, rest;
  for (const char* n : {"R", "G", "B", "A"})
    if (list.findChannel(n)) names.emplace_back(n);
  for (auto it = list.begin(); it != list.end(); ++it)
    if (std::find(names.begin(), names.end(), it.name()) == names.end()) rest.emplace_back(it.name());
  names.insert(names.end(), rest.begin(), rest.end());
  return names;
}

}  // namespace

std::unique_ptr<ScanlineOutput> open_exr(const std::string& file, int width, int height, int channels,
                                         ExrCompression compression) {
  return rethrow([&] { return std::make_unique<ExrOutput>(file, width, height, channels, compression); });
}

Header exr_header(const std::string& file) {
  return rethrow([&] {
    Imf::InputFile in(file.c_str());
    const Imath::Box2i dw = in.header().dataWindow();
    return Header{dw.max.x - dw.min.x + 1, dw.max.y - dw.min.y + 1,
                  static_cast<int>(ordered_channels(in.header().channels()).size()), "openexr"};
  });
}

ImageBuffer read_exr(const std::string& file) {
  return rethrow([&] {
    Imf::InputFile in(file.c_str(), exr_threads());
    const Imath::Box2i dw = in.header().dataWindow();
    const std::vector<std::string> names = ordered_channels(in.header().channels());
    ImageBuffer img(dw.max.x - dw.min.x + 1, dw.max.y - dw.min.y + 1, static_cast<int>(names.size()));
    const size_t xs = sizeof(float) * names.size(), ys = xs * size_t(img.width);
    char* base = reinterpret_cast<char*>(img.data.data()) - ptrdiff_t(xs) * dw.min.x - ptrdiff_t(ys) * dw.min.y;
    Imf::FrameBuffer fb;
    for (size_t c = 0; c < names.size(); ++c) fb.insert(names[c], Imf::Slice(Imf::FLOAT, base + sizeof(float) * c, xs, ys));
    in.setFrameBuffer(fb);
    in.readPixels(dw.min.y, dw.max.y);
    return img;
  });
}

}  // namespace holoray::formats
