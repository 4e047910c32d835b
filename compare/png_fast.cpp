#include "compare/png_fast.hpp"

#include <emmintrin.h>
#include <fmt/format.h>
#include <libdeflate.h>
#include <sys/mman.h>

#include <cstdint>
#include <cstring>
#include <memory>
#include <vector>

#include "compare/image_io.hpp"

namespace aosuite {
namespace {

std::uint32_t be32(const unsigned char* p) {
  return std::uint32_t{p[0]} << 24 | std::uint32_t{p[1]} << 16 | std::uint32_t{p[2]} << 8 | p[3];
}

int paeth(int a, int b, int c) {
  const int p = a + b - c;
  const int pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
  if (pa <= pb && pa <= pc) return a;
  return pb <= pc ? b : c;
}

// Paeth for 4-byte pixels, a pixel at a time in SSE2 16-bit lanes (the approach of libpng's
// filter_sse2_intrinsics.c): the scalar loop's per-byte branches made it the slowest filter.
void unpaeth4(unsigned char* row, const unsigned char* prev, std::size_t len) {
  const __m128i zero = _mm_setzero_si128();
  auto load4 = [&](const unsigned char* p) {
    std::int32_t v;
    std::memcpy(&v, p, 4);
    return _mm_unpacklo_epi8(_mm_cvtsi32_si128(v), zero);
  };
  auto abs16 = [&](__m128i v) { return _mm_max_epi16(v, _mm_sub_epi16(zero, v)); };
  __m128i a = zero, c = zero;
  for (std::size_t i = 0; i < len; i += 4) {
    const __m128i b = load4(prev + i);
    const __m128i pa = abs16(_mm_sub_epi16(b, c));  // |p - a| with p = a + b - c
    const __m128i pb = abs16(_mm_sub_epi16(a, c));
    const __m128i pc = abs16(_mm_add_epi16(_mm_sub_epi16(b, c), _mm_sub_epi16(a, c)));
    const __m128i smallest = _mm_min_epi16(pc, _mm_min_epi16(pa, pb));
    const __m128i use_a = _mm_cmpeq_epi16(smallest, pa), use_b = _mm_cmpeq_epi16(smallest, pb);
    const __m128i b_or_c = _mm_or_si128(_mm_and_si128(use_b, b), _mm_andnot_si128(use_b, c));
    const __m128i pred = _mm_or_si128(_mm_and_si128(use_a, a), _mm_andnot_si128(use_a, b_or_c));
    const __m128i d = _mm_and_si128(_mm_add_epi16(load4(row + i), pred), _mm_set1_epi16(0xff));
    const std::int32_t out = _mm_cvtsi128_si32(_mm_packus_epi16(d, d));
    std::memcpy(row + i, &out, 4);
    a = d;
    c = b;
  }
}

// Reverses one row's filter in place; `prev` is the previous unfiltered row (zeros for row 0).
template <int Bpp>
bool unfilter(int type, unsigned char* row, const unsigned char* prev, std::size_t len) {
  switch (type) {
    case 0:
      return true;
    case 1:
      for (std::size_t i = Bpp; i < len; ++i)
        row[i] = static_cast<unsigned char>(row[i] + row[i - Bpp]);
      return true;
    case 2:
      for (std::size_t i = 0; i < len; ++i) row[i] = static_cast<unsigned char>(row[i] + prev[i]);
      return true;
    case 3:
      for (std::size_t i = 0; i < Bpp; ++i)
        row[i] = static_cast<unsigned char>(row[i] + (prev[i] >> 1));
      for (std::size_t i = Bpp; i < len; ++i) {
        row[i] = static_cast<unsigned char>(row[i] + ((row[i - Bpp] + prev[i]) >> 1));
      }
      return true;
    case 4:
      if constexpr (Bpp == 4) {
        unpaeth4(row, prev, len);
        return true;
      }
      for (std::size_t i = 0; i < Bpp; ++i) row[i] = static_cast<unsigned char>(row[i] + prev[i]);
      for (std::size_t i = Bpp; i < len; ++i) {
        row[i] = static_cast<unsigned char>(row[i] + paeth(row[i - Bpp], prev[i], prev[i - Bpp]));
      }
      return true;
    default:
      return false;
  }
}

// A byte buffer for a whole image. Fresh pages cost a fault each on first touch, which on
// virtual machines is most of a decode's time: ask for transparent huge pages instead.
cv::Mat big_buffer(std::size_t bytes) {
  cv::Mat m(1, static_cast<int>(bytes), CV_8U);
  constexpr std::uintptr_t kHuge = std::uintptr_t{2} << 20;
  const auto begin = reinterpret_cast<std::uintptr_t>(m.data);
  const std::uintptr_t first = (begin + kHuge - 1) & ~(kHuge - 1);
  const std::uintptr_t last = (begin + bytes) & ~(kHuge - 1);
  if (last > first) ::madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);
  // Fault every page in with one call rather than one fault per page (Linux >= 5.14; on
  // older kernels this fails harmlessly and pages fault in as they are touched).
  const std::uintptr_t page_begin = begin & ~std::uintptr_t{4095};
  ::madvise(reinterpret_cast<void*>(page_begin), begin + bytes - page_begin, MADV_POPULATE_WRITE);
  return m;
}

struct Decompressor {
  libdeflate_decompressor* d = libdeflate_alloc_decompressor();
  ~Decompressor() { libdeflate_free_decompressor(d); }
};

}  // namespace

