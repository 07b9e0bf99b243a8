// How a PNG's zlib level, strategy and row filter trade file size against
// writing time on real EIAs, and what deflating in segments on every core
// (level1_none_segmented) gains (the choice in src/image/png_format.cpp).
// Usage: png_encode IMAGE.exr...   (Google Benchmark flags first)
// Each image is encoded to PNG in memory-backed /tmp with every setting;
// the counters give the file's bytes and its ratio to the raw 8-bit size.
#include <benchmark/benchmark.h>
#include <png.h>
#include <zlib.h>

#include <filesystem>
#include <string>
#include <vector>

#include "image/formats.hpp"
#include "image/image_io.hpp"

namespace {

struct Setting {
  const char* name;
  holoray::formats::PngCompression compression;
};

const Setting kSettings[] = {
    {"level0_none", {0, Z_DEFAULT_STRATEGY, PNG_FILTER_NONE}},
    {"level1_none", {1, Z_DEFAULT_STRATEGY, PNG_FILTER_NONE}},
    {"level1_none_segmented", {1, Z_DEFAULT_STRATEGY, PNG_FILTER_NONE, size_t{256} << 10}},
    {"level1_rle_none", {1, Z_RLE, PNG_FILTER_NONE}},
    {"level1_rle_sub", {1, Z_RLE, PNG_FILTER_SUB}},
    {"level1_huffman_sub", {1, Z_HUFFMAN_ONLY, PNG_FILTER_SUB}},
    {"level1_sub", {1, Z_DEFAULT_STRATEGY, PNG_FILTER_SUB}},
    {"level1_up", {1, Z_DEFAULT_STRATEGY, PNG_FILTER_UP}},
    {"level1_paeth", {1, Z_DEFAULT_STRATEGY, PNG_FILTER_PAETH}},
    {"level3_none", {3, Z_DEFAULT_STRATEGY, PNG_FILTER_NONE}},
    {"level6_all", {6, Z_DEFAULT_STRATEGY, PNG_ALL_FILTERS}},  // libpng's defaults
};

void encode(benchmark::State& state, const holoray::ImageBuffer* image, holoray::formats::PngCompression c) {
  const std::string out = (std::filesystem::temp_directory_path() / "holoray_png_encode.png").string();
  for (auto _ : state) {
    auto png = holoray::formats::open_png(out, image->width, image->height, image->channels, holoray::Encoding::linear, c);
    png->write_rows(image->data.data(), image->height);
    png->close();
  }
  const double bytes = static_cast<double>(std::filesystem::file_size(out));
  state.counters["bytes"] = bytes;
  state.counters["of_raw"] = bytes / static_cast<double>(image->data.size());
  std::filesystem::remove(out);
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  std::vector<holoray::ImageBuffer> images;
  images.reserve(static_cast<size_t>(argc));
  for (int i = 1; i < argc; ++i) {
    images.push_back(holoray::read_image(argv[i]));
    const std::string stem = std::filesystem::path(argv[i]).stem().string();
    for (const Setting& s : kSettings)
      benchmark::RegisterBenchmark((stem + "/" + s.name).c_str(), encode, &images.back(), s.compression)
          ->Unit(benchmark::kMillisecond);
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
}
