#include "live/offscreen_window.hpp"

#include <stdexcept>

namespace holoray::live {

namespace {

class OffscreenWindow final : public Window {
 public:
  explicit OffscreenWindow(std::array<int, 2> size) : size_(size) {}
  std::vector<std::string> instance_extensions() const override { return {}; }
  uint64_t create_surface(void*) override { throw std::logic_error("an offscreen window has no surface"); }
  std::array<int, 2> framebuffer_size() const override { return size_; }
  void set_title(const std::string&) override {}
  bool closed() const override { return closed_; }
  void close() override { closed_ = true; }
  // Nothing to wait for: the loop's input is its event script.
  std::vector<InputEvent> events(bool) override { return {}; }
  void wake() override {}

 private:
  std::array<int, 2> size_;
  bool closed_ = false;
};

}  // namespace

std::unique_ptr<Window> offscreen_window(const WindowRequest& request) {
  if (request.width < 1 || request.height < 1) throw std::invalid_argument("an offscreen window needs a size");
  return std::make_unique<OffscreenWindow>(std::array<int, 2>{request.width, request.height});
}

}  // namespace holoray::live
