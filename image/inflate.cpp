#include "image/inflate.hpp"

#include <immintrin.h>
#include <isa-l/igzip_lib.h>

#include <algorithm>
#include <array>
#include <cstring>

#include "image/inflate_tables.hpp"

namespace aosuite {

using inflate_detail::Alphabet;
using inflate_detail::Entry;
using inflate_detail::kDistBits;
using inflate_detail::Kind;
using inflate_detail::kLitBits;

namespace {

constexpr std::size_t kWindow = 32768;
// The fast loop runs while a whole iteration cannot pass the ends of its buffers: four
// literal runs (8-byte stores) and a match (258 bytes, stores up to 64 past it) of output;
// three 8-byte refills, each moving at most 7 bytes, of input.
constexpr std::size_t kFastOutRoom = 4 * 8 + 258 + 64;
constexpr std::size_t kFastInRoom = 32;

std::uint64_t load64(const unsigned char* p) {
  std::uint64_t v;
  std::memcpy(&v, p, 8);
  return v;
}
void store64(unsigned char* p, std::uint64_t v) { std::memcpy(p, &v, 8); }
std::uint64_t low_bits(std::uint64_t v, unsigned n) {
  return n >= 64 ? v : v & ((std::uint64_t{1} << n) - 1);
}

// A match at most 8 bytes back repeats the last d bytes written: byte k of it is byte
// 8 - d + k % d of those 8 (both 16-byte lanes of a shuffle hold them). Stored 32 bytes at a
// time, kStep[d] apart, the largest multiple of d that fits.
constexpr auto kPattern = [] {
  std::array<std::array<std::uint8_t, 32>, 9> p{};
  for (unsigned d = 1; d <= 8; ++d) {
    for (unsigned k = 0; k < 32; ++k) p[d][k] = static_cast<std::uint8_t>(8 - d + k % d);
  }
  return p;
}();
constexpr std::array<std::uint8_t, 9> kStep = {0, 32, 32, 30, 32, 30, 30, 28, 32};
// n % d for n < 256, d <= 8 without a division: n - d * (n * kRecip[d] >> 16).
constexpr std::array<std::uint32_t, 9> kRecip = {0,     65536, 32768, 21846, 16384,
                                                 13108, 10923, 9363,  8192};
constexpr bool recip_exact() {
  for (unsigned d = 1; d <= 8; ++d) {
    for (unsigned n = 0; n < 256; ++n) {
      if (n - d * (n * kRecip[d] >> 16) != n % d) return false;
    }
  }
  return true;
}
static_assert(recip_exact());

enum class Phase { kHeader, kBlock, kStored, kCodes, kTrailer, kEnd, kBad };
enum class Step { kMore, kFull, kBlockEnd, kBad };

}  // namespace

struct Inflater::State {
  Source source;
  bool fast_ok = false;
  Phase phase = Phase::kHeader;
  bool final_block = false, eof = false;
  const unsigned char *in = nullptr, *in_end = nullptr;
  std::uint64_t bits = 0;  // above `nbits` only zeros or the input's next bits
  unsigned nbits = 0;
  std::uint32_t stored_left = 0;
  unsigned pending_len = 0, pending_dist = 0;  // the rest of a match a full buffer cut
  // The output: this call's, and the stream's last kWindow bytes before it.
  unsigned char *out_begin = nullptr, *out = nullptr, *out_end = nullptr;
  unsigned char* summed = nullptr;  // where the output not yet in `adler` starts
  std::array<unsigned char, kWindow> window{};
  std::size_t window_fill = 0;
  std::uint32_t adler = 1;

  // The block's codes: first-level tables and their second levels, and the literal runs
  // (`runs` points into run_scratch).
  std::array<std::uint32_t, inflate_detail::kLitEnough> lit_table{};
  std::array<std::uint32_t, inflate_detail::kDistEnough> dist_table{};
  std::array<std::uint64_t, inflate_detail::kRunScratch> run_scratch{};
  const std::uint64_t* runs = nullptr;
  std::array<std::uint8_t, 288 + 32> lens{};

