// unfilter_rows against the PNG specification's byte-at-a-time definition, on many generated
// cases: random filter sequences (so every mix of four rows the AVX2 kernel takes, and every
// pair the SSE4.1 one takes), widths around the kernels' lead-in and lead-out, RGB and RGBA,
// both kernel choices, laid out in place as the PNG reader lays them out.
#include "image/png_unfilter.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <random>
#include <vector>

namespace aosuite {
namespace {

using Bytes = std::vector<unsigned char>;

// The specification's reconstruction, a byte at a time (PNG 2nd ed., 9.2 and 9.4).
Bytes reference_unfilter(const Bytes& raw, const Bytes& above, std::size_t len, int bpp,
                         std::uint32_t rows) {
  Bytes out(rows * len);
  for (std::uint32_t y = 0; y < rows; ++y) {
    const unsigned char* src = &raw[y * (len + 1)];
    const unsigned char* up = y == 0 ? above.data() : &out[(y - 1) * len];
    unsigned char* dst = &out[y * len];
    for (std::size_t i = 0; i < len; ++i) {
      const int a = i < std::size_t(bpp) ? 0 : dst[i - bpp], b = up[i];
      const int c = i < std::size_t(bpp) ? 0 : up[i - bpp];
      int pred = 0;
      switch (src[0]) {
        case 1:
          pred = a;
          break;
        case 2:
          pred = b;
          break;
        case 3:
          pred = (a + b) / 2;
          break;
        case 4: {
          const int p = a + b - c, pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
          pred = pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
          break;
        }
        default:
          break;
      }
      dst[i] = static_cast<unsigned char>(src[1 + i] + pred);
    }
  }
  return out;
}

TEST(Unfilter, MatchesTheSpecificationForEveryKernelAndFilterMix) {
  std::mt19937 rng(2026);
  int cases = 0;
  for (int bpp : {3, 4}) {
    for (std::size_t w : {1u, 2u, 7u, 8u, 9u, 13u, 14u, 33u, 100u, 257u, 1921u}) {
      for (int round = 0; round < 12; ++round) {
        const std::size_t len = w * bpp;
        const auto rows = static_cast<std::uint32_t>(1 + rng() % 23);
        // Small values make Paeth's ties (a + 2b = 3c) common; full-range ones its branches.
        const int span = round % 3 == 0 ? 4 : 256;
        Bytes raw(rows * (len + 1)), above(len);
        for (auto& v : above) v = static_cast<unsigned char>(rng() % span);
        for (std::uint32_t y = 0; y < rows; ++y) {
          // Some cases all chained filters (Sub, Average, Paeth), some all Paeth, others any.
          constexpr unsigned char kChained[3] = {1, 3, 4};
          const unsigned pick = static_cast<unsigned>(rng());
          raw[y * (len + 1)] = round % 4 == 1   ? kChained[pick % 3]
                               : round % 4 == 2 ? 4
                                                : static_cast<unsigned char>(pick % 5);
          for (std::size_t i = 0; i < len; ++i) {
            raw[y * (len + 1) + 1 + i] = static_cast<unsigned char>(rng() % span);
          }
        }
        const Bytes want = reference_unfilter(raw, above, len, bpp, rows);
        for (UnfilterKernels kernels : {UnfilterKernels::kBest, UnfilterKernels::kSse41}) {
          // The PNG reader's layout: filtered rows from the room's end on, unfiltered in place.
          const std::size_t room = kUnfilterRoomRows * len;
          Bytes buf(room + raw.size());
          std::copy(raw.begin(), raw.end(), buf.begin() + long(room));
          unfilter_rows(buf.data() + room, buf.data(), above.data(), len, bpp, rows, kernels);
          for (std::uint32_t y = 0; y < rows; ++y) {
            for (std::size_t i = 0; i < len; ++i) {
              ASSERT_EQ(buf[y * len + i], want[y * len + i])
                  << "bpp " << bpp << ", width " << w << ", row " << y << " (filter "
                  << int(raw[y * (len + 1)]) << "), byte " << i << ", kernels "
                  << (kernels == UnfilterKernels::kBest ? "best" : "sse4.1");
            }
          }
          ++cases;
        }
      }
    }
  }
  EXPECT_EQ(cases, 2 * 11 * 12 * 2);
}

}  // namespace
}  // namespace aosuite
