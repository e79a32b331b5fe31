// The threads a parallel bench runs its copies on: one oneTBB task arena per
// thread count, shared by every bench of the process that asks for that many.
#pragma once

#include <cstddef>
#include <memory>

#include <tbb/global_control.h>
#include <tbb/task_arena.h>

namespace crowdprof {

struct BenchThreads {
  // More threads than cores are given, not silently capped by TBB's default
  // worker limit (one per core): the control lifts it while the arena lives.
  // One control for the process, set to the most threads any live arena asks
  // for, shared by every arena above the default (oneTBB applies the smallest
  // of the live controls, so one per arena would cap the larger arenas).
  std::shared_ptr<tbb::global_control> parallelism;
  std::unique_ptr<tbb::task_arena> arena;
};

// The arena of `threads` threads (at least 1), made on first use and kept while
// a bench holds it. Shared, not one per bench: oneTBB's workers serve one arena
// at a time and come to another only after it has asked for them for a while,
// so with an arena per bench `compare` (modes interleaved in blocks of frames)
// would run a mode's first frames after another's block on the calling thread
// alone, slower than the same frames with every thread (docs/experiments.md).
// Thread-safe.
std::shared_ptr<BenchThreads> bench_threads(size_t threads);

// How many slots a thread of `threads` may be given in its arena: oneTBB gives
// an arena at least two (the caller's and a worker's), even one of one thread,
// and two outside threads executing in it at once take both. What a per-thread
// scratch indexed by tbb::this_task_arena::current_thread_index() needs.
inline size_t arena_slots(size_t threads) {
  return threads < 2 ? 2 : threads;
}

}  // namespace crowdprof