  std::size_t available() const { return window_fill + static_cast<std::size_t>(out - out_begin); }
  // The byte `back` bytes before p (back <= available at p).
  unsigned char byte_back(const unsigned char* p, std::size_t back) const {
    const auto here = static_cast<std::size_t>(p - out_begin);
    return back <= here ? p[-static_cast<std::ptrdiff_t>(back)]
                        : window[window_fill - (back - here)];
  }

  // The 8 bytes before p, the last in the top byte (zeros before the stream's start).
  std::uint64_t last8(const unsigned char* p) const {
    const std::size_t have = window_fill + static_cast<std::size_t>(p - out_begin);
    std::uint64_t v = 0;
    for (std::size_t back = 1; back <= 8 && back <= have; ++back) {
      v |= std::uint64_t{byte_back(p, back)} << (64 - 8 * back);
    }
    return v;
  }

  void consume(unsigned n) { bits >>= n, nbits -= n; }
  bool next_piece();
  void refill();
  Step careful_symbol();
  void copy_careful(unsigned len, unsigned dist);
  Step huffman();
  Step fast();
  bool read_block_header();
  bool read_dynamic_tables();
  void use_fixed_tables();
  void run();
  void keep_window();
};

bool Inflater::State::next_piece() {
  bits = low_bits(bits, nbits);  // nothing above nbits may outlive the piece it came from
  const std::span<const unsigned char> piece = source();
  if (piece.empty()) return !(eof = true);
  in = piece.data(), in_end = piece.data() + piece.size();
  return true;
}

// At least 56 bits, or all that is left; never 64 (the fast loop's refill shifts by nbits).
void Inflater::State::refill() {
  while (nbits < 56) {
    if (in == in_end && (eof || !next_piece())) return;
    bits |= std::uint64_t{*in++} << nbits;
    nbits += 8;
  }
}

// Copies a match a byte at a time as far as the output allows; the rest waits.
void Inflater::State::copy_careful(unsigned len, unsigned d) {
  const auto room = static_cast<std::size_t>(out_end - out);
  const unsigned n = static_cast<unsigned>(std::min<std::size_t>(len, room));
  for (unsigned k = 0; k < n; ++k, ++out) *out = byte_back(out, d);
  pending_len = len - n, pending_dist = d;
}

// Reads one code (a match with its distance) and writes what it stands for, exactly.
Step Inflater::State::careful_symbol() {
  refill();
  std::uint32_t e = lit_table[bits & ((1u << kLitBits) - 1)];
  if (Entry::kind(e) == Kind::kSub) {
    e = lit_table[Entry::base(e) + low_bits(bits >> kLitBits, Entry::small(e))];
  }
  unsigned used = Entry::length(e);
  if (used > nbits || Entry::kind(e) == Kind::kInvalid) return Step::kBad;
  if (Entry::kind(e) == Kind::kLiteral) {
    if (out == out_end) return Step::kFull;
    *out++ = static_cast<unsigned char>(Entry::small(e));
    consume(used);
    return Step::kMore;
  }
  if (Entry::kind(e) == Kind::kEnd) {
    consume(used);
    return Step::kBlockEnd;
  }
  const unsigned len =
      Entry::base(e) + static_cast<unsigned>(low_bits(bits >> used, Entry::small(e)));
  used += Entry::small(e);
  std::uint32_t d = dist_table[(bits >> used) & ((1u << kDistBits) - 1)];
  if (Entry::kind(d) == Kind::kSub) {
    d = dist_table[Entry::base(d) + low_bits(bits >> (used + kDistBits), Entry::small(d))];
  }
  if (Entry::kind(d) != Kind::kBase) return Step::kBad;
  const unsigned dist_at = used + Entry::length(d);
  const unsigned distance =
      Entry::base(d) + static_cast<unsigned>(low_bits(bits >> dist_at, Entry::small(d)));
  used = dist_at + Entry::small(d);
  if (used > nbits || distance > available()) return Step::kBad;
  consume(used);
  copy_careful(len, distance);
  return pending_len > 0 ? Step::kFull : Step::kMore;
}

// Decodes the current block until it ends or the output is full.
Step Inflater::State::huffman() {
  for (;;) {
    if (pending_len > 0) {
      copy_careful(pending_len, pending_dist);
      if (pending_len > 0) return Step::kFull;
    }
    if (fast_ok && static_cast<std::size_t>(in_end - in) >= kFastInRoom &&
        static_cast<std::size_t>(out_end - out) >= kFastOutRoom) {
      const Step s = fast();
      if (s != Step::kMore) return s;
    }
    const Step s = careful_symbol();
    if (s != Step::kMore) return s;
  }
}

// The loop most of a stream is decoded in, while no buffer end is near (kFastInRoom,
// kFastOutRoom): refills without bounds checks, literal runs stored 8 bytes at a time, and
// the last 8 bytes written kept in `hist` for matches up to 8 bytes back. Its speed is the
// chain from one table lookup to the next, so each lookup is issued before the refill that
// follows it (there are always kLitBits bits left for it) and a run entry's low byte is the
// shift itself. kMore where a buffer end came near.
__attribute__((target("avx2,bmi,bmi2"))) Step Inflater::State::fast() {
  const std::uint64_t* const run_table = runs;
  const std::uint32_t *const lit_codes = lit_table.data(), *const dist_codes = dist_table.data();
  std::uint64_t b = bits;
  unsigned nb = nbits;
  const unsigned char* p = in;
  const unsigned char* const p_last = in_end - kFastInRoom;
  unsigned char* o = out;
  unsigned char* const o_last = out_end - kFastOutRoom;
  std::uint64_t hist = last8(o);
  // Locals, not members: stores through `o` may alias any member, which would be reloaded
  // after each one.
  const unsigned char* const begin = out_begin;
  const std::size_t before = window_fill;
  constexpr std::uint64_t kLitMask = (1u << kLitBits) - 1, kDistMask = (1u << kDistBits) - 1;
  const auto refill = [&] {
    b |= load64(p) << nb;
    p += (63 - nb) >> 3;
    nb |= 56;
  };
  // A run entry: literals, a length, or both (inflate_tables.hpp).
  const auto is_run = [](std::uint64_t e) { return (e & 0xf00) != 0; };
  const auto put_run = [&](std::uint64_t run) {
    const std::uint64_t bytes = run >> 16;
    const auto n = static_cast<unsigned>(run >> 8 & 7);
    store64(o, bytes);
    o += n;
    b >>= run & 63;  // one shrx: it masks the count itself
    nb -= static_cast<unsigned>(run & 0xff);
    hist = hist >> (8 * n) | bytes << (63 - 8 * n) << 1;  // n may be 0
  };
  if (nb < kLitBits) refill();
  Step result = Step::kMore;
  while (p <= p_last && o <= o_last) {
    unsigned len = 0;
    std::uint64_t e = run_table[b & kLitMask];  // nb >= kLitBits here
    refill();
    if (is_run(e)) {  // up to four runs before the next refill (4 * kLitBits bits)
      put_run(e);
      if (e & inflate_detail::kRunLength) goto run_length;
      e = run_table[b & kLitMask];
      if (!is_run(e)) goto other;
      put_run(e);
      if (e & inflate_detail::kRunLength) goto run_length;
      e = run_table[b & kLitMask];
      if (!is_run(e)) goto other;
      put_run(e);
      if (e & inflate_detail::kRunLength) goto run_length;
      e = run_table[b & kLitMask];
      if (!is_run(e)) goto other;
      put_run(e);
      if (!(e & inflate_detail::kRunLength)) continue;
    run_length:
      len = static_cast<unsigned>(e >> 56) + 3;
      refill();  // 28 bits for a distance with its extra bits
      goto distance;
    other:
      refill();  // 48 bits for a length and a distance, with their extra bits
    }
    {
      std::uint32_t s = static_cast<std::uint32_t>(e >> 16);
      if (Entry::kind(s) == Kind::kSub) {
        s = lit_codes[Entry::base(s) + _bzhi_u64(b >> kLitBits, Entry::small(s))];
      }
      const unsigned l = Entry::length(s);
      if (Entry::kind(s) == Kind::kLiteral) {  // a code longer than kLitBits
        *o++ = static_cast<unsigned char>(Entry::small(s));
        b >>= l, nb -= l;
        hist = hist >> 8 | std::uint64_t{Entry::small(s)} << 56;
        refill();
        continue;
      }
      if (Entry::kind(s) != Kind::kBase) {
        if (Entry::kind(s) == Kind::kEnd)
          b >>= l, nb -= l, result = Step::kBlockEnd;
        else
          result = Step::kBad;
        break;
      }
      len = static_cast<unsigned>(Entry::base(s) + _bzhi_u64(b >> l, Entry::small(s)));
      b >>= l + Entry::small(s), nb -= l + Entry::small(s);
    }
  distance:
    std::uint32_t d = dist_codes[b & kDistMask];
    if (Entry::kind(d) == Kind::kSub) {
      d = dist_codes[Entry::base(d) + _bzhi_u64(b >> kDistBits, Entry::small(d))];
    }
    if (Entry::kind(d) != Kind::kBase) {
      result = Step::kBad;
      break;
    }
    const unsigned dl = Entry::length(d);
    const auto distance =
        static_cast<unsigned>(Entry::base(d) + _bzhi_u64(b >> dl, Entry::small(d)));
    b >>= dl + Entry::small(d), nb -= dl + Entry::small(d);
    const auto here = static_cast<std::size_t>(o - begin);
    if (distance > before + here) {
      result = Step::kBad;
      break;
    }
    if (distance <= 8) {
      const __m256i last =
          _mm256_broadcastsi128_si256(_mm_cvtsi64_si128(static_cast<long long>(hist)));
      const __m256i pattern = _mm256_shuffle_epi8(
          last, _mm256_loadu_si256(reinterpret_cast<const __m256i*>(kPattern[distance].data())));
      // Two stores whatever the length (most matches fit), then a loop: a loop's exit on
      // every match's length is a branch the predictor keeps missing.
      const unsigned step = kStep[distance];
      _mm256_storeu_si256(reinterpret_cast<__m256i*>(o), pattern);
      _mm256_storeu_si256(reinterpret_cast<__m256i*>(o + step), pattern);
      for (unsigned at = 2 * step; at < len; at += step) {
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(o + at), pattern);
      }
      const __m128i low = _mm256_castsi256_si128(pattern);
      const auto lo = static_cast<std::uint64_t>(_mm_cvtsi128_si64(low));
      const auto hi = static_cast<std::uint64_t>(_mm_extract_epi64(low, 1));
      // The last 8 bytes: for len >= 8 the pattern's from (len - 8) % d on.
      const unsigned n = len - 8, j = 8 * (n - distance * ((n & 255) * kRecip[distance] >> 16));
      const std::uint64_t long_match = lo >> (j & 63) | hi << ((56 - j) & 63) << 8;
      const std::uint64_t short_match = hist >> ((8 * len) & 63) | lo << ((64 - 8 * len) & 63);
      hist = len >= 8 ? long_match : short_match;
    } else if (distance <= here) {
      // The last 8 bytes are read from the source where it lies wholly before the copy: read
      // back from what was just stored, they would wait for the stores to retire.
      const unsigned char* src = o - distance;
      const std::uint64_t first = load64(src);
      const std::uint64_t tail = len <= distance ? load64(src + (len >= 8 ? len - 8 : 0)) : 0;
      if (distance >= 32) {
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(o),
                            _mm256_loadu_si256(reinterpret_cast<const __m256i*>(src)));
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(o + 32),
                            _mm256_loadu_si256(reinterpret_cast<const __m256i*>(src + 32)));
        for (unsigned at = 64; at < len; at += 32) {
          _mm256_storeu_si256(reinterpret_cast<__m256i*>(o + at),
                              _mm256_loadu_si256(reinterpret_cast<const __m256i*>(src + at)));
        }
      } else {
        for (unsigned at = 0; at < len; at += 8) store64(o + at, load64(src + at));
      }
      hist = len < 8           ? hist >> (8 * len) | first << (64 - 8 * len)
             : len <= distance ? tail
                               : load64(o + len - 8);
    } else {  // from the window kept from the call before
      for (unsigned k = 0; k < len; ++k) o[k] = byte_back(o + k, distance);
      hist = last8(o + len);
    }
    o += len;
  }
  bits = b, nbits = nb, in = p, out = o;
  return result;
}

