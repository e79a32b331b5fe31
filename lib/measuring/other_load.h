// How much of the machine other processes took while this one ran its
// measured runs: the busy neighbour (another job, a build, a tenant's memory
// traffic on the same cores) that a stored time baseline cannot see, read
// from /proc/stat's busy time less this process's and its children's CPU
// time. A check that ran slower says so when it warns (gate/work_witness.h).
#pragma once

namespace crowdprof {

struct OtherLoad {
  bool known = false;       // false where /proc/stat cannot be read
  double wall_s = 0;        // how long it was measured over
  double others_cores = 0;  // CPU time of every other process over wall_s: 1.0 is a whole core
  double steal_cores = 0;   // time a hypervisor gave this machine's cores to other guests, likewise
  unsigned cores = 0;       // the machine's cores
};

// Started at construction; read() gives the load since then. Children count
// as this process's own once they are waited for (getrusage's RUSAGE_CHILDREN),
// so read it after the runs it covers have ended.
class OtherLoadMeter {
 public:
  OtherLoadMeter();
  OtherLoad read() const;

 private:
  struct Snapshot {
    bool known = false;
    double busy_s = 0, steal_s = 0, own_s = 0, wall_s = 0;
  };
  static Snapshot now();
  Snapshot start_;
};

}  // namespace crowdprof
