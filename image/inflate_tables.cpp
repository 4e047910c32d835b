#include "image/inflate_tables.hpp"

#include <immintrin.h>

#include <algorithm>
#include <array>
#include <stdexcept>

namespace aosuite::inflate_detail {
namespace {

// RFC 1951 §3.2.5: lengths 257..285 and distances 0..29.
constexpr std::array<std::uint16_t, 29> kLengthBase = {3,  4,  5,  6,   7,   8,   9,   10,  11, 13,
                                                       15, 17, 19, 23,  27,  31,  35,  43,  51, 59,
                                                       67, 83, 99, 115, 131, 163, 195, 227, 258};
constexpr std::array<std::uint8_t, 29> kLengthExtra = {0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2,
                                                       2, 3, 3, 3, 3, 4, 4, 4, 4, 5, 5, 5, 5, 0};
constexpr std::array<std::uint16_t, 30> kDistBase = {
    1,   2,   3,   4,   5,   7,    9,    13,   17,   25,   33,   49,   65,    97,    129,
    193, 257, 385, 513, 769, 1025, 1537, 2049, 3073, 4097, 6145, 8193, 12289, 16385, 24577};
constexpr std::array<std::uint8_t, 30> kDistExtra = {0, 0, 0,  0,  1,  1,  2,  2,  3,  3,
                                                     4, 4, 5,  5,  6,  6,  7,  7,  8,  8,
                                                     9, 9, 10, 10, 11, 11, 12, 12, 13, 13};

std::uint32_t symbol_entry(Alphabet alphabet, unsigned sym, unsigned len) {
  switch (alphabet) {
    case Alphabet::kCodeLengths:
      return Entry::make(len, Kind::kLiteral, sym, 0);
    case Alphabet::kLitLen:
      if (sym < 256) return Entry::make(len, Kind::kLiteral, sym, 0);
      if (sym == 256) return Entry::make(len, Kind::kEnd, 0, 0);
      if (sym < 286) {
        return Entry::make(len, Kind::kBase, kLengthExtra[sym - 257], kLengthBase[sym - 257]);
      }
      return Entry::make(len, Kind::kInvalid, 0, 0);
    case Alphabet::kDist:
      if (sym < 30) return Entry::make(len, Kind::kBase, kDistExtra[sym], kDistBase[sym]);
      return Entry::make(len, Kind::kInvalid, 0, 0);
  }
  return 0;
}

// The low `len` bits of code (len <= 15), reversed: deflate's codes are read from their most
// significant bit, the tables indexed least significant bit first.
constexpr auto kReversedByte = [] {
  std::array<std::uint8_t, 256> r{};
  for (unsigned v = 0; v < 256; ++v) {
    for (unsigned i = 0; i < 8; ++i)
      r[v] = static_cast<std::uint8_t>(r[v] | (v >> i & 1) << (7 - i));
  }
  return r;
}();
unsigned reverse_bits(unsigned code, unsigned len) {
  return (unsigned{kReversedByte[code & 255]} << 8 | kReversedByte[code >> 8 & 255]) >> (16 - len);
}

}  // namespace

bool build_table(const std::uint8_t* lens, unsigned n, Alphabet alphabet, std::uint32_t* table) {
  const unsigned bits = alphabet == Alphabet::kLitLen ? kLitBits
                        : alphabet == Alphabet::kDist ? kDistBits
                                                      : kCodeLenBits;
  const std::size_t enough = alphabet == Alphabet::kLitLen ? kLitEnough
                             : alphabet == Alphabet::kDist ? kDistEnough
                                                           : kCodeLenEnough;
  const std::size_t size = std::size_t{1} << bits;
  std::array<unsigned, 16> count{};
  for (unsigned s = 0; s < n; ++s) ++count[lens[s]];
  count[0] = 0;
  int left = 1;  // codes of the current length still free
  for (unsigned len = 1; len < 16; ++len) {
    left = 2 * left - static_cast<int>(count[len]);
    if (left < 0) return false;  // over-subscribed
  }
  unsigned max = 15;
  while (max > 0 && count[max] == 0) --max;
  // zlib lets an incomplete set through only as one code of length 1 (not for code lengths,
  // where an empty set fails later anyway: every length would read as 0).
  const bool incomplete = left > 0;
  if (incomplete && (alphabet == Alphabet::kCodeLengths || max > 1)) return false;
  if (incomplete) std::fill_n(table, size, Entry::make(1, Kind::kInvalid, 0, 0));
  if (max == 0) return true;

  // Symbols in canonical order: by length, then value.
  std::array<unsigned, 16> offset{};
  for (unsigned len = 1; len < 15; ++len) offset[len + 1] = offset[len] + count[len];
  std::array<std::uint16_t, 288> sorted;  // the first `total` are set
  unsigned total = 0;
  for (unsigned s = 0; s < n; ++s) {
    if (lens[s] != 0) sorted[offset[lens[s]]++] = static_cast<std::uint16_t>(s), ++total;
  }

  std::array<unsigned, 16> remaining = count;  // codes of each length not yet placed
  unsigned code = 0, len = lens[sorted[0]];
  unsigned sub_prefix = ~0u, sub_bits = 0;
  std::size_t sub_offset = 0, next_sub = size;
  for (unsigned k = 0; k < total; ++k) {
    const unsigned sym = sorted[k], l = lens[sym];
    if (k > 0) code = (code + 1) << (l - len);
    len = l;
    const unsigned rev = reverse_bits(code, l);
    const std::uint32_t e = symbol_entry(alphabet, sym, l);
    if (l <= bits) {
      for (std::size_t i = rev; i < size; i += std::size_t{1} << l) table[i] = e;
    } else {
      const unsigned prefix = rev & static_cast<unsigned>(size - 1);
      if (prefix != sub_prefix) {
        // zlib's rule for a second-level table's size: enough bits to hold every code that
        // shares this prefix, which in canonical order are the ones that follow.
        unsigned curr = l - bits;
        int room = 1 << curr;
        while (curr + bits < max) {
          room -= static_cast<int>(remaining[curr + bits]);
          if (room <= 0) break;
          ++curr;
          room <<= 1;
        }
        sub_prefix = prefix, sub_bits = curr, sub_offset = next_sub;
        next_sub += std::size_t{1} << curr;
        if (next_sub > enough) throw std::logic_error("inflate: table larger than its bound");
        table[prefix] = Entry::make(0, Kind::kSub, sub_bits, static_cast<unsigned>(sub_offset));
      }
      for (std::size_t i = rev >> bits; i < std::size_t{1} << sub_bits;
           i += std::size_t{1} << (l - bits)) {
        table[sub_offset + i] = e;
      }
    }
    --remaining[l];
  }
  return true;
}

namespace {

// One entry of tier r: a length code whose extra bits fit, as the whole length; or a literal
// (length l) followed by the run from the r - l bits after it, which gives up its length, or
// when full its last literal, to make room.
std::uint64_t run_entry(const std::uint32_t* litlen, const std::uint8_t* lens,
                        const std::uint64_t* scratch, unsigned r, std::size_t j) {
  const std::uint32_t e = litlen[j];  // only the low r bits of j decide a code that fits
  const unsigned l = Entry::length(e);
  if (Entry::kind(e) == Kind::kBase && l > 0) {
    const unsigned used = l + Entry::small(e);
    if (used > r) return 0;
    const auto len =
        static_cast<unsigned>(Entry::base(e) + ((j >> l) & ((1u << Entry::small(e)) - 1)));
    return std::uint64_t{len - 3} << 56 | used << 12 | kRunLength | used;
  }
  if (Entry::kind(e) != Kind::kLiteral || l > r) return 0;
  std::uint64_t rest = scratch[(std::size_t{1} << (r - l)) - 1 + (j >> l)];
  const unsigned count = rest >> 8 & 7;
  if ((rest & kRunLength) && count == kMaxRun - 1) {
    rest = (rest & ((std::uint64_t{1} << 56) - 1) & ~std::uint64_t{0xf800}) - (rest >> 12 & 15);
  } else if (count == kMaxRun) {
    rest = (rest & ((std::uint64_t{1} << 56) - 1)) - lens[rest >> 56] - (1u << 8);
  }
  const bool with_length = rest & kRunLength;
  const std::uint64_t bytes = (rest >> 16) & ((std::uint64_t{1} << (with_length ? 40 : 48)) - 1);
  return (bytes << 8 | Entry::small(e)) << 16 |
         (with_length ? rest & (std::uint64_t{255} << 56) : 0) | ((rest & 0xffff) + (1u << 8) + l);
}

// run_entry for four entries at once (r >= 2): about four times faster, and a run table is
// built for every block (16K codes in zlib's blocks).
__attribute__((target("avx2"))) void run_tier_avx2(const std::uint32_t* litlen,
                                                   const std::uint8_t* lens, std::uint64_t* scratch,
                                                   unsigned r) {
  std::uint64_t* tier = scratch + (std::size_t{1} << r) - 1;
  const __m256i vr = _mm256_set1_epi64x(r), one = _mm256_set1_epi64x(1);
  const __m256i low4 = _mm256_set1_epi64x(15), low8 = _mm256_set1_epi64x(255);
  const __m256i zero = _mm256_setzero_si256();
  __m256i j = _mm256_setr_epi64x(0, 1, 2, 3);
  for (std::size_t j0 = 0; j0 < std::size_t{1} << r; j0 += 4) {
    const __m256i e =
        _mm256_cvtepu32_epi64(_mm_loadu_si128(reinterpret_cast<const __m128i*>(litlen + j0)));
    const __m256i l = _mm256_and_si256(e, low4);
    const __m256i literal =
        _mm256_cmpeq_epi64(_mm256_and_si256(_mm256_srli_epi64(e, 4), low4), zero);
    const __m256i fits = _mm256_andnot_si256(
        _mm256_cmpgt_epi64(l, vr), _mm256_andnot_si256(_mm256_cmpeq_epi64(l, zero), literal));
    const __m256i shift = _mm256_blendv_epi8(vr, l, fits);
    const __m256i index =
        _mm256_add_epi64(_mm256_sub_epi64(_mm256_sllv_epi64(one, _mm256_sub_epi64(vr, shift)), one),
                         _mm256_srlv_epi64(j, shift));
    __m256i rest = _mm256_i64gather_epi64(reinterpret_cast<const long long*>(scratch), index, 8);
    // A full run must give up its last literal (run_entry): rare enough to do one at a time.
    const __m256i full =
        _mm256_cmpeq_epi64(_mm256_and_si256(_mm256_srli_epi64(rest, 8), _mm256_set1_epi64x(7)),
                           _mm256_set1_epi64x(kMaxRun));
    // So must a run that ends in a length, and a length code makes one: both one at a time.
    const __m256i length_rest = _mm256_cmpeq_epi64(
        _mm256_and_si256(rest, _mm256_set1_epi64x(kRunLength)), _mm256_set1_epi64x(kRunLength));
    const __m256i length_code =
        _mm256_cmpeq_epi64(_mm256_and_si256(_mm256_srli_epi64(e, 4), low4), _mm256_set1_epi64x(1));
    const int fix = _mm256_movemask_pd(_mm256_castsi256_pd(
        _mm256_or_si256(_mm256_and_si256(_mm256_or_si256(full, length_rest), fits), length_code)));
    const __m256i run = _mm256_or_si256(
        _mm256_or_si256(_mm256_slli_epi64(_mm256_srli_epi64(rest, 16), 24),
                        _mm256_slli_epi64(_mm256_and_si256(_mm256_srli_epi64(e, 8), low8), 16)),
        _mm256_add_epi64(_mm256_and_si256(rest, _mm256_set1_epi64x(0x7ff)),
                         _mm256_add_epi64(l, _mm256_set1_epi64x(1 << 8))));
    // Where no literal run starts, the top tier holds the first-level entry instead.
    const __m256i none = r == kLitBits ? _mm256_slli_epi64(e, 16) : zero;
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(tier + j0), _mm256_blendv_epi8(none, run, fits));
    for (unsigned f = static_cast<unsigned>(fix); f != 0; f &= f - 1) {
      const std::size_t k = j0 + static_cast<unsigned>(__builtin_ctz(f));
      tier[k] = run_entry(litlen, lens, scratch, r, k);
      if (tier[k] == 0 && r == kLitBits) tier[k] = std::uint64_t{litlen[k]} << 16;
    }
    j = _mm256_add_epi64(j, _mm256_set1_epi64x(4));
  }
}

}  // namespace

// Tier r (the 2^r entries at scratch[2^r - 1]) holds the literal run read from exactly r
// bits, built from the smaller tiers (run_entry).
const std::uint64_t* build_run_table(const std::uint32_t* litlen, const std::uint8_t* lens,
                                     std::uint64_t* scratch, bool vector) {
  static const bool has_avx2 = __builtin_cpu_supports("avx2");
  const bool avx2 = vector && has_avx2;
  scratch[0] = 0;
  for (unsigned r = 1; r <= kLitBits; ++r) {
    if (avx2 && r >= 2) {
      run_tier_avx2(litlen, lens, scratch, r);
      continue;
    }
    std::uint64_t* tier = scratch + (std::size_t{1} << r) - 1;
    for (std::size_t j = 0; j < std::size_t{1} << r; ++j)
      tier[j] = run_entry(litlen, lens, scratch, r, j);
  }
  std::uint64_t* top = scratch + (std::size_t{1} << kLitBits) - 1;
  if (!avx2) {
    for (std::size_t j = 0; j < std::size_t{1} << kLitBits; ++j) {
      if (top[j] == 0) top[j] = std::uint64_t{litlen[j]} << 16;
    }
  }
  return top;
}

}  // namespace aosuite::inflate_detail