void Inflater::State::use_fixed_tables() {
  std::fill_n(lens.begin(), 144, 8);
  std::fill_n(lens.begin() + 144, 112, 9);
  std::fill_n(lens.begin() + 256, 24, 7);
  std::fill_n(lens.begin() + 280, 8, 8);
  std::fill_n(lens.begin() + 288, 32, 5);
  inflate_detail::build_table(lens.data(), 288, Alphabet::kLitLen, lit_table.data());
  inflate_detail::build_table(lens.data() + 288, 32, Alphabet::kDist, dist_table.data());
  runs = inflate_detail::build_run_table(lit_table.data(), lens.data(), run_scratch.data());
}

// zlib's checks, in its order: counts, the code-length code (complete), the lengths (a repeat
// needs a length before it and room after), end-of-block present, both codes acceptable.
bool Inflater::State::read_dynamic_tables() {
  refill();
  if (nbits < 14) return false;
  const unsigned nlen = 257 + (bits & 31), ndist = 1 + (bits >> 5 & 31),
                 ncode = 4 + (bits >> 10 & 15);
  consume(14);
  if (nlen > 286 || ndist > 30) return false;
  static constexpr std::array<std::uint8_t, 19> kOrder = {16, 17, 18, 0, 8,  7, 9,  6, 10, 5,
                                                          11, 4,  12, 3, 13, 2, 14, 1, 15};
  std::array<std::uint8_t, 19> code_lens{};
  for (unsigned i = 0; i < ncode; ++i) {
    refill();
    if (nbits < 3) return false;
    code_lens[kOrder[i]] = static_cast<std::uint8_t>(bits & 7);
    consume(3);
  }
  std::array<std::uint32_t, inflate_detail::kCodeLenEnough> code_table;  // a complete code fills it
  if (!inflate_detail::build_table(code_lens.data(), 19, Alphabet::kCodeLengths,
                                   code_table.data())) {
    return false;
  }
  // Distance lengths go to lens[288..]; a repeat may cross from one set into the other.
  lens.fill(0);
  const auto slot = [&](unsigned i) -> std::uint8_t& {
    return lens[i < nlen ? i : 288 + i - nlen];
  };
  for (unsigned have = 0; have < nlen + ndist;) {
    refill();
    const std::uint32_t e = code_table[bits & ((1u << inflate_detail::kCodeLenBits) - 1)];
    const unsigned l = Entry::length(e), sym = Entry::small(e);
    if (sym < 16) {
      if (l > nbits) return false;
      consume(l);
      slot(have++) = static_cast<std::uint8_t>(sym);
      continue;
    }
    static constexpr std::array<unsigned, 3> kExtra = {2, 3, 7}, kMin = {3, 3, 11};
    const unsigned extra = kExtra[sym - 16];
    if (l + extra > nbits) return false;
    const unsigned copies = kMin[sym - 16] + static_cast<unsigned>(low_bits(bits >> l, extra));
    consume(l + extra);
    if ((sym == 16 && have == 0) || have + copies > nlen + ndist) return false;
    const std::uint8_t value = sym == 16 ? slot(have - 1) : 0;
    for (unsigned k = 0; k < copies; ++k) slot(have++) = value;
  }
  if (lens[256] == 0) return false;
  if (!inflate_detail::build_table(lens.data(), nlen, Alphabet::kLitLen, lit_table.data()) ||
      !inflate_detail::build_table(lens.data() + 288, ndist, Alphabet::kDist, dist_table.data())) {
    return false;
  }
  runs = inflate_detail::build_run_table(lit_table.data(), lens.data(), run_scratch.data());
  return true;
}

