// Fuzz target: bytes as a result file given to `crowdprof diff` and
// `crowdprof report`: bench, check or compare JSON. Both read the file with
// read_json_file and then take it apart their own way (bench_results_in for
// diff, the typed document for the report), so each reader is driven to its
// end: the file diffed against itself, a comparison or capacity search written
// and read back,
// and the page made. Each must refuse with
// an InputError or finish; any other exception, nlohmann's JSON_ASSERT reached
// (an unguarded read), a regression of a file against itself, or a sanitizer
// report is a finding.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>

#include "base/errors.h"
#include "base/json_assert.h"
#include "fuzz_file.h"
#include "gate/diff.h"
#include "reports/html_report.h"
#include "gate/regression.h"
#include "result/result_codec.h"
#include "result/result_document.h"

namespace {

void run_diff(const nlohmann::json& doc, const std::string& path) {
  using namespace crowdprof;
  std::vector<Result> runs = bench_results_in(doc, path);
  CheckOptions options;
  Diff diff = diff_results(runs, path, runs, path, options);
  (void)format_diff(diff, options);
  // The codec reads back the diff it writes, to the same document.
  const nlohmann::json written = diff_to_json(diff, options);
  if (diff_record_to_json(diff_record_from_json(written, path)) != written) {
    std::fprintf(stderr, "fuzz: a diff written and read back changed\n");
    std::abort();
  }
  if (diff.regressed()) {
    std::fprintf(stderr, "fuzz: a result regressed against itself in diff\n");
    std::abort();
  }
}

void run_report(const nlohmann::json& doc, const std::string& path) {
  using namespace crowdprof;
  ResultDocument document = result_document_from_json(doc, path);
  // The codec reads back what it writes of a comparison or a capacity search,
  // to the same document.
  if (document.kind != "bench") {
    nlohmann::json written = result_document_to_json(document);
    if (result_document_to_json(result_document_from_json(written, path)) != written) {
      std::fprintf(stderr, "fuzz: a %s document written and read back changed\n", document.kind.c_str());
      std::abort();
    }
  }
  HtmlReportInput input;
  input.sources = {path};
  add_document(input, std::move(document), path);
  (void)html_report(input);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace crowdprof;
  const std::string path = crowdprof::fuzz::write_input(data, size, "result.json");
  nlohmann::json doc;
  try {
    doc = read_json_file(path);
  } catch (const InputError&) {
    return 0;  // Refused cleanly.
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fuzz: read_json_file, not an InputError: %s\n", e.what());
    std::abort();
  }
  // The two readers are independent: one refusing says nothing about the other.
  for (auto* reader : {&run_diff, &run_report}) {
    try {
      reader(doc, path);
    } catch (const JsonAssertion& e) {
      // Refused, but only by the net under the reads: one was not guarded.
      std::fprintf(stderr, "fuzz: %s, an unguarded read: %s\n", reader == &run_diff ? "diff" : "report", e.what());
      std::abort();
    } catch (const InputError&) {
    } catch (const std::exception& e) {
      std::fprintf(stderr, "fuzz: %s, not an InputError: %s\n", reader == &run_diff ? "diff" : "report", e.what());
      std::abort();
    }
  }
  return 0;
}
