// Fuzz target: bytes as a result file (bench --json, a check baseline), through
// what `check --result` does with it: read and validate, then compare it with
// itself and format the verdict. The reader must refuse with an InputError or
// give a document every later step takes; any other exception, nlohmann's
// JSON_ASSERT reached (an unguarded read), or a sanitizer report is a finding.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>

#include "base/errors.h"
#include "base/json_assert.h"
#include "fuzz_file.h"
#include "gate/regression.h"
#include "result/result_codec.h"
#include "result/run_match.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace crowdprof;
  const std::string path = crowdprof::fuzz::write_input(data, size, "result.json");
  try {
    Result doc = read_result(path);
    // The codec reads back what it writes, to the same document.
    nlohmann::json written = result_to_json(doc);
    if (result_to_json(result_from_json(written, path)) != written) {
      std::fprintf(stderr, "fuzz: a result written and read back changed\n");
      std::abort();
    }
    require_same_run(doc, doc, path);
    (void)comparison_notes(doc, doc);
    CheckOptions options;
    options.metrics = {"frame_ms", resolve_metric("Animations")};
    CheckResult result = check_results(doc, doc, options);
    (void)format_check(result, options);
    if (result.regressed()) {
      std::fprintf(stderr, "fuzz: a result regressed against itself\n");
      std::abort();
    }
  } catch (const JsonAssertion& e) {
    // Refused, but only by the net under the reads: one was not guarded.
    std::fprintf(stderr, "fuzz: an unguarded read: %s\n", e.what());
    std::abort();
  } catch (const InputError&) {
    // Refused cleanly.
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fuzz: not an InputError: %s\n", e.what());
    std::abort();
  }
  return 0;
}
