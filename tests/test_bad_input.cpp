// The bad-input suite (issue 5): every case of tests/data/bad_inputs.toml runs
// the CLI in a fresh folder and must exit with its status and print its
// message as a whole line; docs/errors.md holds the same cases as a table and
// must agree with the file (HOLORAY_UPDATE_DOCS=1 rewrites the table).
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <toml++/toml.h>

#include "test_util.hpp"

namespace holoray {
namespace {

struct BadInputCase {
  std::string id, what, command, message;
  std::vector<std::pair<std::string, std::string>> files;  // name, contents (placeholders expanded)
  std::string garbage;                                    // file of 4 KiB of random bytes, if any
  int status = 1;
  int file_size_limit_kib = 0;
  bool prefix = false;  // the message's end depends on the machine: match the start of a line
};

const std::string kCasesFile = std::string(HOLORAY_SOURCE_DIR) + "/tests/data/bad_inputs.toml";
const std::string kDocFile = std::string(HOLORAY_SOURCE_DIR) + "/docs/errors.md";

std::string expand(std::string s, const toml::table& defaults) {
  for (const auto& [key, value] : defaults) {
    const std::string mark = "{" + std::string(key.str()) + "}";
    const std::string v = value.value_or(std::string());
    for (size_t at; (at = s.find(mark)) != std::string::npos;) s.replace(at, mark.size(), v);
  }
  return s;
}

std::vector<BadInputCase> load_cases() {
  std::vector<BadInputCase> out;
  toml::table root;
  try {
    root = toml::parse_file(kCasesFile);
  } catch (const toml::parse_error& e) {
    ADD_FAILURE() << kCasesFile << ": " << e.description();
    return out;
  }
  const toml::table defaults = root["defaults"].as_table() ? *root["defaults"].as_table() : toml::table{};
  if (const toml::array* cases = root["case"].as_array())
    for (const toml::node& n : *cases) {
      const toml::table& t = *n.as_table();
      BadInputCase c;
      c.id = t["id"].value_or(std::string());
      c.what = t["class"].value_or(std::string());
      c.command = expand(t["command"].value_or(std::string()), defaults);
      c.message = t["message"].value_or(std::string());
      c.garbage = t["garbage"].value_or(std::string());
      c.status = t["status"].value_or(1);
      c.file_size_limit_kib = t["file_size_limit_kib"].value_or(0);
      c.prefix = t["prefix"].value_or(false);
      if (const toml::table* files = t["files"].as_table())
        for (const auto& [name, contents] : *files)
          c.files.emplace_back(std::string(name.str()), expand(contents.value_or(std::string()), defaults));
      out.push_back(std::move(c));
    }
  return out;
}

const std::vector<BadInputCase>& cases() {
  static const std::vector<BadInputCase> all = load_cases();
  return all;
}

class BadInput : public ::testing::TestWithParam<size_t> {};

TEST_P(BadInput, ExitsWithItsStatusAndMessage) {
  const BadInputCase& c = cases()[GetParam()];
  ASSERT_FALSE(c.message.empty()) << c.id << ": no message in " << kCasesFile;
  test::TempDir dir;
  for (const auto& [name, contents] : c.files) test::write_text(dir.file(name), contents);
  if (!c.garbage.empty()) {
    std::mt19937 rng(1);
    std::string bytes(4096, '\0');
    for (char& b : bytes) b = static_cast<char>(rng() & 0xff);
    test::write_text(dir.file(c.garbage), bytes);
  }
  // /bin/sh's ulimit -f counts 512-byte blocks; an ignored SIGXFSZ makes the
  // write fail with an error instead of killing the process, as a full disk does.
  const std::string limit =
      c.file_size_limit_kib ? fmt::format("trap '' XFSZ; ulimit -f {}; ", 2 * c.file_size_limit_kib) : std::string();
  const auto r = test::run_shell(fmt::format("cd '{}' && {}{} {}", dir.path.string(), limit, HOLORAY_CLI, c.command));
  const std::string& output = r.output;
  ASSERT_NE(r.status, -1) << c.id << " did not exit normally (crashed?)\n" << output;
  EXPECT_EQ(r.status, c.status) << output;
  std::istringstream lines(output);
  bool found = false;
  for (std::string line; std::getline(lines, line);)
    found = found || line == c.message || (c.prefix && line.starts_with(c.message));
  EXPECT_TRUE(found) << "expected the line\n  " << c.message << "\nin\n" << output;
}

INSTANTIATE_TEST_SUITE_P(Cases, BadInput, ::testing::Range<size_t>(0, cases().size()),
                         [](const auto& info) { return cases()[info.param].id; });

// --- docs/errors.md ---

std::string cell(std::string s) {
  for (size_t at; (at = s.find('|')) != std::string::npos;) s.replace(at, 1, "\\|");
  return s;
}

// A code span that survives backticks inside it.
std::string code(const std::string& s) { return s.find('`') == std::string::npos ? "`" + s + "`" : "`` " + s + " ``"; }

std::string shown_input(const BadInputCase& c, const std::string& head) {
  std::string s;
  for (const auto& [name, contents] : c.files) {
    std::string body = contents;
    if (!head.empty() && body.starts_with(head)) body = "(viewpoint, light, material) " + body.substr(head.size());
    while (!body.empty() && body.back() == '\n') body.pop_back();
    for (size_t at; (at = body.find('\n')) != std::string::npos;) body.replace(at, 1, " ⏎ ");
    if (body.size() > 90) body = body.substr(0, 87) + "...";
    s += fmt::format("{}`{}`: `{}`", s.empty() ? "" : "<br>", name, body);
  }
  if (!c.garbage.empty()) s += fmt::format("{}`{}`: 4 KiB of random bytes", s.empty() ? "" : "<br>", c.garbage);
  if (c.file_size_limit_kib) s += fmt::format("{}file size limit {} KiB", s.empty() ? "" : "<br>", c.file_size_limit_kib);
  return s.empty() ? "(none)" : cell(s);
}

std::string errors_table() {
  toml::table root = toml::parse_file(kCasesFile);
  const std::string head = root["defaults"]["scene_head"].value_or(std::string());
  std::string t = "| # | Bad input | Files | Command (`holoray ...`) | Message (first line) | Exit |\n|---|---|---|---|---|---|\n";
  int k = 0;
  for (const BadInputCase& c : cases())
    t += fmt::format("| {} | {} | {} | {} | {}{} | {} |\n", ++k, cell(c.what), shown_input(c, head), code(cell(c.command)),
                     code(cell(c.message)), c.prefix ? " ..." : "", c.status);
  return t;
}

TEST(ErrorsDoc, TableListsEveryBadInputCase) {
  std::ifstream in(kDocFile);
  ASSERT_TRUE(in) << kDocFile;
  std::string doc((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string begin = "<!-- cases:begin -->\n", end = "<!-- cases:end -->";
  const size_t b = doc.find(begin), e = doc.find(end);
  ASSERT_TRUE(b != std::string::npos && e != std::string::npos && b < e) << "markers missing in " << kDocFile;
  const std::string table = errors_table();
  const std::string current = doc.substr(b + begin.size(), e - b - begin.size());
  if (current != table && std::getenv("HOLORAY_UPDATE_DOCS")) {
    doc.replace(b + begin.size(), e - b - begin.size(), table);
    std::ofstream(kDocFile, std::ios::binary) << doc;
    return;
  }
  EXPECT_EQ(current, table) << "docs/errors.md is out of date with tests/data/bad_inputs.toml; rerun the test with "
                               "HOLORAY_UPDATE_DOCS=1 to rewrite the table";
}

}  // namespace
}  // namespace holoray
