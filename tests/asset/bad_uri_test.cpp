// Bad input, part 3: buffer and image URIs that would read outside the asset's
// folder. Assets come from strangers: a .gltf must not be able to read
// /etc/passwd or ~/.ssh, whatever spelling it uses.
#include <filesystem>

#include <gtest/gtest.h>

#include "gltf_fixture.h"
#include "loader_checks.h"

namespace crowdprof::test {
namespace {
namespace fs = std::filesystem;

// A fixture in <scratch>/<test>/asset/ whose buffer URI is `uri`; a real copy of
// the buffer sits one folder up as ../secret.bin, so ".." would succeed if allowed.
std::string with_buffer_uri(const std::string& test, const std::string& uri) {
  fs::path dir = scratch_dir(test) / "asset";
  fs::create_directories(dir);
  SkinnedFixture f;
  write_file(dir.parent_path() / "secret.bin", f.bin.data(), f.bin.size());
  f.json["buffers"] = {{{"byteLength", f.bin.size()}, {"uri", uri}}};
  f.write_gltf(dir / "character.gltf");
  return (dir / "character.gltf").string();
}

TEST(BadUri, BufferUriWithDotDot) {
  expect_bad_input(with_buffer_uri("uri_dotdot", "../secret.bin"),
                   {"buffer 0 URI \"../secret.bin\"", "outside the asset's folder"});
  expect_bad_input(with_buffer_uri("uri_dotdot_inner", "sub/../../secret.bin"), {"outside the asset's folder"});
  expect_bad_input(with_buffer_uri("uri_backslash", "..\\secret.bin"), {"buffer 0 URI"});
}

TEST(BadUri, DotDotThatStaysInsideIsRead) {
  std::string file = with_buffer_uri("uri_dotdot_inside", "sub/../real.bin");
  fs::path dir = fs::path(file).parent_path();
  fs::create_directory(dir / "sub");
  fs::copy_file(dir.parent_path() / "secret.bin", dir / "real.bin");
  EXPECT_EQ(load_gltf(file).characters.size(), 1u);
  // A symlinked folder's ".." is its target's parent: outside, so refused.
  std::string linked = with_buffer_uri("uri_dotdot_link", "link/../secret.bin");
  fs::path linked_dir = fs::path(linked).parent_path();
  fs::create_directory_symlink(linked_dir.parent_path() / "elsewhere", linked_dir / "link");
  fs::create_directory(linked_dir.parent_path() / "elsewhere");
  expect_bad_input(linked, {"outside the asset's folder"});
}

TEST(BadUri, BufferUriAbsolute) {
  expect_bad_input(with_buffer_uri("uri_absolute", "/etc/passwd"), {"buffer 0 URI \"/etc/passwd\"", "absolute"});
}

TEST(BadUri, BufferUriFileScheme) {
  expect_bad_input(with_buffer_uri("uri_scheme", "file:///etc/passwd"), {"buffer 0 URI", "scheme"});
  expect_bad_input(with_buffer_uri("uri_http", "https://example.com/x.bin"), {"buffer 0 URI", "scheme"});
}

TEST(BadUri, BufferUriPercentEncoded) {
  expect_bad_input(with_buffer_uri("uri_percent", "..%2Fsecret.bin"), {"buffer 0 URI", "outside the asset's folder"});
  expect_bad_input(with_buffer_uri("uri_percent_dots", "%2E%2E/secret.bin"), {"outside the asset's folder"});
  expect_bad_input(with_buffer_uri("uri_percent_abs", "%2Fetc%2Fpasswd"), {"buffer 0 URI", "absolute"});
}

TEST(BadUri, SymlinkInsideFolderPointingOut) {
  std::string file = with_buffer_uri("uri_symlink", "inside.bin");
  fs::path dir = fs::path(file).parent_path();
  fs::create_symlink(dir.parent_path() / "secret.bin", dir / "inside.bin");
  expect_bad_input(file, {"buffer 0 URI \"inside.bin\"", "outside the asset's folder"});
  // A symlinked folder inside leading out.
  std::string nested = with_buffer_uri("uri_symlink_dir", "up/secret.bin");
  fs::path nested_dir = fs::path(nested).parent_path();
  fs::create_directory_symlink(nested_dir.parent_path(), nested_dir / "up");
  expect_bad_input(nested, {"outside the asset's folder"});
}

TEST(BadUri, SymlinkInsideFolderStayingInsideIsRead) {
  // The check is about where a link leads, not about links as such.
  std::string file = with_buffer_uri("uri_symlink_ok", "alias.bin");
  fs::path dir = fs::path(file).parent_path();
  fs::copy_file(dir.parent_path() / "secret.bin", dir / "real.bin");
  fs::create_symlink("real.bin", dir / "alias.bin");
  EXPECT_EQ(load_gltf(file).characters.size(), 1u);
}

TEST(BadUri, ImageUrisOutsideFolder) {
  for (const char* uri : {"../secret.png", "/etc/passwd", "file:///etc/passwd", "..%2Fsecret.png"}) {
    fs::path dir = scratch_dir("image_uri") / "asset";
    fs::create_directories(dir);
    SkinnedFixture f;
    f.json["images"] = {{{"uri", uri}}};
    f.write_gltf(dir / "character.gltf", /*data_uri=*/true);
    expect_bad_input((dir / "character.gltf").string(), {"image 0 URI"});
  }
}

TEST(BadUri, MissingBufferFile) {
  expect_bad_input(with_buffer_uri("uri_missing", "gone.bin"), {"buffer 0", "\"gone.bin\"", "missing"});
}

}  // namespace
}  // namespace crowdprof::test
