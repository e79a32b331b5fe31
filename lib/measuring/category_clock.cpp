#include "measuring/category_clock.h"

namespace crowdprof {

namespace {
constexpr std::array<std::string_view, kCategoryCount> kNames = {"Physics",    "Logic",      "Animations", "Network",
                                                                 "Scenegraph", "Rasterizer", "Services",   "Overhead",
                                                                 "Outside",    "GPU Latency"};
constexpr std::array<std::string_view, kCategoryCount> kColumns = {"physics",    "logic",      "animations", "network",
                                                                   "scenegraph", "rasterizer", "services",   "overhead",
                                                                   "outside",    "gpu_latency"};
}  // namespace

std::string_view category_name(Category category) {
  return kNames[static_cast<size_t>(category)];
}
std::string series_name(Category category) {
  return std::string(category_column(category)) + "_ms";
}

std::string_view category_column(Category category) {
  return kColumns[static_cast<size_t>(category)];
}

double FrameTimes::total_ms() const {
  double total = 0.0;
  for (double m : ms) total += m;
  return total;
}

void CategoryClock::begin_frame(Category category) {
  ns_.fill(0);
  if (!running_) {
    last_ = Clock::now();
    running_ = true;
  } else {
    // Whatever ran between frames (reports, progress) belongs to this frame's
    // current category, as in the BGE where the clock never stops.
    switch_to(current_);
  }
  switch_to(category);
}

Category CategoryClock::switch_to(Category category) {
  Clock::time_point now = Clock::now();
  ns_[static_cast<size_t>(current_)] += std::chrono::duration_cast<std::chrono::nanoseconds>(now - last_).count();
  last_ = now;
  Category left = current_;
  current_ = category;
  return left;
}

FrameTimes CategoryClock::end_frame() {
  switch_to(current_);
  FrameTimes times;
  for (size_t i = 0; i < kCategoryCount; ++i) times.ms[i] = static_cast<double>(ns_[i]) * 1e-6;
  return times;
}

}  // namespace crowdprof
