#include "common/thread_beside.hpp"

#include <gtest/gtest.h>
#include <pthread.h>
#include <sched.h>

#include <atomic>
#include <stdexcept>
#include <vector>

namespace aosuite {
namespace {

cpu_set_t my_cpus() {
  cpu_set_t cpus;
  EXPECT_EQ(pthread_getaffinity_np(pthread_self(), sizeof cpus, &cpus), 0);
  return cpus;
}

// Sets this thread's CPUs for the test's length, then gives the old ones back.
class PinnedTo {
 public:
  explicit PinnedTo(const cpu_set_t& cpus) : old_(my_cpus()) {
    EXPECT_EQ(pthread_setaffinity_np(pthread_self(), sizeof cpus, &cpus), 0);
  }
  ~PinnedTo() { pthread_setaffinity_np(pthread_self(), sizeof old_, &old_); }
  PinnedTo(const PinnedTo&) = delete;
  PinnedTo& operator=(const PinnedTo&) = delete;

 private:
  cpu_set_t old_;
};

TEST(ThreadBeside, RunsTheWorkAndJoinsItOnDestruction) {
  std::atomic<int> done = 0;
  {
    std::vector<ThreadBeside> threads;
    for (int i = 0; i < 8; ++i) threads.emplace_back([&] { ++done; });  // moved as it grows
  }
  EXPECT_EQ(done.load(), 8);
}

// The new thread may use every CPU its creator may, but the one the creator was on.
TEST(ThreadBeside, NeverRunsOnItsCreatorsCpu) {
  const cpu_set_t creator = my_cpus();
  if (CPU_COUNT(&creator) < 2) GTEST_SKIP() << "needs a process allowed two CPUs";
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

// A creator held to one CPU leaves its thread there too: there is nowhere else.
TEST(ThreadBeside, OneCpuLeavesThePlacementToTheKernel) {
  cpu_set_t one;
  CPU_ZERO(&one);
  CPU_SET(sched_getcpu(), &one);
  const PinnedTo pinned(one);
  cpu_set_t seen;
  {
    const ThreadBeside t([&] { seen = my_cpus(); });
  }
  EXPECT_TRUE(CPU_EQUAL(&seen, &one));
}

TEST(SideBySide, RunsBothAndRethrowsHereFirst) {
  int there = 0, here = 0;
  side_by_side([&] { there = 1; }, [&] { here = 1; });
  EXPECT_EQ(there + here, 2);

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

}  // namespace
}  // namespace aosuite
