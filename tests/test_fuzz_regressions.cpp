// Replays every input saved in fuzz/regressions/<target>/ through the same
// fuzz target body (fuzz/fuzz_targets.hpp): a finding fixed once stays fixed,
// in the plain build and in the sanitizer build alike. Each body throws only
// the reader's documented error type; anything else fails here.
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "../fuzz/fuzz_targets.hpp"
#include "test_util.hpp"

namespace holoray {
namespace {

std::vector<std::filesystem::path> saved_inputs(const std::string& target) {
  std::vector<std::filesystem::path> files;
  const auto dir = std::filesystem::path(test::source_dir()) / "fuzz" / "regressions" / target;
  if (std::filesystem::is_directory(dir))
    for (const auto& e : std::filesystem::directory_iterator(dir))
      if (e.is_regular_file()) files.push_back(e.path());
  return files;
}

template <class Body>
void replay(const std::string& target, Body body) {
  const auto files = saved_inputs(target);
  for (const auto& f : files) {
    SCOPED_TRACE(f.string());
    const std::string bytes = test::read_bytes(f.string());
    EXPECT_NO_THROW(body(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size()));
  }
  ::testing::Test::RecordProperty("inputs", static_cast<int>(files.size()));
}

TEST(FuzzRegressions, NffInputsParseOrFailWithParseError) { replay("nff", fuzz::nff); }
TEST(FuzzRegressions, TachyonInputsParseOrFailWithParseError) { replay("tachyon", fuzz::tachyon); }
TEST(FuzzRegressions, ShotInputsParseOrFailWithTheirErrors) { replay("shot", fuzz::shot); }
TEST(FuzzRegressions, CameraPathInputsParseOrFailWithParseError) { replay("camera_path", fuzz::camera_path); }
TEST(FuzzRegressions, DisplayInputsParseOrFailWithParseError) { replay("display", fuzz::display); }
TEST(FuzzRegressions, GltfInputsReadOrFailWithRuntimeError) { replay("gltf", fuzz::gltf); }

}  // namespace
}  // namespace holoray