std::optional<cv::Mat> decode_png_fast(std::span<const unsigned char> png,
                                       const std::string& name) {
  auto corrupt = [&](const char* why) {
    return FileError(fmt::format("{}: {}: truncated or corrupt PNG", name, why));
  };
  // Signature (checked by the caller), then IHDR must come first.
  if (png.size() < 8 + 25 || be32(&png[8]) != 13 || std::memcmp(&png[12], "IHDR", 4) != 0) {
    return std::nullopt;
  }
  const std::uint32_t w = be32(&png[16]), h = be32(&png[20]);
  const int depth = png[24], colour = png[25], interlace = png[28];
  if (depth != 8 || (colour != 2 && colour != 6) || interlace != 0 || w == 0 || h == 0 ||
      w > 65535 || h > 65535 || std::uint64_t{w} * h > kMaxImagePixels) {
    return std::nullopt;  // libspng decodes (or refuses) everything else
  }
  // Gather IDAT, verifying each chunk's CRC as libspng would.
  std::vector<std::span<const unsigned char>> idat;
  std::size_t pos = 8, total = 0;
  bool ended = false;
  while (!ended) {
    if (pos + 12 > png.size()) throw corrupt("file ends inside a chunk");
    const std::uint32_t len = be32(&png[pos]);
    if (len > png.size() - pos - 12) throw corrupt("file ends inside a chunk");
    const unsigned char* type = &png[pos + 4];
    const std::uint32_t crc = be32(&png[pos + 8 + len]);
    const bool critical = !(type[0] & 0x20);
    if (critical && libdeflate_crc32(0, type, len + 4) != crc) throw corrupt("chunk CRC mismatch");
    if (std::memcmp(type, "IDAT", 4) == 0) {
      idat.emplace_back(&png[pos + 8], len);
      total += len;
    } else if (std::memcmp(type, "tRNS", 4) == 0 || std::memcmp(type, "PLTE", 4) == 0) {
      return std::nullopt;  // a transparent colour key: leave it to libspng
    }
    ended = std::memcmp(type, "IEND", 4) == 0;
    pos += 12 + len;
  }
  if (idat.empty()) throw corrupt("no image data");
  std::vector<unsigned char> joined;
  std::span<const unsigned char> stream = idat.front();
  if (idat.size() > 1) {
    joined.reserve(total);
    for (const auto& s : idat) joined.insert(joined.end(), s.begin(), s.end());
    stream = joined;
  }
  const int bpp = colour == 6 ? 4 : 3;
  const std::size_t row_len = std::size_t{w} * bpp;
  // Inflate into one buffer, unfilter in place, then close up the filter bytes so that for
  // RGBA the same memory becomes the image: no second image-sized allocation or copy.
  cv::Mat raw = big_buffer((row_len + 1) * h);
  static thread_local Decompressor dec;
  std::size_t got = 0;
  const libdeflate_result rc =
      libdeflate_zlib_decompress(dec.d, stream.data(), stream.size(), raw.data, raw.total(), &got);
  if (rc != LIBDEFLATE_SUCCESS || got != raw.total()) throw corrupt("bad or short image data");

  const std::vector<unsigned char> zeros(row_len, 0);
  const unsigned char* prev = zeros.data();
  cv::Mat out = bpp == 4 ? cv::Mat() : big_buffer(std::size_t{w} * h * 4);
  for (std::uint32_t y = 0; y < h; ++y) {
    unsigned char* row = raw.data + y * (row_len + 1) + 1;
    const bool ok = bpp == 4 ? unfilter<4>(row[-1], row, prev, row_len)
                             : unfilter<3>(row[-1], row, prev, row_len);
    if (!ok) throw corrupt("unknown row filter");
    if (bpp == 4) {
      // Row y moves y + 1 bytes left; the previous row's unfiltered bytes stay readable
      // because rows only ever move left over bytes already consumed.
      unsigned char* dst = raw.data + y * row_len;
      std::memmove(dst, row, row_len);
      prev = dst;
    } else {
      unsigned char* dst = out.data + std::size_t{y} * w * 4;
      for (std::uint32_t x = 0; x < w; ++x) {
        dst[4 * x] = row[3 * x], dst[4 * x + 1] = row[3 * x + 1], dst[4 * x + 2] = row[3 * x + 2];
        dst[4 * x + 3] = 255;
      }
      prev = row;
    }
  }
  if (bpp == 4) out = raw.colRange(0, static_cast<int>(row_len * h));
  return out.reshape(4, static_cast<int>(h));
}

}  // namespace aosuite
