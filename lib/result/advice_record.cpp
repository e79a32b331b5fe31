#include "result/advice_record.h"

#include <cmath>

#include "base/errors.h"

namespace crowdprof {

namespace {

using nlohmann::json;

json interval_json(const MsInterval& i) {
  return {{"median", i.median}, {"low", i.low}, {"high", i.high}};
}

json candidate_json(const AdviceCandidate& c) {
  return {{"lever", c.lever},
          {"changes", c.changes},
          {"metric_ms", interval_json(c.metric)},
          {"frame_median_ms", c.frame_ms},
          {"saved_ms", interval_json(c.saved)},
          {"error_measured", c.error_measured},
          {"error_px", c.error_px},
          {"error_mm", c.error_mm},
          {"error_height_pct", c.error_height_pct},
          {"capacity_estimate", c.capacity_estimate},
          {"digest", c.digest},
          {"verdict", c.verdict}};
}

json optional_count(const std::optional<size_t>& n) {
  return n ? json(*n) : json();
}

// Reads fields of one object, each checked; errors name the field's path.
class Fields {
 public:
  Fields(const json& object, std::string where, const std::string& path)
      : o_(object), where_(std::move(where)), path_(path) {
    if (!o_.is_object()) throw bad("", "an object");
  }
  InputError bad(const std::string& key, const char* expected) const {
    return InputError(path_,
                      "an advise result whose \"" + where_ + (key.empty() ? "" : "." + key) + "\" is not " + expected);
  }
  const json& at(const std::string& key) const {
    if (!o_.contains(key)) throw bad(key, "there");
    return o_[key];
  }
  double number(const std::string& key, bool signed_ok = false) const {
    const json& v = at(key);
    if (!v.is_number() || !std::isfinite(v.get<double>()) || (!signed_ok && v.get<double>() < 0))
      throw bad(key, signed_ok ? "a number" : "a number of 0 or more");
    return v.get<double>();
  }
  size_t count(const std::string& key) const {
    const json& v = at(key);
    if (!v.is_number_unsigned() && !(v.is_number_integer() && v.get<int64_t>() >= 0)) throw bad(key, "a whole number");
    return v.get<size_t>();
  }
  std::optional<size_t> optional_count(const std::string& key) const {
    if (!o_.contains(key) || o_[key].is_null()) return std::nullopt;
    return count(key);
  }
  std::string text(const std::string& key) const {
    const json& v = at(key);
    if (!v.is_string()) throw bad(key, "a string");
    return v.get<std::string>();
  }
  bool flag(const std::string& key) const {
    const json& v = at(key);
    if (!v.is_boolean()) throw bad(key, "true or false");
    return v.get<bool>();
  }
  std::vector<std::string> texts(const std::string& key) const {
    const json& v = at(key);
    if (!v.is_array()) throw bad(key, "a list of strings");
    std::vector<std::string> out;
    for (const json& item : v) {
      if (!item.is_string()) throw bad(key, "a list of strings");
      out.push_back(item.get<std::string>());
    }
    return out;
  }
  const json& array(const std::string& key) const {
    const json& v = at(key);
    if (!v.is_array()) throw bad(key, "a list");
    return v;
  }
  MsInterval interval(const std::string& key, bool signed_ok) const {
    Fields i(at(key), where_ + "." + key, path_);
    return {i.number("median", signed_ok), i.number("low", signed_ok), i.number("high", signed_ok)};
  }

