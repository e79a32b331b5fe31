// Proves that the ThreadSanitizer run can see races through oneTBB. With a
// oneTBB that was not built with TSan (Debian's), TSan cannot see the
// synchronisation inside the library, so `clean` below (workers write, the
// main thread reads after parallel_for returned) is reported as a race: that
// was the 40-70 reports per threaded run. With oneTBB built with TSan,
// `clean` must report nothing and `race` (two workers adding to one counter)
// must be reported, or the run proves nothing either way.
#include <chrono>
#include <cstdio>
#include <cstring>
#include <mutex>
#include <set>
#include <thread>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

int main(int argc, char** argv) {
  const bool race = argc > 1 && std::strcmp(argv[1], "race") == 0;
  // Four threads even on a 2-core machine, and chunks slow enough that the
  // workers take some: a run on one thread would race with nothing.
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 4);
  std::vector<long> values(256, 0);
  long total = 0;
  std::mutex mutex;
  std::set<std::thread::id> ran_on;
  tbb::parallel_for(tbb::blocked_range<size_t>(0, values.size(), 8), [&](const tbb::blocked_range<size_t>& r) {
    {
      std::lock_guard lock(mutex);
      ran_on.insert(std::this_thread::get_id());
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
    for (size_t i = r.begin(); i != r.end(); ++i) {
      values[i] = static_cast<long>(i);
      if (race) total += static_cast<long>(i);  // unsynchronised on purpose
    }
  });
  long sum = 0;
  for (long v : values) sum += v;  // after the join: ordered by TBB
  std::printf("%zu threads, sum %ld, racy total %ld\n", ran_on.size(), sum, total);
  if (ran_on.size() < 2) {
    std::fprintf(stderr, "tsan_canary: the loop ran on one thread, so it proves nothing\n");
    return 2;
  }
  return 0;
}
