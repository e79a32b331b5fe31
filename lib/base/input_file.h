// What every reader of a file from outside (characters, baselines, results)
// shares, and how a character file is named on the command line, so that each refuses the same things in the same
// words: JSON that cannot be used, and a look at a file's first bytes before it is read whole.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace crowdprof {

// JSON nested deeper than this is refused: glTF needs about 8 levels and a result
// 4, and the JSON walkers after the parser (dump, tiny_gltf's extras) recurse
// once per level.
inline constexpr int kMaxJsonDepth = 64;

// How much of a file a reader looks at to judge its format, before reading it
// whole: a 1 GB file that is not what it should be is refused at once.
inline constexpr size_t kFormatProbeBytes = 4096;

// Parses `text`, the contents of the file `path`, as JSON. Every failure is an
// InputError naming the file: "truncated JSON (it ends after N bytes)" when the
// text stops mid-value, "broken JSON: ..." for any other syntax error or nesting
// deeper than kMaxJsonDepth, and "a number too large for a double: ..." for a
// literal such as 1e400 (nlohmann reports that as out_of_range, not as a parse
// error, and it used to escape as "the run failed").
// With `unique_keys` (scene files, which people write by hand), a key given
// twice in one object is an InputError naming it.
nlohmann::json parse_json_input(const std::string& path, std::string_view text, bool unique_keys = false);

// The first min(kFormatProbeBytes, size) bytes of the file, or "" when it cannot
// be opened (the caller's full read reports that).
std::string read_file_head(const std::string& path);

// Text from a file, made safe for a one-line message: control characters become
// '?', and anything past `limit` characters becomes "...".
std::string printable(std::string_view text, size_t limit = 60);

// "scene.glb" or "scene.glb#skin=2": which file, and which of its skins.
struct CharacterSpec {
  std::string file;
  int skin = -1;  // -1: the file's only skin
};
// Throws UsageError for a malformed "#..." suffix.
CharacterSpec parse_character_spec(const std::string& spec);

}  // namespace crowdprof
