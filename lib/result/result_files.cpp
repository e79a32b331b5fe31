// Reading result files and the documents that hold results (the codec's file
// side: lib/result/result_codec.h).
#include <filesystem>
#include <fstream>
#include <iterator>

#include "base/errors.h"
#include "base/input_file.h"
#include "base/output_file.h"
#include "result/result_codec.h"

namespace crowdprof {

using nlohmann::json;

std::string document_kind(const nlohmann::json& doc) {
  if (!doc.is_object() || !doc.contains("crowdprof") || !doc["crowdprof"].is_object()) return "bench";
  const json& tag = doc["crowdprof"];
  return tag.contains("kind") && tag["kind"].is_string() ? tag["kind"].get<std::string>() : std::string("bench");
}

nlohmann::json read_json_file(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code error;
  fs::file_status status = fs::status(path, error);
  if (!fs::exists(status)) throw InputError(path, "no such file");
  if (fs::is_directory(status)) throw InputError(path, "a directory, not a crowdprof result");
  if (!fs::is_regular_file(status)) throw InputError(path, "not a regular file, so not a crowdprof result");
  // 10 million frames of eleven samples fit in well under this.
  constexpr uintmax_t kMaxResultBytes = uintmax_t{2} << 30;
  if (fs::file_size(path, error) > kMaxResultBytes) throw InputError(path, "larger than 2 GiB: not a crowdprof result");
  // A result is a JSON object: judged on the first bytes, before a large file
  // that is something else is read whole.
  std::string head = read_file_head(path);
  size_t first = head.find_first_not_of(" \t\r\n");
  if (first != std::string::npos && head[first] != '{')
    throw InputError(path, "not a crowdprof result (not a JSON object)");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "cannot be read");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (text.find_first_not_of(" \t\r\n") == std::string::npos)
    throw InputError(path, "empty file, not a crowdprof result");
  return parse_json_input(path, text);
}

bool is_partial_result(const nlohmann::json& doc) {
  return doc.is_object() && doc.contains("partial") && doc["partial"] == true;
}

nlohmann::json as_partial_result(nlohmann::json doc) {
  doc.erase("pid");
  doc.erase("started_s");
  doc["partial"] = true;
  return doc;
}

Result read_result(const std::string& path) {
  return result_from_json(read_json_file(path), path);
}

std::vector<Result> bench_results_in(const nlohmann::json& doc, const std::string& path) {
  std::string kind = document_kind(doc);
  if (kind != "compare" && kind != "capacity" && kind != "advise") return {result_from_json(doc, path)};
  if (!doc.contains("runs") || !doc["runs"].is_array() || doc["runs"].empty())
    throw InputError(path, "a comparison without \"runs\": not a complete crowdprof result");
  std::vector<Result> out;
  for (size_t i = 0; i < doc["runs"].size(); ++i)  // bench results only: a comparison does not nest
    out.push_back(result_from_json(doc["runs"][i], path + " (runs[" + std::to_string(i) + "])"));
  return out;
}

namespace {

std::pair<std::string, std::string> split_skin(const std::string& file) {
  size_t hash = file.rfind("#skin=");
  return hash == std::string::npos ? std::pair{file, std::string()}
                                   : std::pair{file.substr(0, hash), file.substr(hash)};
}
}  // namespace

nlohmann::json with_paths_relative_to(nlohmann::json result, const std::string& result_path) {
  namespace fs = std::filesystem;
  fs::path folder = fs::absolute(fs::path(result_path)).parent_path();
  auto relocate = [&](json& scene) {
    if (!scene.is_object() || !scene.contains("file") || !scene["file"].is_string()) return;
    if (scene.value("file_from", json("")) == "result") return;
    auto [file, skin] = split_skin(scene["file"].get<std::string>());
    if (file.empty()) return;
    fs::path relative = fs::absolute(file).lexically_normal().lexically_relative(folder.lexically_normal());
    if (relative.empty()) return;
    scene["file"] = relative.string() + skin;
    scene["file_from"] = "result";
  };
  if (result.is_object() && result.contains("scene")) relocate(result["scene"]);
  if (result.is_object() && result.contains("runs") && result["runs"].is_array())
    for (json& run : result["runs"])
      if (run.is_object() && run.contains("scene")) relocate(run["scene"]);
  return result;
}

std::string recorded_scene_file(const Result& result, const std::string& result_path) {
  namespace fs = std::filesystem;
  auto [file, skin] = split_skin(result.run.file);
  fs::path folder = fs::path(result_path).parent_path();
  fs::path beside = (folder / file).lexically_normal();
  if (fs::path(file).is_absolute()) return file + skin;
  if (result.file_from_result) return beside.string() + skin;
  std::error_code error;
  if (!fs::exists(file, error) && fs::exists(beside, error)) return beside.string() + skin;
  return file + skin;
}
void write_result_file(const std::string& path, const std::string& what, const Result& result) {
  write_text(path, what,
             [&](std::ostream& out) { out << with_paths_relative_to(result_to_json(result), path).dump(2) << "\n"; });
}

}  // namespace crowdprof
