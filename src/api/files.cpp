// The public text-file writer (holoray/files.hpp).
#include "holoray/files.hpp"

#include "scene/file_text.hpp"

namespace holoray::api {

void write_text_file(const std::string& path, const std::string& text) { holoray::write_text_file(path, text); }

}  // namespace holoray::api