bool Inflater::State::read_block_header() {
  refill();
  if (nbits < 3) return false;
  final_block = bits & 1;
  const unsigned type = bits >> 1 & 3;
  consume(3);
  switch (type) {
    case 0: {
      consume(nbits & 7);
      refill();
      if (nbits < 32) return false;
      const auto len = static_cast<std::uint32_t>(bits & 0xffff);
      if ((bits >> 16 & 0xffff) != (~len & 0xffff)) return false;
      consume(32);
      stored_left = len;
      phase = Phase::kStored;
      return true;
    }
    case 1:
      use_fixed_tables();
      phase = Phase::kCodes;
      return true;
    case 2:
      if (!read_dynamic_tables()) return false;
      phase = Phase::kCodes;
      return true;
    default:
      return false;
  }
}

// Saves the stream's last kWindow bytes, for matches from the next call's output.
void Inflater::State::keep_window() {
  const auto made = static_cast<std::size_t>(out - out_begin);
  if (made >= kWindow) {
    std::memcpy(window.data(), out - kWindow, kWindow);
    window_fill = kWindow;
    return;
  }
  const std::size_t keep = std::min(window_fill, kWindow - made);
  std::memmove(window.data(), window.data() + window_fill - keep, keep);
  std::memcpy(window.data() + keep, out_begin, made);
  window_fill = keep + made;
}

