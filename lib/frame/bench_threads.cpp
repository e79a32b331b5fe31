#include "frame/bench_threads.h"

#include <algorithm>
#include <map>
#include <mutex>

namespace crowdprof {

std::shared_ptr<BenchThreads> bench_threads(size_t threads) {
  threads = std::max<size_t>(threads, 1);
  static std::mutex mutex;
  // Weak: the arena and its control go with the last bench that uses them,
  // before static destruction (oneTBB must not be torn down after main()).
  static std::map<size_t, std::weak_ptr<BenchThreads>> made;
  static std::weak_ptr<tbb::global_control> widest;
  static size_t widest_threads = 0;
  std::lock_guard lock(mutex);
  if (std::shared_ptr<BenchThreads> live = made[threads].lock()) return live;
  auto made_now = std::make_shared<BenchThreads>();
  // The worker limit this arena finds: the process's widest control, else oneTBB's default.
  std::shared_ptr<tbb::global_control> control = widest.lock();
  size_t limit =
      control ? widest_threads : tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);
  if (threads > limit) {
    // A wider control replaces the narrower one in every live arena, so that
    // the narrower one dies with this lock and stops capping the new arena.
    control = std::make_shared<tbb::global_control>(tbb::global_control::max_allowed_parallelism, threads);
    widest = control;
    widest_threads = threads;
    for (auto& [count, entry] : made)
      if (std::shared_ptr<BenchThreads> other = entry.lock(); other && other->parallelism) other->parallelism = control;
  }
  made_now->parallelism = control;
  made_now->arena = std::make_unique<tbb::task_arena>(static_cast<int>(threads));
  made[threads] = made_now;
  return made_now;
}

}  // namespace crowdprof
