#include "common/thread_beside.hpp"

#include <sched.h>

#include <memory>
#include <system_error>

namespace aosuite {
namespace {

void* run(void* work) {
  const std::unique_ptr<std::function<void()>> owned(static_cast<std::function<void()>*>(work));
  (*owned)();
  return nullptr;
}

// Every CPU the process may use but the caller's, in `attr`; none such (one CPU, or more
// than a cpu_set_t holds) leaves the placement to the kernel.
void elsewhere(pthread_attr_t& attr) {
  const int here = sched_getcpu();
  cpu_set_t cpus;
  if (here < 0 || here >= CPU_SETSIZE || sched_getaffinity(0, sizeof cpus, &cpus) != 0) return;
  CPU_CLR(here, &cpus);
  if (CPU_COUNT(&cpus) > 0) pthread_attr_setaffinity_np(&attr, sizeof cpus, &cpus);
}

}  // namespace

ThreadBeside::ThreadBeside(std::function<void()> work) {
  auto owned = std::make_unique<std::function<void()>>(std::move(work));
  pthread_attr_t attr;
  pthread_attr_init(&attr);
  elsewhere(attr);
  const int error = pthread_create(&thread_, &attr, run, owned.get());
  pthread_attr_destroy(&attr);
  if (error != 0) throw std::system_error(error, std::generic_category(), "starting a thread");
  owned.release();  // run() owns it now
}

ThreadBeside::ThreadBeside(ThreadBeside&& other) noexcept
    : thread_(other.thread_), joinable_(other.joinable_) {
  other.joinable_ = false;
}

ThreadBeside::~ThreadBeside() {
  if (joinable_) pthread_join(thread_, nullptr);
}

}  // namespace aosuite