void Inflater::State::run() {
  for (;;) {
    switch (phase) {
      case Phase::kHeader: {
        refill();
        if (nbits < 16) return void(phase = Phase::kBad);
        const unsigned cmf = bits & 255, flg = bits >> 8 & 255;
        consume(16);
        const bool ok =
            (cmf & 15) == 8 && (cmf >> 4) <= 7 && (cmf << 8 | flg) % 31 == 0 && !(flg & 0x20);
        phase = ok ? Phase::kBlock : Phase::kBad;
        break;
      }
      case Phase::kBlock:
        if (!read_block_header()) phase = Phase::kBad;
        break;
      case Phase::kStored:
        while (stored_left > 0 && out < out_end) {
          if (nbits >= 8) {  // whole bytes already read ahead
            *out++ = static_cast<unsigned char>(bits);
            consume(8), --stored_left;
            continue;
          }
          if (in == in_end && (eof || !next_piece())) return void(phase = Phase::kBad);
          bits = 0;  // nbits is 0: what lies above came from the bytes copied now
          const std::size_t k =
              std::min<std::size_t>({stored_left, static_cast<std::size_t>(out_end - out),
                                     static_cast<std::size_t>(in_end - in)});
          std::memcpy(out, in, k);
          out += k, in += k, stored_left -= static_cast<std::uint32_t>(k);
        }
        if (stored_left > 0) return;
        phase = final_block ? Phase::kTrailer : Phase::kBlock;
        break;
      case Phase::kCodes:
        switch (huffman()) {
          case Step::kFull:
            return;
          case Step::kBad:
            return void(phase = Phase::kBad);
          default:
            phase = final_block ? Phase::kTrailer : Phase::kBlock;
        }
        break;
      case Phase::kTrailer: {
        consume(nbits & 7);
        refill();
        if (nbits < 32) return void(phase = Phase::kBad);
        const std::uint32_t stored = __builtin_bswap32(static_cast<std::uint32_t>(bits));
        consume(32);
        const auto unsummed = static_cast<std::size_t>(out - summed);
        phase = stored == isal_adler32(adler, summed, unsummed) ? Phase::kEnd : Phase::kBad;
        break;
      }
      case Phase::kEnd:
      case Phase::kBad:
        return;
    }
  }
}

