#include "common/thread_beside.hpp"

#include <gtest/gtest.h>
#include <pthread.h>
#include <sched.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

#include "common/cpu_set.hpp"

namespace aosuite {
namespace {

cpu_set_t my_cpus() {
  cpu_set_t cpus;
  EXPECT_EQ(sched_getaffinity(0, sizeof cpus, &cpus), 0);
  return cpus;
}

cpu_set_t just(int cpu) {
  cpu_set_t one;
  CPU_ZERO(&one);
  CPU_SET(cpu, &one);
  return one;
}

// Sets this thread's CPUs for the test's length, then gives the old ones back.
class PinnedTo {
 public:
  explicit PinnedTo(const cpu_set_t& cpus) : old_(my_cpus()) {
    EXPECT_EQ(sched_setaffinity(0, sizeof cpus, &cpus), 0);
  }
  ~PinnedTo() { sched_setaffinity(0, sizeof old_, &old_); }
  PinnedTo(const PinnedTo&) = delete;
  PinnedTo& operator=(const PinnedTo&) = delete;

 private:
  cpu_set_t old_;
};

// Waits (at most 10 s) until `flag` is set.
bool wait_for(const std::atomic<bool>& flag) {
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (!flag.load()) {
    if (std::chrono::steady_clock::now() > give_up) return false;
    std::this_thread::yield();
  }
  return true;
}

TEST(ThreadBeside, RunsTheWorkAndJoinsItOnDestruction) {
  std::atomic<int> done = 0;
  {
    std::vector<ThreadBeside> threads;  // moved as it grows
    for (int i = 0; i < 8; ++i) {
      threads.emplace_back([&] {
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
        ++done;
      });
    }
  }
  EXPECT_EQ(done.load(), 8);
}

// The set a new thread gets: the creator's CPUs less the one it is on, when any remain.
TEST(ThreadBeside, CpusBesideLeaveOutTheCreatorsCpu) {
  const auto set = [](std::initializer_list<int> cpus) {
    cpu_set_t s;
    CPU_ZERO(&s);
    for (int c : cpus) CPU_SET(c, &s);
    return s;
  };
  const auto same = [](cpu_set_t a, cpu_set_t b) { return CPU_EQUAL(&a, &b) != 0; };
  EXPECT_TRUE(same(cpus_beside(0, set({0, 1})), set({1})));
  EXPECT_TRUE(same(cpus_beside(1, set({0, 1, 2})), set({0, 2})));
  EXPECT_TRUE(same(cpus_beside(3, set({3})), set({3})));         // no other: its own
  EXPECT_TRUE(same(cpus_beside(2, set({0, 1})), set({0, 1})));   // not among them
  EXPECT_TRUE(same(cpus_beside(-1, set({0, 1})), set({0, 1})));  // sched_getcpu failed
  EXPECT_TRUE(same(cpus_beside(CPU_SETSIZE, set({0, 1})), set({0, 1})));
}

// The new thread really gets such a set: one CPU fewer than its creator's, all of them its
// creator's. (Which CPU is left out depends on where the scheduler had the creator, so that is
// checked above, not here.)
TEST(ThreadBeside, TheThreadRunsOnTheCreatorsOtherCpus) {
  const cpu_set_t creator = my_cpus();
  if (CPU_COUNT(&creator) < 2) GTEST_SKIP() << "needs a thread allowed two CPUs";
  for (int round = 0; round < 50; ++round) {
    cpu_set_t seen;
    int ran_on = -1;
    {
      const ThreadBeside t([&] { seen = my_cpus(), ran_on = sched_getcpu(); });
    }
    ASSERT_EQ(CPU_COUNT(&seen), CPU_COUNT(&creator) - 1);
    cpu_set_t both;
    CPU_AND(&both, &seen, &creator);
    ASSERT_TRUE(CPU_EQUAL(&both, &seen)) << "a CPU its creator may not use";
    ASSERT_TRUE(CPU_ISSET(ran_on, &seen));
  }
}

// A creator held to one CPU gives its thread that CPU: there is no other.
TEST(ThreadBeside, ACreatorHeldToOneCpuSharesIt) {
  const cpu_set_t one = just(sched_getcpu());
  const PinnedTo pinned(one);
  cpu_set_t seen;
  {
    const ThreadBeside t([&] { seen = my_cpus(); });
  }
  EXPECT_TRUE(CPU_EQUAL(&seen, &one));
}

TEST(SideBySide, RunsBothAtOnceOnTwoThreads) {
  std::atomic<bool> there_started = false, here_started = false;
  bool there_saw_here = false, here_saw_there = false;
  pthread_t there_thread{};
  side_by_side(
      [&] {
        there_thread = pthread_self();
        there_started = true;
        there_saw_here = wait_for(here_started);
      },
      [&] {
        here_started = true;
        here_saw_there = wait_for(there_started);
      });
  EXPECT_TRUE(there_saw_here && here_saw_there) << "one ran after the other";
  EXPECT_FALSE(pthread_equal(there_thread, pthread_self()));
}

TEST(SideBySide, RethrowsHereFirst) {
  auto throws = [](const char* what) { return [what] { throw std::runtime_error(what); }; };
  auto message = [](auto&& a, auto&& b) {
    try {
      side_by_side(a, b);
    } catch (const std::runtime_error& e) {
      return std::string(e.what());
    }
    return std::string("nothing thrown");
  };
  EXPECT_EQ(message(throws("there"), [] {}), "there");
  EXPECT_EQ(message([] {}, throws("here")), "here");
  EXPECT_EQ(message(throws("there"), throws("here")), "here");
}

TEST(CpuSet, UsableCpusCountsTheThreadsOwn) {
  const cpu_set_t mine = my_cpus();
  EXPECT_EQ(usable_cpus(), CPU_COUNT(&mine));
  const PinnedTo pinned(just(sched_getcpu()));
  EXPECT_EQ(usable_cpus(), 1);
}

// A thread held to one CPU (as a ThreadBeside thread is kept off one) may go wherever the
// main thread may while a MainThreadCpus lives, and is held again after.
TEST(CpuSet, MainThreadCpusWidensForItsLifeOnly) {
  cpu_set_t main;
  ASSERT_EQ(sched_getaffinity(getpid(), sizeof main, &main), 0);
  std::thread([&] {
    const cpu_set_t one = just(sched_getcpu());
    ASSERT_EQ(sched_setaffinity(0, sizeof one, &one), 0);
    {
      const MainThreadCpus everywhere;
      const cpu_set_t during = my_cpus();
      EXPECT_TRUE(CPU_EQUAL(&during, &main));
    }
    const cpu_set_t after = my_cpus();
    EXPECT_TRUE(CPU_EQUAL(&after, &one));
  }).join();
}

}  // namespace
}  // namespace aosuite
