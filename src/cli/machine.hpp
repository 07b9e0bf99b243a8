// holoray/cli: facts about this machine the commands print or check against.
#pragma once

#include <cstdint>
#include <string>

namespace holoray::cli {

/// Installed memory in bytes; 0 when unknown.
uint64_t physical_memory_bytes();
/// "N cores, CPU model" for reports.
std::string machine_description();

}  // namespace holoray::cli
