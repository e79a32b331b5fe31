// The one reader and writer of results (docs/formats.md; result_reader.cpp,
// result_writer.cpp): JSON in, a checked Result out, and back. Nothing else in
// crowdprof reads a result's fields by name. Inputs may come from strangers:
// every field is checked before use and a bad one is an InputError naming the
// file and the field.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "result/result.h"

namespace crowdprof {

// The document bench --json writes for `result`, format kResultFormat.
nlohmann::json result_to_json(const Result& result);

// The "environment" section: the machine and build, and which GL drew.
nlohmann::json environment_to_json(const Result& result);

// The result in `doc`, read from `path` (named in errors). InputError unless it
// is a bench result of a format this version reads, with the scene, the mode
// and its switches, per-frame samples for the frame and every category (as many
// as "frames", finite, not negative), the counters and a digest; optional
// sections are checked when present.
Result result_from_json(const nlohmann::json& doc, const std::string& path);

// A document a run cut short wrote ("partial": true). It may hold no frame, so
// it is written as it is and never read back as a result.
bool is_partial_result(const nlohmann::json& doc);

// A cut run's document as check writes it: marked partial, without the
// process fields (pid, started_s) that pooling moves into "runs".
nlohmann::json as_partial_result(nlohmann::json doc);

// Reads a JSON file that should hold a crowdprof document: InputError naming
// `path` when it is missing, not a regular file, larger than 2 GiB, empty,
// truncated, not JSON or not an object. What it holds is not checked.
nlohmann::json read_json_file(const std::string& path);

// read_json_file, then result_from_json.
Result read_result(const std::string& path);

// Why a document of `format` (written by crowdprof `version`) is not read, or ""
// when this crowdprof reads that format: one message for results and the
// documents that hold them.
std::string unreadable_format(int64_t format, const std::string& version);

// The kind a crowdprof document names ("bench", "compare", "capacity", "check",
// "ab_check", ...); "bench" when it names none.
std::string document_kind(const nlohmann::json& doc);

// The bench results a document holds: itself for a bench result, each run for
// a compare or capacity result. InputError naming `path` (and the run) when one
// is not a readable result, or a compare result holds none.
std::vector<Result> bench_results_in(const nlohmann::json& doc, const std::string& path);

// A document as written to `result_path`: its scene file (and those of a
// compare or capacity result's runs) stored relative to the result's folder,
// marked "file_from": "result", so that the result can be checked from any
// folder and moved with its scene. A "#skin=N" suffix is kept.
nlohmann::json with_paths_relative_to(nlohmann::json doc, const std::string& result_path);

// The scene file a result read from `result_path` recorded, as a path usable
// from here: resolved from the result's folder when it was stored relative to
// it; as recorded for older results (relative to the folder they were made in),
// unless only the result's folder has it.
std::string recorded_scene_file(const Result& result, const std::string& result_path);

// Writes a result as bench --json does, its scene file stored relative to
// `path` (with_paths_relative_to), through write_text (base/output_file.h).
void write_result_file(const std::string& path, const std::string& what, const Result& result);

}  // namespace crowdprof
