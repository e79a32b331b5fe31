#include "measuring/other_load.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

namespace crowdprof {

namespace {

double seconds_of(const timeval& t) {
  return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_usec) * 1e-6;
}

}  // namespace

OtherLoadMeter::OtherLoadMeter() : start_(now()) {}

OtherLoadMeter::Snapshot OtherLoadMeter::now() {
  Snapshot s;
  s.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
  rusage self{}, children{};
  getrusage(RUSAGE_SELF, &self);
  getrusage(RUSAGE_CHILDREN, &children);
  s.own_s = seconds_of(self.ru_utime) + seconds_of(self.ru_stime) + seconds_of(children.ru_utime) +
            seconds_of(children.ru_stime);
  // cpu  user nice system idle iowait irq softirq steal guest guest_nice (in clock ticks);
  // guest time is already inside user.
  std::ifstream in("/proc/stat");
  std::string label;
  unsigned long long user = 0, nice = 0, system = 0, idle = 0, iowait = 0, irq = 0, softirq = 0, steal = 0;
  if (!(in >> label >> user >> nice >> system >> idle >> iowait >> irq >> softirq) || label != "cpu") return s;
  in >> steal;  // absent on old kernels: 0
  const long ticks = sysconf(_SC_CLK_TCK);
  if (ticks <= 0) return s;
  s.busy_s = static_cast<double>(user + nice + system + irq + softirq) / static_cast<double>(ticks);
  s.steal_s = static_cast<double>(steal) / static_cast<double>(ticks);
  s.known = true;
  return s;
}

OtherLoad OtherLoadMeter::read() const {
  const Snapshot end = now();
  OtherLoad load;
  load.cores = std::max(1u, std::thread::hardware_concurrency());
  load.wall_s = end.wall_s - start_.wall_s;
  if (!start_.known || !end.known || load.wall_s <= 0) return load;
  load.known = true;
  // /proc/stat counts in ticks (10 ms), so a short window reads a little
  // either side of the truth; never below none, never above every core.
  const double others = (end.busy_s - start_.busy_s) - (end.own_s - start_.own_s);
  load.others_cores = std::clamp(others / load.wall_s, 0.0, static_cast<double>(load.cores));
  load.steal_cores = std::clamp((end.steal_s - start_.steal_s) / load.wall_s, 0.0, static_cast<double>(load.cores));
  return load;
}

}  // namespace crowdprof
