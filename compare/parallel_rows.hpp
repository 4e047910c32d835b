// Splits an image's rows into one band per CPU the caller may use. Plain threads rather than
// cv::parallel_for_: the comparator runs once per process, and starting OpenCV's TBB pool
// cost more (~3 ms) than the 1080p comparison itself.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "common/cpu_set.hpp"
#include "common/thread_beside.hpp"

namespace aosuite {

// Calls band(y0, y1) over [0, height), on the calling thread alone when the image is too
// small for a thread to pay for itself (about 2^17 pixels each). `band` must not throw.
template <class Band>
void parallel_rows(int width, int height, Band&& band) {
  const std::size_t pixels = std::size_t(std::max(width, 0)) * std::size_t(std::max(height, 0));
  const auto cpus = static_cast<std::size_t>(usable_cpus());
  const int n = static_cast<int>(std::min({pixels >> 17, cpus, std::size_t(std::max(height, 0))}));
  if (n <= 1) {
    band(0, height);
    return;
  }
  auto edge = [&](int i) { return static_cast<int>(std::int64_t{height} * i / n); };
  std::vector<ThreadBeside> others;  // off this thread's CPU (common/thread_beside.hpp)
  others.reserve(std::size_t(n - 1));
  for (int i = 1; i < n; ++i) others.emplace_back([&, i] { band(edge(i), edge(i + 1)); });
  band(0, edge(1));
}

}  // namespace aosuite
