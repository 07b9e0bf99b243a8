// One rule for an `up` direction (math/vec.hpp, up_orients): an NFF file, a
// Tachyon file, a shot file's camera key, a Tachyon camera path and the API
// accept and refuse the same viewpoints, at the tolerance the array's frame
// needs (issue 54: five checks had three tolerances).
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>

#include "holoray/scene.hpp"
#include "scene/nff_reader.hpp"
#include "shot/camera_path.hpp"
#include "shot/shot_reader.hpp"
#include "test_util.hpp"

namespace holoray {
namespace {

// `up` tilted `tilt` radians from the view direction (0, 0, -1).
std::string up_at(double tilt) { return fmt::format("{:.17g} 0 {:.17g}", std::sin(tilt), -std::cos(tilt)); }

// Whether `read` takes the viewpoint without throwing.
bool accepts(const std::function<void()>& read) {
  try {
    read();
    return true;
  } catch (const std::exception&) {
    return false;
  }
}

bool nff_accepts(double tilt) {
  return accepts([&] {
    parse_nff("v\nfrom 0 0 5\nat 0 0 0\nup " + up_at(tilt) + "\nangle 40\nhither 1\nresolution 8 8\ns 0 0 0 1\n", "s.nff");
  });
}

bool shot_accepts(double tilt) {
  std::string up = up_at(tilt);
  std::replace(up.begin(), up.end(), ' ', ',');
  return accepts([&] {
    parse_shot("frames = 1\n[camera]\n[[camera.key]]\nframe = 0\nfrom = [0, 0, 5]\nat = [0, 0, 0]\nup = [" + up +
                   "]\n[[object]]\nscene = 'a.nff'\n",
               "s.toml");
  });
}

bool path_accepts(double tilt) {
  return accepts([&] { parse_camera_path("0 0 -1 " + up_at(tilt) + " 0 0 5\n", "p.cam"); });
}

bool api_accepts(double tilt) {
  return accepts([&] {
    api::Scene s;
    s.set_viewpoint({0, 0, 5}, {0, 0, 0}, {std::sin(tilt), 0, -std::cos(tilt)}, 40);
  });
}

TEST(UpDirection, EveryReaderAndTheApiDrawTheSameLine) {
  for (double tilt : {0.0, 1e-12, 1e-10, 1e-7, 1e-3, 0.5}) {
    const bool usable = tilt > 1e-9;
    EXPECT_EQ(nff_accepts(tilt), usable) << "NFF, tilt " << tilt;
    EXPECT_EQ(shot_accepts(tilt), usable) << "shot, tilt " << tilt;
    EXPECT_EQ(path_accepts(tilt), usable) << "camera path, tilt " << tilt;
    EXPECT_EQ(api_accepts(tilt), usable) << "API, tilt " << tilt;
  }
}

}  // namespace
}  // namespace holoray