Inflater::Inflater(Source source, Path path) : s_(std::make_unique<State>()) {
  s_->source = std::move(source);
  s_->fast_ok =
      path == Path::kFast && __builtin_cpu_supports("avx2") && __builtin_cpu_supports("bmi2");
}
Inflater::~Inflater() = default;
Inflater::Inflater(Inflater&&) noexcept = default;
Inflater& Inflater::operator=(Inflater&&) noexcept = default;

// A slice at a time, each added to the checksum while it is still in cache: summed after a
// whole band, a large one came back from memory (two thirds of the time on a well
// compressed 1080p render).
std::size_t Inflater::inflate(unsigned char* out, std::size_t n) {
  constexpr std::size_t kSumSlice = 128 << 10;
  State& s = *s_;
  s.out_begin = s.out = s.summed = out;
  unsigned char* const end = out + n;
  do {
    s.out_end = s.out + std::min(kSumSlice, static_cast<std::size_t>(end - s.out));
    s.run();
    s.adler = isal_adler32(s.adler, s.summed, static_cast<std::size_t>(s.out - s.summed));
    s.summed = s.out;
  } while (s.out == s.out_end && s.out != end);
  s.keep_window();
  return static_cast<std::size_t>(s.out - out);
}

bool Inflater::ended() const { return s_->phase == Phase::kEnd; }
bool Inflater::bad() const { return s_->phase == Phase::kBad; }
bool Inflater::ran_out() const { return bad() && s_->eof; }

}  // namespace aosuite
