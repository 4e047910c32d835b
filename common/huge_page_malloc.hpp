// Mesa, LLVM and the read-back buffers fault their memory in 4 KB at a time, and on the VMs
// this runs on a page fault costs about 10 us (bench/README.md): 57,700 faults for one 1080p
// render process, 2,400 more per frame. glibc backs malloc with transparent huge pages when
// a tunable says so, and reads its tunables only at start-up, so a process that renders
// re-executes itself once with it set: 15,400 faults, none more per frame, a 1080p SAO
// frame 389 -> 260 ms (render_bench). Header-only: the `aosuite` launcher links no renderer.
#pragma once

#include <unistd.h>

#include <cstdlib>
#include <string>

namespace aosuite {

// Returns at once when GLIBC_TUNABLES already names glibc.malloc.hugetlb (set by the user,
// or this process is the re-executed one); else adds it and re-executes /proc/self/exe
// with the same arguments, returning only if that fails.
inline void reexec_with_huge_page_malloc(char** argv) {
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  std::string wanted = tunables ? tunables : "";
  if (wanted.find("glibc.malloc.hugetlb") != std::string::npos) return;
  wanted += wanted.empty() ? "glibc.malloc.hugetlb=1" : ":glibc.malloc.hugetlb=1";
  if (setenv("GLIBC_TUNABLES", wanted.c_str(), 1) != 0) return;
  execv("/proc/self/exe", argv);
}

}  // namespace aosuite
