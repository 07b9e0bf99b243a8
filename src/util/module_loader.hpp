// holoray/util: holoray's own modules (holoray_ffmpeg.so, holoray_glfw.so),
// loaded on first use so that no other command and no library user loads
// their libraries: found beside an installed binary in ../lib/holoray, else
// where the build put them.
#pragma once

#include <string>

namespace holoray {

/// The address of `symbol` in the module `file` (a file name such as
/// "holoray_glfw.so"), the module opened once per process (RTLD_LOCAL: its
/// libraries' symbols stay inside it). `built`: where the build put it
/// ("" for nowhere). Throws std::runtime_error: `missing` and the places
/// looked in when neither holds it, dlopen's reason when it cannot be loaded, or that it
/// lacks the symbol. Thread-safe.
void* module_symbol(const std::string& file, const std::string& built, const char* symbol, const std::string& missing);

}  // namespace holoray
