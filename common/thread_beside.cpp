#include "common/thread_beside.hpp"

#include <sched.h>

#include <memory>
#include <system_error>

namespace aosuite {
namespace {

void* run(void* work) noexcept {
  const std::unique_ptr<std::function<void()>> owned(static_cast<std::function<void()>*>(work));
  (*owned)();
  return nullptr;
}

// Every CPU the caller may use but its own, in `attr`; false where there is none (one CPU,
// or more than a cpu_set_t holds), which leaves the placement to the kernel.
bool elsewhere(pthread_attr_t& attr) {
  const int here = sched_getcpu();
  cpu_set_t allowed;
  if (sched_getaffinity(0, sizeof allowed, &allowed) != 0) return false;
  cpu_set_t cpus = cpus_beside(here, allowed);
  return !CPU_EQUAL(&cpus, &allowed) && pthread_attr_setaffinity_np(&attr, sizeof cpus, &cpus) == 0;
}

}  // namespace

cpu_set_t cpus_beside(int here, cpu_set_t allowed) {
  if (here < 0 || here >= CPU_SETSIZE || !CPU_ISSET(here, &allowed) || CPU_COUNT(&allowed) < 2)
    return allowed;
  CPU_CLR(here, &allowed);
  return allowed;
}

ThreadBeside::ThreadBeside(std::function<void()> work) {
  auto owned = std::make_unique<std::function<void()>>(std::move(work));
  pthread_attr_t attr;
  pthread_attr_init(&attr);
  int error = elsewhere(attr) ? pthread_create(&thread_, &attr, run, owned.get()) : -1;
  pthread_attr_destroy(&attr);
  // A set the kernel refuses (a CPU gone offline meanwhile) is no reason to fail: anywhere.
  // glibc's thread then ends without calling run(), so `owned` is still ours.
  if (error != 0) error = pthread_create(&thread_, nullptr, run, owned.get());
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
