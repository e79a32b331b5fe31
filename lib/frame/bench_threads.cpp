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
  std::lock_guard lock(mutex);
  if (std::shared_ptr<BenchThreads> live = made[threads].lock()) return live;
  auto made_now = std::make_shared<BenchThreads>();
  if (threads > tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism))
    made_now->parallelism = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, threads);
  made_now->arena = std::make_unique<tbb::task_arena>(static_cast<int>(threads));
  made[threads] = made_now;
  return made_now;
}

}  // namespace crowdprof
