// Threads for work that runs beside the caller's, started on other CPUs. Linux starts a new
// thread on its creator's CPU and leaves it to an idle CPU to pull it over when that CPU next
// balances; even once apart, a thread woken by the other (from a lock or a page fault) was
// put back on the waker's CPU. On the 2-vCPU machines measured here, the two decoders of a
// 1080p comparison took turns on one CPU for 3-9 ms of their 15 in most processes
// (bench/README.md, "the two decoders on one CPU").
#pragma once

#include <pthread.h>
#include <sched.h>

#include <exception>
#include <functional>

namespace aosuite {

// `allowed` without `here` (the CPU the creator is on), unless that leaves none or `here` is no
// CPU a cpu_set_t holds: then `allowed` itself. What ThreadBeside gives its thread.
cpu_set_t cpus_beside(int here, cpu_set_t allowed);

// Runs `work` on a new thread, joined on destruction (as std::jthread), allowed every CPU the
// creating thread may use but the one it was on, when there is another (else the creator's
// CPUs). The exclusion is one way and for good: the creator stays free to go anywhere, and
// threads the new one starts inherit its narrowed set (a pool meant for every CPU is started
// under MainThreadCpus, cpu_set.hpp). `work` must not throw: that ends the process.
class ThreadBeside {
 public:
  explicit ThreadBeside(std::function<void()> work);
  ThreadBeside(ThreadBeside&& other) noexcept;
  ThreadBeside& operator=(ThreadBeside&&) = delete;
  ThreadBeside(const ThreadBeside&) = delete;
  ThreadBeside& operator=(const ThreadBeside&) = delete;
  ~ThreadBeside();

 private:
  pthread_t thread_{};
  bool joinable_ = true;
};

// Runs `there` on a ThreadBeside and `here` on this thread; once both are done, rethrows
// what `here` threw, else what `there` threw.
template <class There, class Here>
void side_by_side(There&& there, Here&& here) {
  std::exception_ptr thrown;
  {
    const ThreadBeside other([&] {
      try {
        there();
      } catch (...) {
        thrown = std::current_exception();
      }
    });
    here();
  }
  if (thrown) std::rethrow_exception(thrown);
}

}  // namespace aosuite
