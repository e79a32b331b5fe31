// nlohmann's JSON_ASSERT as a crowdprof input error. nlohmann checks its
// preconditions with JSON_ASSERT, which is assert(): in a Release build a read
// it forbids (const operator[] of a missing key, an iterator past the end) is
// undefined behaviour, and in a debug or sanitizer build an abort. Here it
// throws instead, so a read the code forgot to guard ends as exit 3, never as a
// read past the end of an object. lib/CMakeLists.txt force-includes this header
// into every file of every target that can include nlohmann (tiny_gltf's
// implementation too): one definition everywhere, before nlohmann's own.
// Readers still guard every read of an untrusted document; this is the net
// under them, and tests treat reaching it as a finding (JsonAssertion).
#pragma once

#include "errors.h"  // beside this file: it is force-included, before any include path

namespace crowdprof {

// What JSON_ASSERT throws: an InputError whose file is not known where nlohmann
// finds the problem; a reader that knows it names it (see load_gltf).
class JsonAssertion : public InputError {
 public:
  explicit JsonAssertion(const std::string& problem) : InputError("a JSON input", problem), problem_(problem) {}
  const std::string& problem() const { return problem_; }

 private:
  std::string problem_;
};

[[noreturn]] void json_assertion_failed(const char* condition);

}  // namespace crowdprof

#define JSON_ASSERT(condition) \
  (static_cast<bool>(condition) ? static_cast<void>(0) : ::crowdprof::json_assertion_failed(#condition))
