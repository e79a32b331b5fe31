// Fuzz target: bytes as a scene file, through what bench does with one before
// it runs: load and check the scene (its mode and switches too), write it back
// and read that again (the same text), load each character it names, and make
// each character's crowd group (action names resolved). Beside the scene lies
// one character, "character.glb" (the tests' small skinned fixture), so that
// scenes that name it reach past the file checks. Refusals are InputError (or
// UsageError for a malformed FILE#skin=N); anything else, nlohmann's
// JSON_ASSERT reached (an unguarded read), or a sanitizer report is a finding.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>

#include "../gltf_fixture.h"
#include "base/errors.h"
#include "asset/gltf_loader.h"
#include "base/json_assert.h"
#include "fuzz_file.h"
#include "scene/scene_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace crowdprof;
  const std::string path = crowdprof::fuzz::write_input(data, size, "scene.json");
  static const bool character_written = [&] {
    test::SkinnedFixture().write_glb(std::filesystem::path(path).parent_path() / "character.glb");
    return true;
  }();
  (void)character_written;
  try {
    SceneFile scene = load_scene_file(path);
    // The codec: a scene that reads, written beside it, reads back as the
    // same text (mode, switches and all).
    const std::string again = crowdprof::fuzz::input_path("written.json");
    const std::string text = scene_file_text(scene, again);
    crowdprof::fuzz::write_input(reinterpret_cast<const uint8_t*>(text.data()), text.size(), "written.json");
    if (scene_file_text(load_scene_file(again), again) != text) {
      std::fprintf(stderr, "fuzz: a written scene reads back as another:\n%s\n", text.c_str());
      std::abort();
    }
    for (size_t i = 0; i < scene.characters.size(); ++i) {
      // A "generate" entry's values were checked above; making the humanoid
      // (up to 2.5 million vertices) is the generator's, tested on its own.
      if (scene.characters[i].generate) continue;
      Character character = load_character(scene.characters[i].path);
      (void)scene_group(scene, i, character);
    }
  } catch (const JsonAssertion& e) {
    // Refused, but only by the net under the reads: one was not guarded.
    std::fprintf(stderr, "fuzz: an unguarded read: %s\n", e.what());
    std::abort();
  } catch (const InputError&) {
    // Refused cleanly.
  } catch (const UsageError&) {
    // A malformed FILE#skin=N: the command line's kind of error (exit 2).
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fuzz: neither InputError nor UsageError: %s\n", e.what());
    std::abort();
  }
  return 0;
}
