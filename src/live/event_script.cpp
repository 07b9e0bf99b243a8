#include "live/event_script.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <fstream>
#include <system_error>

#include "scene/parse_error.hpp"

namespace holoray::live {

namespace {

constexpr const char* kKeys[] = {"Up",    "Down", "Left",   "Right", "A",        "V",      "S",
                                 "shift+S", "Space", "PageDown", "PageUp", "Home", "Escape", "Q"};

struct Token {
  std::string text;
  int col = 0;  // 1-based
};

std::vector<Token> split(const std::string& line) {
  std::vector<Token> out;
  const size_t end = std::min(line.find('#'), line.size());
  size_t k = 0;
  while (k < end) {
    while (k < end && std::isspace(static_cast<unsigned char>(line[k]))) ++k;
    const size_t start = k;
    while (k < end && !std::isspace(static_cast<unsigned char>(line[k]))) ++k;
    if (k > start) out.push_back({line.substr(start, k - start), int(start) + 1});
  }
  return out;
}

}  // namespace

bool is_live_key(const std::string& name) { return std::find(std::begin(kKeys), std::end(kKeys), name) != std::end(kKeys); }

std::vector<ScriptedEvent> read_event_script(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::system_error(errno, std::generic_category(), fmt::format("cannot read '{}'", path));
  std::vector<ScriptedEvent> out;
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    const std::vector<Token> t = split(line);
    if (t.empty()) continue;
    auto fail = [&](const Token* at, const std::string& expected) -> ScriptedEvent {
      const int col = at ? at->col : int(line.size()) + 1;
      throw ParseError(path, {number, col},
                       fmt::format("expected {}, found {}", expected, at ? fmt::format("'{}'", at->text) : "the line's end"), line);
    };
    auto number_at = [&](size_t k, const char* what) {
      if (k >= t.size()) fail(nullptr, what);
      double v = 0;
      const std::string& s = t[k].text;
      const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
      if (ec != std::errc() || end != s.data() + s.size() || !std::isfinite(v)) fail(&t[k], what);
      return v;
    };
    ScriptedEvent e;
    const double frame = number_at(0, "a frame number (1 or more)");
    if (frame < 1 || frame != std::floor(frame) || frame > 1e9) fail(&t[0], "a frame number (1 or more)");
    e.frame = int(frame);
    if (!out.empty() && e.frame < out.back().frame)
      fail(&t[0], fmt::format("a frame number of {} or more (frames ascend)", out.back().frame));
    if (t.size() < 2) fail(nullptr, "an event: orbit, pan, pointer, wheel or key");
    const std::string& kind = t[1].text;
    size_t arguments = 0;
    if (kind == "orbit" || kind == "pan" || kind == "pointer") {
      e.event.kind = kind == "orbit" ? InputEvent::Kind::orbit : kind == "pan" ? InputEvent::Kind::pan : InputEvent::Kind::pointer;
      const bool at = kind == "pointer";
      e.event.dx = number_at(2, at ? "X, pixels from the left" : "DX, pixels");
      e.event.dy = number_at(3, at ? "Y, pixels from the top" : "DY, pixels");
      arguments = 2;
    } else if (kind == "wheel") {
      e.event.kind = InputEvent::Kind::wheel;
      e.event.dy = number_at(2, "wheel clicks (up > 0)");
      arguments = 1;
    } else if (kind == "key") {
      e.event.kind = InputEvent::Kind::key;
      if (t.size() < 3 || !is_live_key(t[2].text))
        fail(t.size() < 3 ? nullptr : &t[2], fmt::format("a key: {}", fmt::join(kKeys, ", ")));
      e.event.key = t[2].text;
      arguments = 1;
    } else {
      fail(&t[1], "an event: orbit, pan, pointer, wheel or key");
    }
    if (t.size() > 2 + arguments) fail(&t[2 + arguments], "the line's end");
    out.push_back(e);
  }
  return out;
}

}  // namespace holoray::live
