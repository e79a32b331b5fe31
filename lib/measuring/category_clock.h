// The BGE's profile clock (KX_TimeCategoryLogger): one clock that is always
// running in exactly one category, so the categories add up to the frame.
#pragma once

#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <string_view>

namespace crowdprof {

// In the BGE's overlay order.
enum class Category : uint8_t {
  Physics,
  Logic,
  Animations,
  Network,
  Scenegraph,
  Rasterizer,
  Services,
  Overhead,
  Outside,
  GpuLatency,
};
inline constexpr size_t kCategoryCount = 10;

// "Physics", ..., "GPU Latency": the names the BGE printed.
std::string_view category_name(Category category);
// The name in lower case, "GPU Latency" as "gpu_latency".
std::string_view category_column(Category category);
// The category's series of per-frame milliseconds, one name in CSV columns,
// JSON keys and metric names alike (result format 2): "animations_ms",
// "gpu_latency_ms". Format 1 keyed JSON by category_name().
std::string series_name(Category category);

// Milliseconds per category for one frame; their sum is the frame time.
struct FrameTimes {
  std::array<double, kCategoryCount> ms{};
  double total_ms() const;
  double operator[](Category c) const { return ms[static_cast<size_t>(c)]; }
};

class CategoryClock {
 public:
  using Clock = std::chrono::steady_clock;

  // Starts a frame with the clock in `category`.
  void begin_frame(Category category);
  // Charges the time since the last switch to the current category and makes
  // `category` current. Returns the category it left, for scoped switches.
  Category switch_to(Category category);
  // Charges the last stretch and returns the frame; the clock keeps running in
  // the current category, so the time until the next begin_frame is not lost:
  // it is charged to the next frame.
  FrameTimes end_frame();

 private:
  Clock::time_point last_{};
  Category current_ = Category::Outside;
  std::array<int64_t, kCategoryCount> ns_{};
  bool running_ = false;
};

}  // namespace crowdprof
