// The one error rule (include/holoray/errors.hpp): every malformed input file
// is a SceneError naming the file, whichever reader found it; a file that
// cannot be read is a std::system_error carrying its errno.
#include <gtest/gtest.h>

#include <cerrno>
#include <string>
#include <system_error>

#include "holoray/errors.hpp"
#include "holoray/scene.hpp"
#include "test_util.hpp"

namespace holoray {
namespace {

// The error a load throws, caught as the type the rule names.
template <class Error>
Error load_error(const std::string& path) {
  try {
    (void)api::Scene::load(path);
  } catch (const Error& e) {
    return e;
  }
  ADD_FAILURE() << "'" << path << "' loaded without the expected error";
  throw std::logic_error("no error");
}

TEST(ErrorRule, MeshFileTheLibraryRefusesIsASceneErrorNamingIt) {
  test::TempDir dir;
  const std::string path = dir.file("bad.obj");
  test::write_text(path, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");  // vertex 9 of 3
  const api::SceneError e = load_error<api::SceneError>(path);
  EXPECT_EQ(e.file(), path);
  EXPECT_EQ(e.line(), 0);
  EXPECT_EQ(std::string(e.what()), "cannot read '" + path + "': " + e.message());
}

TEST(ErrorRule, MeshFileOurChecksRefuseIsASceneErrorNamingIt) {
  test::TempDir dir;
  const std::string path = dir.file("m.gltf");
  test::write_text(path, R"({"asset": {"version": "2.0"}, "accessors": [{"componentType": 5126, "count": 0, "type": "SCALAR"}]})");
  const api::SceneError e = load_error<api::SceneError>(path);
  EXPECT_EQ(e.file(), path);
  EXPECT_EQ(e.message(), "/accessors/0/count must be an integer of at least 1");
}

TEST(ErrorRule, SyntaxErrorIsASceneErrorWithItsPosition) {
  test::TempDir dir;
  const std::string path = dir.file("s.nff");
  test::write_text(path, "s 0 0 0\n");
  const api::SceneError e = load_error<api::SceneError>(path);
  EXPECT_EQ(e.file(), path);
  EXPECT_EQ(e.line(), 1);
  EXPECT_GT(e.column(), 0);
}

TEST(ErrorRule, MissingFileIsAnIoErrorWithItsErrno) {
  test::TempDir dir;
  for (const char* name : {"nothere.nff", "nothere.dat", "nothere.obj", "nothere.gltf"}) {
    const std::system_error e = load_error<std::system_error>(dir.file(name));
    EXPECT_EQ(e.code(), std::errc::no_such_file_or_directory) << name;
    EXPECT_EQ(std::string(e.what()), "cannot read '" + dir.file(name) + "': " + e.code().message()) << name;
  }
}

TEST(ErrorRule, FolderIsAnIoErrorNotASceneError) {
  test::TempDir dir;
  const std::system_error e = load_error<std::system_error>(dir.path.string());
  EXPECT_EQ(e.code(), std::errc::is_a_directory);
}

}  // namespace
}  // namespace holoray
