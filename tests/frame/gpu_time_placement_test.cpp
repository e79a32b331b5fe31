// A GPU time the timer could not have measured is not reported: every frame
// ends in glFinish, so its GPU work fits in its wall time. llvmpipe's first
// GL_TIME_ELAPSED of a long frame has been seen to give the clock's absolute
// time (42,884,627 ms for a 27 s frame); such a frame counts as not read back.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "characters.h"
#include "frame/crowd_bench.h"
#include "frame/frame_renderer.h"
#include "frame/run_bench.h"

using namespace crowdprof;

namespace {

// Draws nothing; frame 0's GPU time is absurd, the others' 0.25 ms.
class AbsurdFirstTimer final : public FrameRenderer {
 public:
  size_t max_gpu_joints(const ModeSwitches&) const override { return 1024; }
  void require(const ModeSwitches&) const override {}
  void prepare(const FrameView&) override {}
  uint64_t animation_gpu_bytes() const override { return 0; }
  GpuMemoryRecord gpu_memory() const override { return {}; }
  void draw(const FrameView& view, Counters&) override { pending_.push_back(view.frame); }
  void finish() override {}
  std::string gpu_timing_missing() const override { return {}; }
  std::string pipeline_statistics_missing() const override { return "not in this fake"; }
  size_t take_gpu_times(const FrameView*, uint64_t frame, std::span<GpuTime> out, bool wait) override {
    size_t written = 0;
    while (!pending_.empty() && written < out.size() && (wait || pending_.front() < frame)) {
      out[written++] = {pending_.front(), pending_.front() == 0 ? 4.3e10 : 0.25, {}};
      pending_.erase(pending_.begin());
    }
    return written;
  }

 private:
  std::vector<uint64_t> pending_;
};

}  // namespace

TEST(GpuTimePlacement, ATimeLongerThanItsFrameIsNotReported) {
  AbsurdFirstTimer renderer;
  BenchConfig config;
  config.mode = find_mode("threaded")->switches;
  config.crowd.copies = 2;
  config.renderer = &renderer;
  CrowdBench bench(test::small_humanoid(), config);
  RunOptions options;
  options.frames = 3;
  options.warmup = 0;
  Result report = run_bench(bench, "humanoid", options);
  ASSERT_EQ(report.frame_records.size(), 3u);
  EXPECT_TRUE(std::isnan(report.frame_records[0].gpu_ms)) << report.frame_records[0].gpu_ms;
  EXPECT_EQ(report.frame_records[1].gpu_ms, 0.25);
  EXPECT_EQ(report.frame_records[2].gpu_ms, 0.25);
}
