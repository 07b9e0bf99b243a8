#include "shot/camera_path.hpp"

#include <fmt/format.h>

#include <cmath>

#include "scene/file_text.hpp"
#include "scene/tokenizer.hpp"

namespace holoray {

namespace {
constexpr size_t kMaxPathFrames = 10'000'000;
}

std::vector<CameraPathFrame> parse_camera_path(std::string_view text, const std::string& source) {
  Tokenizer tok(text, source);
  std::vector<CameraPathFrame> frames;
  static constexpr const char* kField[9] = {"view x", "view y", "view z", "up x", "up y", "up z",
                                            "centre x", "centre y", "centre z"};
  while (!tok.at_end()) {
    if (frames.size() >= kMaxPathFrames)
      tok.fail(tok.peek().loc, fmt::format("more than {} frames in one camera path", kMaxPathFrames));
    const Token first = tok.peek();
    double v[9];
    for (int k = 0; k < 9; ++k) {
      const Token& t = tok.peek();
      if (k > 0 && (t.text.empty() || t.loc.line != first.loc.line))
        tok.fail(t.text.empty() ? tok.end_loc() : t.loc,
                 fmt::format("expected 9 numbers on line {} (view direction, up direction, centre), found {}",
                             first.loc.line, k));
      v[k] = tok.number(kField[k]);
    }
    CameraPathFrame f{{v[0], v[1], v[2]}, {v[3], v[4], v[5]}, {v[6], v[7], v[8]}, first.loc};
    if (length(f.view) == 0) tok.fail(first.loc, "the view direction is zero");
    if (!up_orients(f.view, f.up))
      tok.fail(first.loc, "the up direction is zero or parallel to the view direction");
    if (!tok.at_end() && tok.peek().loc.line == first.loc.line)
      tok.fail(tok.peek().loc, fmt::format("expected the end of line {} after 9 numbers, found {}", first.loc.line,
                                           describe_token(tok.peek())));
    frames.push_back(f);
  }
  if (frames.empty()) tok.fail(tok.end_loc(), "expected at least one frame (9 numbers), found end of file");
  return frames;
}

std::vector<CameraPathFrame> read_camera_path(const std::string& path) {
  return parse_camera_path(read_text_file(path), path);
}

}  // namespace holoray
