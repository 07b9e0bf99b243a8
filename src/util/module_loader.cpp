#include "util/module_loader.hpp"

#include <dlfcn.h>
#include <fmt/format.h>

#include <filesystem>
#include <map>
#include <mutex>
#include <stdexcept>
#include <vector>

namespace holoray {

void* module_symbol(const std::string& file, const std::string& built, const char* symbol, const std::string& missing) {
  static std::mutex mutex;
  // Per module and symbol: its address, or why there is none (kept: a
  // second call gives the first one's answer without trying again).
  static std::map<std::string, std::pair<void*, std::string>> found;
  const std::lock_guard lock(mutex);
  auto [it, first] = found.try_emplace(file + ":" + symbol);
  auto& [address, why] = it->second;
  if (first) {
    std::vector<std::string> candidates;
    std::error_code ec;
    const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (!ec) candidates.push_back((exe.parent_path().parent_path() / "lib/holoray" / file).string());
    if (!built.empty()) candidates.push_back(built);
    why = fmt::format("{} (looked for {})", missing, fmt::join(candidates, ", "));
    for (const std::string& path : candidates) {
      if (!std::filesystem::exists(path, ec)) continue;
      void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
      if (!handle) {
        why = dlerror();
        break;
      }
      address = dlsym(handle, symbol);
      why = address ? "" : fmt::format("'{}' has no {}", path, symbol);
      break;
    }
  }
  if (!address) throw std::runtime_error(why);
  return address;
}

}  // namespace holoray
