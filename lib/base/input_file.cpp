#include "base/input_file.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <fstream>
#include <unordered_set>
#include <vector>

#include "base/errors.h"

namespace crowdprof {

namespace {

// nlohmann's DOM builder with a depth limit. The callback parser did the same
// through a std::function called on every event and kept stacks of its own; a
// fuzzer spent a third of each glTF input in it.
// With `unique_keys`, a key given twice in one object is refused: nlohmann
// keeps the last silently, so a typo'd copy of a key would change a benchmark.
class DepthLimitedDom : public nlohmann::detail::json_sax_dom_parser<nlohmann::json> {
 public:
  DepthLimitedDom(nlohmann::json& out, const std::string& path, bool unique_keys)
      : json_sax_dom_parser(out), path_(path), unique_keys_(unique_keys) {}
  bool start_object(std::size_t size) {
    if (unique_keys_) keys_.emplace_back();
    return enter() && json_sax_dom_parser::start_object(size);
  }
  bool start_array(std::size_t size) { return enter() && json_sax_dom_parser::start_array(size); }
  bool key(string_t& name) {
    if (unique_keys_ && !keys_.empty()) {
      if (!keys_.back().insert(name).second)
        throw InputError(path_, "the key \"" + printable(name, 60) +
                                    "\" is given twice in one object (JSON would keep the last without a word)");
    }
    return json_sax_dom_parser::key(name);
  }
  bool end_object() {
    --depth_;
    if (unique_keys_ && !keys_.empty()) keys_.pop_back();
    return json_sax_dom_parser::end_object();
  }
  bool end_array() {
    --depth_;
    return json_sax_dom_parser::end_array();
  }

 private:
  bool enter() {
    if (++depth_ > kMaxJsonDepth)
      throw InputError(path_, "broken JSON: nested more than " + std::to_string(kMaxJsonDepth) + " levels deep");
    return true;
  }
  const std::string& path_;
  int depth_ = 0;
  bool unique_keys_ = false;
  std::vector<std::unordered_set<std::string>> keys_;  // of each open object, with unique_keys_
};

}  // namespace

nlohmann::json parse_json_input(const std::string& path, std::string_view text, bool unique_keys) {
  try {
    nlohmann::json out;
    DepthLimitedDom dom(out, path, unique_keys);
    nlohmann::json::sax_parse(text.begin(), text.end(), &dom);
    return out;
  } catch (const nlohmann::json::parse_error& e) {
    // nlohmann's message reads "[json.exception.parse_error.101] parse error at line 1, ...".
    std::string what = e.what();
    if (e.byte >= text.size() || what.find("end of input") != std::string::npos)
      throw InputError(path, "truncated JSON (it ends after " + std::to_string(text.size()) + " bytes)");
    size_t at = what.find("] ");
    throw InputError(path, "broken JSON: " + printable(at == std::string::npos ? what : what.substr(at + 2), 200));
  } catch (const nlohmann::json::out_of_range& e) {
    // "[json.exception.out_of_range.406] number overflow parsing '1e400'"
    std::string what = e.what();
    size_t at = what.find("] ");
    throw InputError(path, "a number too large for a double: " +
                               printable(at == std::string::npos ? what : what.substr(at + 2), 120));
  } catch (const nlohmann::json::exception& e) {
    throw InputError(path, "broken JSON: " + printable(e.what(), 200));
  }
}

std::string read_file_head(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string head(kFormatProbeBytes, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<size_t>(in.gcount()));
  return head;
}

std::string printable(std::string_view text, size_t limit) {
  std::string out;
  for (char ch : text.substr(0, limit)) out += std::iscntrl(static_cast<unsigned char>(ch)) ? '?' : ch;
  if (text.size() > limit) out += "...";
  return out;
}

CharacterSpec parse_character_spec(const std::string& spec) {
  CharacterSpec out;
  size_t hash = spec.rfind('#');
  if (hash == std::string::npos) {
    out.file = spec;
    return out;
  }
  out.file = spec.substr(0, hash);
  std::string selector = spec.substr(hash + 1);
  const std::string key = "skin=";
  int skin = -1;
  const char* first = selector.data() + key.size();
  const char* last = selector.data() + selector.size();
  if (selector.rfind(key, 0) != 0 || first == last || std::from_chars(first, last, skin).ptr != last || skin < 0)
    throw UsageError("'" + spec + "': expected FILE or FILE#skin=N with N a skin index (see crowdprof info)");
  out.skin = skin;
  return out;
}

}  // namespace crowdprof