 private:
  const json& o_;
  std::string where_;
  const std::string& path_;
};

AdviceCandidate read_candidate(const Fields& f) {
  AdviceCandidate c;
  c.lever = f.text("lever");
  c.changes = f.text("changes");
  c.metric = f.interval("metric_ms", false);
  c.frame_ms = f.number("frame_median_ms");
  c.saved = f.interval("saved_ms", true);
  c.error_measured = f.flag("error_measured");
  c.error_px = f.number("error_px");
  c.error_mm = f.number("error_mm");
  c.error_height_pct = f.number("error_height_pct");
  c.capacity_estimate = f.count("capacity_estimate");
  c.digest = f.text("digest");
  c.verdict = f.text("verdict");
  return c;
}

}  // namespace

json advice_to_json(const AdviceRecord& a) {
  json j = {{"budget_ms", a.budget_ms},
            {"metric", a.metric},
            {"max_error_px", a.max_error_px},
            {"time_limit_s", a.time_limit_s},
            {"characters", a.characters},
            {"start_mode", a.start_mode},
            {"start_options", a.start_options},
            {"final_options", a.final_options},
            {"added_options", a.added_options},
            {"levers", a.levers},
            {"left_out", a.left_out},
            {"configurations_measured", a.configurations_measured},
            {"frames_per_configuration", a.frames_per_configuration},
            {"warmup_frames", a.warmup},
            {"block_frames", a.block_frames},
            {"met", a.met},
            {"outcome", a.outcome},
            {"ran_out", a.ran_out},
            {"elapsed_s", a.elapsed_s}};
  j["start"] = candidate_json(a.start);
  j["final"] = candidate_json(a.final);
  j["steps"] = json::array();
  for (const AdviceStep& step : a.steps) {
    json s = {{"taken", optional_count(step.taken)}, {"candidates", json::array()}};
    for (const AdviceCandidate& c : step.candidates) s["candidates"].push_back(candidate_json(c));
    j["steps"].push_back(s);
  }
  j["capacities"] = json::array();
  for (const AdviceCapacity& c : a.capacities)
    j["capacities"].push_back({{"configuration", c.configuration},
                               {"largest_fit", optional_count(c.fit)},
                               {"first_over", optional_count(c.over)},
                               {"capped", c.capped},
                               {"sizes_measured", c.measured}});
  return j;
}

AdviceRecord advice_from_json(const json& advice, const std::string& path) {
  Fields f(advice, "advice", path);
  AdviceRecord a;
  a.budget_ms = f.number("budget_ms");
  a.metric = f.text("metric");
  a.max_error_px = f.number("max_error_px");
  a.time_limit_s = f.number("time_limit_s");
  a.characters = f.count("characters");
  a.start_mode = f.text("start_mode");
  a.start_options = f.text("start_options");
  a.final_options = f.text("final_options");
  a.added_options = f.text("added_options");
  a.levers = f.texts("levers");
  a.left_out = f.texts("left_out");
  a.configurations_measured = f.count("configurations_measured");
  a.frames_per_configuration = f.count("frames_per_configuration");
  a.warmup = f.count("warmup_frames");
  a.block_frames = f.count("block_frames");
  a.met = f.flag("met");
  a.outcome = f.text("outcome");
  a.ran_out = f.text("ran_out");
  a.elapsed_s = f.number("elapsed_s");
  a.start = read_candidate(Fields(f.at("start"), "advice.start", path));
  a.final = read_candidate(Fields(f.at("final"), "advice.final", path));
  const json& steps = f.array("steps");
  for (size_t s = 0; s < steps.size(); ++s) {
    const std::string where = "advice.steps[" + std::to_string(s) + "]";
    Fields step_fields(steps[s], where, path);
    AdviceStep step;
    const json& candidates = step_fields.array("candidates");
    for (size_t c = 0; c < candidates.size(); ++c)
      step.candidates.push_back(
          read_candidate(Fields(candidates[c], where + ".candidates[" + std::to_string(c) + "]", path)));
    step.taken = step_fields.optional_count("taken");
    if (step.taken && *step.taken >= step.candidates.size()) throw step_fields.bad("taken", "one of its candidates");
    a.steps.push_back(std::move(step));
  }
  const json& capacities = f.array("capacities");
  for (size_t c = 0; c < capacities.size(); ++c) {
    Fields cf(capacities[c], "advice.capacities[" + std::to_string(c) + "]", path);
    AdviceCapacity capacity;
    capacity.configuration = cf.text("configuration");
    capacity.fit = cf.optional_count("largest_fit");
    capacity.over = cf.optional_count("first_over");
    capacity.capped = cf.flag("capped");
    capacity.measured = cf.count("sizes_measured");
    a.capacities.push_back(capacity);
  }
  return a;
}

}  // namespace crowdprof
