#include "compare/channel_stats.hpp"

#include <algorithm>
#include <cstdlib>

namespace aosuite::comparison {

void ChannelStats::add(const unsigned char* expected, const unsigned char* actual,
                       std::uint64_t count, std::uint64_t first) {
  // Per channel sums in 32 bits over short runs (a run of 2^16 pixels cannot overflow them),
  // so the inner loop vectorises; the 64-bit totals take each run.
  constexpr std::uint64_t kRun = 1 << 16;
  for (std::uint64_t start = 0; start < count; start += kRun) {
    const std::uint64_t n = std::min(kRun, count - start);
    std::array<std::int32_t, 4> sums{};
    std::uint32_t abs_sum = 0, differing_here = 0;
    int run_max = 0;
    for (std::uint64_t i = 0; i < n; ++i) {
      const unsigned char* e = expected + 4 * (start + i);
      const unsigned char* a = actual + 4 * (start + i);
      int pixel_max = 0;
      for (int c = 0; c < 4; ++c) {
        const int d = int(a[c]) - int(e[c]);
        sums[std::size_t(c)] += d;
        const int ad = std::abs(d);
        abs_sum += std::uint32_t(ad);
        pixel_max = std::max(pixel_max, ad);
      }
      differing_here += pixel_max > 0;
      run_max = std::max(run_max, pixel_max);
    }
    if (run_max > max_delta) {  // rare: find where, once per new maximum
      for (std::uint64_t i = 0; i < n; ++i) {
        const unsigned char* e = expected + 4 * (start + i);
        const unsigned char* a = actual + 4 * (start + i);
        int pixel_max = 0;
        for (int c = 0; c < 4; ++c)
          pixel_max = std::max(pixel_max, std::abs(int(a[c]) - int(e[c])));
        if (pixel_max == run_max) {
          at = std::int64_t(first + start + i);
          break;
        }
      }
      max_delta = run_max;
    }
    for (std::size_t c = 0; c < 4; ++c) sum_signed[c] += sums[c];
    sum_abs += abs_sum;
    differing += differing_here;
  }
  pixels += count;
}

void ChannelStats::merge(const ChannelStats& s) {
  if (s.max_delta > max_delta || (s.max_delta == max_delta && s.at >= 0 && (at < 0 || s.at < at))) {
    max_delta = s.max_delta, at = s.at;
  }
  differing += s.differing, pixels += s.pixels, sum_abs += s.sum_abs;
  for (std::size_t c = 0; c < 4; ++c) sum_signed[c] += s.sum_signed[c];
}

double ChannelStats::mean_shift() const {
  if (pixels == 0) return 0;
  std::int64_t most = 0;
  for (const std::int64_t s : sum_signed) most = std::max(most, s < 0 ? -s : s);
  return double(most) / double(pixels);
}

double ChannelStats::mean_delta() const {
  return pixels == 0 ? 0 : double(sum_abs) / (4.0 * double(pixels));
}

}  // namespace aosuite::comparison
