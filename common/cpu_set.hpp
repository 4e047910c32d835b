// The CPUs a thread may run on. Header-only, so that libaosuite_exr.so can size and start its
// pool with them without linking the common library.
#pragma once

#include <sched.h>
#include <unistd.h>

#include <algorithm>
#include <thread>

namespace aosuite {

// How many CPUs the calling thread may run on (taskset, cpusets), at least 1: what a pool is
// sized by, where std::thread::hardware_concurrency() counts every online CPU.
inline int usable_cpus() {
  cpu_set_t cpus;
  if (sched_getaffinity(0, sizeof cpus, &cpus) == 0) return std::max(1, CPU_COUNT(&cpus));
  return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

// While alive, the calling thread may run wherever the process's main thread may. A thread
// inherits its creator's CPUs, so a pool started from a ThreadBeside thread (kept off one
// CPU, thread_beside.hpp) would stay off it for good; one started under this guard does not.
class MainThreadCpus {
 public:
  MainThreadCpus() {
    cpu_set_t main;
    saved_ = sched_getaffinity(0, sizeof old_, &old_) == 0 &&
             sched_getaffinity(getpid(), sizeof main, &main) == 0 &&
             sched_setaffinity(0, sizeof main, &main) == 0;
  }
  ~MainThreadCpus() {
    if (saved_) sched_setaffinity(0, sizeof old_, &old_);
  }
  MainThreadCpus(const MainThreadCpus&) = delete;
  MainThreadCpus& operator=(const MainThreadCpus&) = delete;

 private:
  cpu_set_t old_;
  bool saved_ = false;
};

}  // namespace aosuite
