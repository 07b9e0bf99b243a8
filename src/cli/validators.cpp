#include "cli/validators.hpp"

#include <fmt/format.h>

#include <charconv>
#include <filesystem>
#include <stdexcept>

#include "holoray/image.hpp"

namespace holoray::cli {

CLI::Validator one_of(std::vector<std::string> names) {
  std::string list, help;
  for (size_t k = 0; k < names.size(); ++k) {
    list += k == 0 ? "" : k + 1 == names.size() ? " or " : ", ";
    list += names[k];
    help += (k == 0 ? "" : "|") + names[k];
  }
  return CLI::Validator(
      [names, list](std::string& value) -> std::string {
        for (const std::string& n : names)
          if (value == n) return "";
        return fmt::format("expected {}, got '{}'", list, value);
      },
      help, "one_of");
}

CLI::Validator in_range(double lo, double hi, bool hi_open, std::string unit) {
  const std::string u = unit.empty() ? "" : " " + unit;
  const std::string bounds = std::isinf(hi) ? fmt::format("at least {}{}", lo, u)
                                            : fmt::format("from {} to {}{}", lo, hi, u);
  return CLI::Validator(
      [=](std::string& value) -> std::string {
        double v = 0;
        const auto r = std::from_chars(value.data(), value.data() + value.size(), v);
        const bool number = !value.empty() && r.ec == std::errc() && r.ptr == value.data() + value.size();
        if (!number) return fmt::format("expected a number {}, got '{}'", bounds, value);
        if (v >= lo && (hi_open ? v < hi : v <= hi)) return "";
        return fmt::format("must be {}, got {}", bounds, value);
      },
      bounds, "in_range");
}

CLI::Validator parsed_by(std::function<void(const std::string&)> parse, std::string description) {
  return CLI::Validator(
      [parse](std::string& value) -> std::string {
        try {
          parse(value);
          return "";
        } catch (const std::invalid_argument& e) {
          const std::string m = e.what();
          // "--lenses: expected ..." -> "expected ...": CLI11 names the option.
          const auto colon = m.find(": ");
          // The API's "`device`: expected ..." likewise.
          const bool named = m.rfind("-", 0) == 0 || m.rfind("`", 0) == 0;
          return named && colon != std::string::npos ? m.substr(colon + 2) : m;
        }
      },
      description, "parsed_by");
}

CLI::Validator existing_file() {
  return CLI::Validator(
      [](std::string& path) -> std::string {
        std::error_code ec;
        if (std::filesystem::is_directory(path, ec)) return fmt::format("cannot read '{}': it is a folder", path);
        if (!std::filesystem::exists(path, ec)) return fmt::format("cannot read '{}': no such file", path);
        return "";
      },
      "FILE", "existing_file");
}

CLI::Validator output_image() {
  return CLI::Validator(
      [](std::string& path) -> std::string {
        if (!api::is_image_output(path)) return fmt::format("unsupported output '{}' (use .png or .exr)", path);
        const std::filesystem::path dir = std::filesystem::path(path).parent_path();
        std::error_code ec;
        if (!dir.empty() && !std::filesystem::is_directory(dir, ec))
          return std::filesystem::exists(dir, ec) ? fmt::format("'{}' is not a folder", dir.string())
                                                  : fmt::format("folder '{}' does not exist", dir.string());
        return "";
      },
      "OUT.png|OUT.exr", "output_image");
}

void lay_out_help(CLI::App& cmd, const std::vector<std::pair<std::string, std::vector<std::string>>>& groups,
                  const std::vector<std::string>& examples, const std::string& guide_page) {
  for (const auto& [heading, names] : groups)
    for (const std::string& name : names) cmd.get_option(name)->group(heading);
  std::string footer = "\nExamples:\n";
  for (const std::string& e : examples) footer += "  " + e + "\n";
  footer += "\nMore in the user guide: " + guide_page;
  cmd.footer(footer);
}

}  // namespace holoray::cli
