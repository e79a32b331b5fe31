// The arenas benches run their parallel stages in (frame/bench_threads.h).
#include <gtest/gtest.h>

#include <tbb/parallel_for.h>

#include <atomic>

#include "frame/bench_threads.h"

namespace crowdprof {
namespace {

// compare interleaves modes in one process: their benches must find the same
// workers, so a thread count is served by one arena while any bench holds it.
TEST(BenchThreads, BenchesWithTheSameThreadCountShareOneArena) {
  std::shared_ptr<BenchThreads> a = bench_threads(2);
  std::shared_ptr<BenchThreads> b = bench_threads(2);
  std::shared_ptr<BenchThreads> c = bench_threads(3);
  EXPECT_EQ(a.get(), b.get());
  EXPECT_EQ(a->arena.get(), b->arena.get());
  EXPECT_NE(a.get(), c.get());
  EXPECT_EQ(a->arena->max_concurrency(), 2);
  EXPECT_EQ(bench_threads(0)->arena->max_concurrency(), 1);
}

// More threads than cores are given (a 2-core machine asked for 5): the
// worker limit is lifted while the arena lives.
TEST(BenchThreads, MoreThreadsThanCoresAreGiven) {
  std::shared_ptr<BenchThreads> five = bench_threads(5);
  EXPECT_EQ(five->arena->max_concurrency(), 5);
  EXPECT_GE(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism), 5u);
  std::atomic<int> ran{0};
  five->arena->execute([&] { tbb::parallel_for(0, 100, [&](int) { ran.fetch_add(1); }); });
  EXPECT_EQ(ran.load(), 100);
}

// The arena goes with its last holder (before static destruction), and a
// later bench gets a new one.
TEST(BenchThreads, TheArenaGoesWithItsLastHolder) {
  std::weak_ptr<BenchThreads> seen;
  {
    std::shared_ptr<BenchThreads> held = bench_threads(4);
    seen = held;
    EXPECT_FALSE(seen.expired());
  }
  EXPECT_TRUE(seen.expired());
  EXPECT_NE(bench_threads(4), nullptr);
}

}  // namespace
}  // namespace crowdprof
