// The arenas benches run their parallel stages in (frame/bench_threads.h).
#include <gtest/gtest.h>

#include <tbb/parallel_for.h>

#include <atomic>
#include <chrono>
#include <thread>

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

// Arenas of different sizes alive together each get their threads: oneTBB
// applies the smallest live worker limit, so they share one control set to the
// largest, in whichever order they are made.
TEST(BenchThreads, ArenasOfDifferentSizesKeepTheWidestLimit) {
  for (bool wide_first : {false, true}) {
    std::shared_ptr<BenchThreads> narrow, wide;
    if (wide_first) wide = bench_threads(6);
    narrow = bench_threads(3);
    if (!wide_first) wide = bench_threads(6);
    EXPECT_GE(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism), 6u) << wide_first;
    wide.reset();
    // The narrow arena still holds a control that lifts the limit to its own.
    EXPECT_GE(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism), 3u) << wide_first;
  }
}

// A one-thread arena has two slots: two outside threads executing in it at
// once may be given slots 0 and 1, which a per-thread scratch must cover.
TEST(BenchThreads, AOneThreadArenaHasTwoSlots) {
  std::shared_ptr<BenchThreads> one = bench_threads(1);
  std::atomic<int> inside{0}, largest{-1};
  auto enter = [&] {
    one->arena->execute([&] {
      // Both threads inside the arena at once (or, were there one slot, the
      // second's work waiting for the first: no deadlock, a second's wait).
      inside.fetch_add(1);
      auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(1);
      while (inside.load() < 2 && std::chrono::steady_clock::now() < give_up) std::this_thread::yield();
      int slot = tbb::this_task_arena::current_thread_index();
      int seen = largest.load();
      while (slot > seen && !largest.compare_exchange_weak(seen, slot)) {
      }
    });
  };
  std::thread a(enter), b(enter);
  a.join();
  b.join();
  EXPECT_LT(static_cast<size_t>(largest.load()), arena_slots(1));
  EXPECT_EQ(arena_slots(1), 2u);
  EXPECT_EQ(arena_slots(4), 4u);
}

}  // namespace
}  // namespace crowdprof
