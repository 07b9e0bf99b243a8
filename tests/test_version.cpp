// The front door: `holoray --version`, and the bash completion that the build
// makes from the CLI11 definition (`holoray --completion bash`), checked
// against what --help shows.
#include <gtest/gtest.h>

#include <iterator>
#include <regex>
#include <set>
#include <sstream>

#include "test_util.hpp"

using namespace holoray;

namespace {

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

// The words the completion script offers after `holoray COMMAND -`: its
// `COMMAND) options="..."` line.
std::set<std::string> completion_options(const std::string& script, const std::string& command) {
  std::smatch m;
  const std::regex line("\n +" + command + "\\) options=\"([^\"]*)\"");
  if (!std::regex_search(script, m, line)) return {};
  std::istringstream words(m[1].str());
  return {std::istream_iterator<std::string>(words), std::istream_iterator<std::string>()};
}

}  // namespace

TEST(Version, NamesReleaseCommitAndLibraries) {
  const auto r = test::run_cli("--version");
  ASSERT_EQ(r.status, 0) << r.output;
  const auto l = lines(r.output);
  ASSERT_EQ(l.size(), 2u) << r.output;
  EXPECT_TRUE(std::regex_match(l[0], std::regex(R"(holoray [0-9]+\.[0-9]+\.[0-9]+ \(git ([0-9a-f]+(-dirty)?|unknown)\))")))
      << l[0];
  EXPECT_TRUE(l[1].starts_with("built with: MPI ")) << l[1];
  EXPECT_TRUE(std::regex_search(l[1], std::regex(R"(Embree [0-9]+\.[0-9]+\.[0-9]+)"))) << l[1];
  for (const char* lib : {"oneTBB ", "libpng ", "OpenEXR ", "assimp ", "FFmpeg ", "fmt ", "CLI11 "})
    EXPECT_NE(l[1].find(lib), std::string::npos) << lib;
}

TEST(Completion, OffersEverySubcommandAndTheirOptions) {
  const auto r = test::run_cli("--completion bash");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("complete -F _holoray holoray"), std::string::npos);
  for (const char* c : {"render", "subaperture", "animate", "compare", "simulate", "interlace", "views"})
    EXPECT_FALSE(completion_options(r.output, c).empty()) << c;
  EXPECT_TRUE(completion_options(r.output, "render").contains("--pixels-per-lens"));
  EXPECT_TRUE(completion_options(r.output, "''").contains("--version"));
  // Hidden: not in --help, not offered.
  EXPECT_FALSE(completion_options(r.output, "''").contains("--completion"));
  EXPECT_EQ(test::run_cli("--help").output.find("--completion"), std::string::npos);
  EXPECT_EQ(test::run_cli("--completion zsh").status, 2);
}

// Generated from the same option list: whatever `holoray CMD --help` shows,
// the completion offers for CMD (and nothing it does not show).
TEST(Completion, MatchesEachCommandsHelp) {
  const std::string script = test::run_cli("--completion bash").output;
  for (const char* c : {"render", "subaperture", "animate", "compare", "simulate", "interlace", "views"}) {
    const auto help = test::run_cli(std::string(c) + " --help");
    ASSERT_EQ(help.status, 0) << help.output;
    std::set<std::string> shown;
    const std::regex option(R"((^|[ ,])(--?[A-Za-z][-A-Za-z0-9]*))");
    for (const std::string& l : lines(help.output)) {
      // An option's own line: two spaces, then its names (the description
      // after it may name other options, as does "Excludes:").
      if (!l.starts_with("  -")) continue;
      const std::string names = l.substr(2, l.find_first_of(" ", 2) - 2);
      for (std::sregex_iterator i(names.begin(), names.end(), option), end; i != end; ++i) shown.insert((*i)[2]);
    }
    EXPECT_FALSE(shown.empty()) << c;
    EXPECT_EQ(completion_options(script, c), shown) << c;
  }
}

// The script in bash itself: `holoray ren<TAB>`, `holoray render --pix<TAB>`,
// and file names after the command.
TEST(Completion, CompletesInBash) {
  test::TempDir dir;
  test::write_text(dir.file("script.bash"), test::run_cli("--completion bash").output);
  test::write_text(dir.file("scene.nff"), "");
  const auto complete = [&](const std::string& words) {
    return test::run_shell("cd " + dir.path.string() + " && bash -c '. script.bash; COMP_WORDS=(" + words +
                           "); COMP_CWORD=$((${#COMP_WORDS[@]} - 1)); _holoray; echo \"${COMPREPLY[*]}\"'");
  };
  EXPECT_EQ(complete("holoray ren").output, "render\n");
  EXPECT_EQ(complete("holoray render --pix").output, "--pixels-per-lens\n");
  EXPECT_EQ(complete("holoray render sce").output, "scene.nff\n");
  EXPECT_EQ(complete("holoray --vers").output, "--version\n");
}
