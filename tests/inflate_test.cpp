// The inflater (image/inflate.hpp) against zlib 1.2's inflate, which libspng uses: on
// streams zlib writes with every level, strategy, window and memory level, cut into pieces
// and read into bands of every size, both paths give zlib's bytes; on those streams with bits
// flipped, truncated or extended, and on hand-made streams for each of zlib's refusals, they
// accept exactly what zlib accepts.
#include "image/inflate.hpp"

#include <gtest/gtest.h>
#include <zlib.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "image/inflate_tables.hpp"
#include "tests/inflate_harness.hpp"

namespace {

using aosuite::Inflater;
using Bytes = std::vector<unsigned char>;

// Data like what PNG encoders compress, and worse: filtered noisy pixels (matches 3, 4 or 8
// back), periodic patterns of every period up to 40, long runs, text-like and random bytes.
Bytes make_data(std::mt19937& rng, std::size_t n) {
  Bytes out(n);
  const int kind = static_cast<int>(rng() % 6);
  const auto period = static_cast<unsigned>(1 + rng() % 40);
  for (std::size_t i = 0; i < n; ++i) {
    const auto r = static_cast<unsigned>(rng());
    switch (kind) {
      case 0:  // filtered noise: mostly 0 and +-1
        out[i] = r % 10 < 4   ? 0
                 : r % 10 < 6 ? 1
                 : r % 10 < 8 ? 255
                              : static_cast<unsigned char>(r >> 8);
        break;
      case 1:  // a pattern with rare changes
        out[i] = i >= period && r % 64 != 0 ? out[i - period] : static_cast<unsigned char>(r >> 8);
        break;
      case 2:  // runs
        out[i] = i > 0 && r % 200 != 0 ? out[i - 1] : static_cast<unsigned char>(r >> 8);
        break;
      case 3:  // a small alphabet
        out[i] = static_cast<unsigned char>('a' + r % 7);
        break;
      case 4:  // repeats from anywhere in the window
        if (i > 300 && r % 8 != 0) {
          const std::size_t back = 1 + (r >> 8) % std::min<std::size_t>(i, 40000);
          const std::size_t len = std::min<std::size_t>(3 + r % 300, n - i);
          for (std::size_t k = 0; k < len; ++k) out[i + k] = out[i + k - back];
          i += len - 1;
        } else {
          out[i] = static_cast<unsigned char>(r >> 8);
        }
        break;
      default:
        out[i] = static_cast<unsigned char>(r >> 8);
    }
  }
  return out;
}

Bytes compress(const Bytes& data, int level, int strategy, int window, int mem) {
  z_stream z{};
  EXPECT_EQ(deflateInit2(&z, level, Z_DEFLATED, window, mem, strategy), Z_OK);
  Bytes out(deflateBound(&z, data.size()) + 64);
  z.next_in = const_cast<unsigned char*>(data.data());
  z.avail_in = static_cast<uInt>(data.size());
  z.next_out = out.data();
  z.avail_out = static_cast<uInt>(out.size());
  EXPECT_EQ(deflate(&z, Z_FINISH), Z_STREAM_END);
  out.resize(z.total_out);
  deflateEnd(&z);
  return out;
}

// zlib's verdict: the bytes it inflates, and whether it reached the stream's end with a good
// checksum (where it refuses, the bytes it wrote before refusing). Window bits 15, as libspng
// sets them.
struct Verdict {
  Bytes out;
  bool accepted = false;
};
Verdict zlib_inflate(const Bytes& stream) {
  z_stream z{};
  EXPECT_EQ(inflateInit2(&z, 15), Z_OK);
  Verdict v;
  unsigned char buf[1 << 16];
  z.next_in = const_cast<unsigned char*>(stream.data());
  z.avail_in = static_cast<uInt>(stream.size());
  int status = Z_OK;
  while (status == Z_OK) {
    z.next_out = buf;
    z.avail_out = sizeof buf;
    status = inflate(&z, Z_NO_FLUSH);
    v.out.insert(v.out.end(), buf, buf + (sizeof buf - z.avail_out));
    if (status == Z_OK && z.avail_in == 0 && z.avail_out != 0) break;  // ran out of input
  }
  inflateEnd(&z);
  v.accepted = status == Z_STREAM_END;
  return v;
}

using Result = aosuite::testing::Inflated;

Result ours(const Bytes& stream, Inflater::Path path, std::size_t piece, std::size_t band,
            std::size_t limit) {
  return aosuite::testing::inflate_in_pieces(stream, path, piece, band, limit);
}

constexpr std::array<Inflater::Path, 2> kPaths = {Inflater::Path::kFast, Inflater::Path::kCareful};

TEST(Inflate, GivesZlibsBytesForEveryStreamZlibWrites) {
  std::mt19937 rng(20261124);
  constexpr std::array<int, 5> kStrategies = {Z_DEFAULT_STRATEGY, Z_FILTERED, Z_HUFFMAN_ONLY, Z_RLE,
                                              Z_FIXED};
  for (int c = 0; c < 240; ++c) {
    const std::size_t n = c % 10 == 0 ? rng() % 64 : rng() % 300000;
    const Bytes data = make_data(rng, n);
    const int level = static_cast<int>(rng() % 10), strategy = kStrategies[rng() % 5];
    const int window = 9 + static_cast<int>(rng() % 7), mem = 1 + static_cast<int>(rng() % 9);
    const Bytes stream = compress(data, level, strategy, window, mem);
    const std::size_t piece = c % 3 == 0 ? stream.size() : 1 + rng() % 5000;
    const std::size_t band = c % 4 == 0 ? n + 1 : 1 + rng() % 70000;
    for (const Inflater::Path path : kPaths) {
      SCOPED_TRACE("case " + std::to_string(c) + " level " + std::to_string(level) + " strategy " +
                   std::to_string(strategy) + " piece " + std::to_string(piece) + " band " +
                   std::to_string(band) + (path == Inflater::Path::kFast ? " fast" : " careful"));
      const Result r = ours(stream, path, piece, band, n + 1);
      ASSERT_TRUE(r.ended);
      ASSERT_FALSE(r.bad);
      ASSERT_EQ(r.out.size(), n);
      ASSERT_TRUE(r.out == data);
    }
  }
}

// Flipped bits, cut ends and extra bytes: wherever zlib accepts the stream, the same bytes;
// wherever it refuses it, a refusal, with no more output than zlib gave before refusing.
TEST(Inflate, AcceptsExactlyWhatZlibAcceptsWhenStreamsAreDamaged) {
  std::mt19937 rng(7);
  int refused = 0, accepted = 0;
  for (int c = 0; c < 1500; ++c) {
    const Bytes data = make_data(rng, rng() % 20000);
    Bytes stream = compress(data, static_cast<int>(rng() % 10),
                            c % 7 == 0 ? Z_FIXED : Z_DEFAULT_STRATEGY, 15, 8);
    const auto damage = static_cast<unsigned>(rng() % 4);
    if (damage == 0 || damage == 3) {  // flipped bits, more often near the block headers
      const int flips = 1 + static_cast<int>(rng() % 3);
      for (int f = 0; f < flips; ++f) {
        const std::size_t at = rng() % 2 == 0 ? rng() % std::min<std::size_t>(stream.size(), 80)
                                              : rng() % stream.size();
        stream[at] ^= static_cast<unsigned char>(1u << (rng() % 8));
      }
    }
    if (damage == 1) stream.resize(rng() % stream.size());
    if (damage == 2 || damage == 3) {
      for (auto k = rng() % 9; k > 0; --k) stream.push_back(static_cast<unsigned char>(rng()));
    }
    const Verdict expected = zlib_inflate(stream);
    for (const Inflater::Path path : kPaths) {
      SCOPED_TRACE("case " + std::to_string(c));
      const Result r =
          ours(stream, path, 1 + rng() % 3000, 1 + rng() % 30000, expected.out.size() + 4096);
      ASSERT_EQ(r.ended, expected.accepted);
      ASSERT_EQ(r.bad, !expected.accepted);
      ASSERT_TRUE(r.out == expected.out);  // where refused, the same bytes up to the fault
    }
    (expected.accepted ? accepted : refused)++;
  }
  // Both verdicts were exercised many times.
  EXPECT_GT(accepted, 300);
  EXPECT_GT(refused, 300);
}

// Bits written least significant first, as deflate reads them; Huffman codes most
// significant bit first.
class BitWriter {
 public:
  void bits(unsigned value, unsigned n) {
    for (unsigned i = 0; i < n; ++i) put(value >> i & 1);
  }
  void code(unsigned code, unsigned len) {
    for (unsigned i = len; i-- > 0;) put(code >> i & 1);
  }
  // The stream with zlib's header and the Adler-32 of what it should inflate to.
  Bytes zlib(const std::string& inflated = "") {
    Bytes out(2 + bytes_.size());
    out[0] = 0x78, out[1] = 0x01;
    std::copy(bytes_.begin(), bytes_.end(), out.begin() + 2);
    const auto adler = static_cast<std::uint32_t>(adler32(
        1, reinterpret_cast<const Bytef*>(inflated.data()), static_cast<uInt>(inflated.size())));
    for (int shift = 24; shift >= 0; shift -= 8)
      out.push_back(static_cast<unsigned char>(adler >> shift));
    return out;
  }

 private:
  void put(unsigned bit) {
    if (fill_ == 0) bytes_.push_back(0);
    bytes_.back() = static_cast<unsigned char>(bytes_.back() | bit << fill_);
    fill_ = (fill_ + 1) & 7;
  }
  Bytes bytes_;
  unsigned fill_ = 0;
};

// A dynamic block's header: the `litlen` and `dist` code lengths each written as itself, in a
// code-length code giving symbols 0..15 four bits each (complete; no repeats).
void dynamic_header(BitWriter& w, bool final, const std::vector<unsigned>& litlen,
                    const std::vector<unsigned>& dist) {
  w.bits(final, 1);
  w.bits(2, 2);
  w.bits(static_cast<unsigned>(litlen.size() - 257), 5);
  w.bits(static_cast<unsigned>(dist.size() - 1), 5);
  w.bits(19 - 4, 4);
  static constexpr std::array<unsigned, 19> kOrder = {16, 17, 18, 0, 8,  7, 9,  6, 10, 5,
                                                      11, 4,  12, 3, 13, 2, 14, 1, 15};
  for (const unsigned sym : kOrder) w.bits(sym < 16 ? 4 : 0, 3);
  for (const unsigned l : litlen) w.code(l, 4);  // canonical: symbol s has code s
  for (const unsigned l : dist) w.code(l, 4);
}

// A complete literal/length code: 'A' (65) is 0, end-of-block 10, length 3 (257) 11.
std::vector<unsigned> small_litlen() {
  std::vector<unsigned> l(258, 0);
  l[65] = 1, l[256] = 2, l[257] = 2;
  return l;
}

// Each of zlib's refusals, and the odd cases it lets through, made by hand.
TEST(Inflate, RefusesWhatZlibRefusesAndNothingElse) {
  struct Case {
    std::string what;
    Bytes stream;
  };
  std::vector<Case> cases;
  {
    BitWriter w;  // a final fixed block with only end-of-block, then a good Adler-32
    w.bits(1, 1), w.bits(1, 2), w.code(0, 7);
    cases.push_back({"an empty fixed block", w.zlib()});
  }
  {
    BitWriter w;
    w.bits(1, 1), w.bits(3, 2);
    cases.push_back({"block type 3", w.zlib()});
  }
  {
    BitWriter w;  // stored, LEN 0, NLEN not its complement
    w.bits(1, 1), w.bits(0, 2), w.bits(0, 5), w.bits(0, 16), w.bits(0x1234, 16);
    cases.push_back({"stored lengths that disagree", w.zlib()});
  }
  {
    BitWriter w;  // fixed literal/length code 286 (8 bits: 11000110)
    w.bits(1, 1), w.bits(1, 2), w.code(0xc6, 8);
    cases.push_back({"fixed code 286", w.zlib()});
  }
  {
    BitWriter w;  // fixed length 257 (0000001) then distance code 30 (11110)
    w.bits(1, 1), w.bits(1, 2), w.code(0x30 + 'A', 8), w.code(1, 7), w.code(30, 5);
    cases.push_back({"fixed distance code 30", w.zlib()});
  }
  {
    BitWriter w;  // length 3 at distance 1 with nothing written yet
    w.bits(1, 1), w.bits(1, 2), w.code(1, 7), w.code(0, 5), w.code(0, 7);
    cases.push_back({"a distance too far back", w.zlib()});
  }
  {
    BitWriter w;  // 'A', then length 3 distance 2: one byte written, distance 2
    w.bits(1, 1), w.bits(1, 2), w.code(0x30 + 'A', 8), w.code(1, 7), w.code(1, 5), w.code(0, 7);
    cases.push_back({"a distance one past the output", w.zlib("AAAA")});
  }
  const auto dynamic = [&](const std::string& what, std::vector<unsigned> litlen,
                           std::vector<unsigned> dist, bool with_data) {
    BitWriter w;
    dynamic_header(w, true, litlen, dist);
    if (with_data) {
      w.code(0, 1);                      // 'A'
      w.code(3, 2);                      // length 3
      w.code(0, dist[0] ? dist[0] : 1);  // distance code 0: 1 back
    }
    w.code(2, 2);  // end of block
    cases.push_back({what, w.zlib(with_data ? "AAAA" : "")});
  };
  dynamic("a complete dynamic block", small_litlen(), {1, 1}, true);
  dynamic("one distance code of length 1 (incomplete, allowed)", small_litlen(), {1}, true);
  dynamic("one distance code of length 2 (incomplete, refused)", small_litlen(), {2}, false);
  dynamic("no distance codes, none used", small_litlen(), {0}, false);
  dynamic("no distance codes, one used", small_litlen(), {0}, true);
  dynamic("over-subscribed distances", small_litlen(), {1, 1, 1}, false);
  {
    std::vector<unsigned> l = small_litlen();
    l[256] = 0, l[66] = 2;
    dynamic("no end-of-block code", l, {1, 1}, false);
  }
  {
    std::vector<unsigned> l = small_litlen();
    l[66] = 2;
    dynamic("over-subscribed literals", l, {1, 1}, false);
  }
  {
    std::vector<unsigned> l = small_litlen();
    l[257] = 3;
    dynamic("incomplete literals", l, {1, 1}, false);
  }
  {
    BitWriter w;  // HLIT 30 (287 codes): zlib allows at most 286
    w.bits(1, 1), w.bits(2, 2), w.bits(30, 5), w.bits(0, 5), w.bits(15, 4);
    cases.push_back({"287 literal/length codes", w.zlib()});
  }
  {
    BitWriter w;  // a repeat (16) with no length before it
    w.bits(1, 1), w.bits(2, 2), w.bits(0, 5), w.bits(0, 5), w.bits(0, 4);
    w.bits(1, 3), w.bits(0, 3), w.bits(0, 3), w.bits(1, 3);  // 16 and 0 at length 1
    w.code(1, 1), w.bits(0, 2);                              // 16: repeat the last length 3 times
    cases.push_back({"a repeat with nothing to repeat", w.zlib()});
  }
  for (const unsigned copies : {2u, 3u}) {  // lengths ending exactly, or one past the end
    BitWriter w;  // 257 + 2 lengths: 'A' and end-of-block 1 bit each, both distances 1 bit
    w.bits(1, 1), w.bits(2, 2), w.bits(0, 5), w.bits(1, 5), w.bits(18 - 4, 4);
    // Code-length code: 1 is 0, 16 is 10, 18 is 11 (in the header's order 16, 17, 18, 0, ..., 1).
    for (const unsigned len : {2, 0, 2, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1})
      w.bits(len, 3);
    w.code(3, 2), w.bits(65 - 11, 7);                                     // 0..64: 0
    w.code(0, 1);                                                         // 65 ('A'): 1
    w.code(3, 2), w.bits(138 - 11, 7), w.code(3, 2), w.bits(52 - 11, 7);  // 66..255: 0
    w.code(0, 1);                                                         // 256: 1
    if (copies == 3) w.code(2, 2), w.bits(0, 2);  // 257..259: 1, one too many
    if (copies == 2) w.code(0, 1), w.code(0, 1);  // 257, 258: 1
    w.code(0, 1), w.code(1, 1);                   // 'A', end of block
    cases.push_back({"a repeat " + std::to_string(copies - 2) + " past the lengths", w.zlib("A")});
  }
  for (const unsigned flg : {0x02u, 0x20u, 0x9cu, 0xdau}) {  // FCHECK, FDICT, good, good
    Bytes s = cases.front().stream;
    s[1] = static_cast<unsigned char>(flg);
    cases.push_back({"FLG " + std::to_string(flg), s});
  }
  for (const unsigned cmf : {0x08u, 0x88u, 0x77u}) {  // 256-byte window; 64 KB; method 7
    Bytes s = cases.front().stream;
    s[0] = static_cast<unsigned char>(cmf);
    s[1] = static_cast<unsigned char>((31 - (cmf << 8) % 31) % 31);
    cases.push_back({"CMF " + std::to_string(cmf), s});
  }
  {
    Bytes s = cases.front().stream;
    s.back() ^= 1;
    cases.push_back({"a bad Adler-32", s});
    s = cases.front().stream;
    s.insert(s.end(), {1, 2, 3});
    cases.push_back({"bytes after the end", s});
    s = cases.front().stream;
    s.pop_back();
    cases.push_back({"a cut Adler-32", s});
  }
  int zlib_accepts = 0;
  for (const Case& c : cases) {
    const Verdict expected = zlib_inflate(c.stream);
    zlib_accepts += expected.accepted;
    for (const Inflater::Path path : kPaths) {
      const Result r = ours(c.stream, path, c.stream.size(), 1 << 16, 1 << 16);
      EXPECT_EQ(r.ended, expected.accepted) << c.what;
      EXPECT_EQ(r.bad, !expected.accepted) << c.what;
      EXPECT_TRUE(r.out == expected.out) << c.what;
    }
  }
  EXPECT_GE(zlib_accepts, 6);
  EXPECT_LE(zlib_accepts, static_cast<int>(cases.size()) - 12);
}

// Random complete literal/length codes (a code split in two at a random leaf until there
// are enough, end-of-block always among them): the run table built with AVX2 and without is
// the same, and every entry says what reading the plain table code by code says.
TEST(InflateTables, RunTableHoldsWhatTheCodesSay) {
  namespace id = aosuite::inflate_detail;
  std::mt19937 rng(11);
  for (int c = 0; c < 300; ++c) {
    // Half the codes skewed as PNG data makes them: a literal of 1 bit, a length of 2 or 3.
    const bool skewed = c % 2 == 0;
    std::vector<unsigned> leaves = {1, 1};
    const std::size_t want = 3 + rng() % 280;
    while (leaves.size() < want) {
      const std::size_t k = skewed && leaves.size() < 4 ? leaves.size() - 1 : rng() % leaves.size();
      if (leaves[k] == 15) continue;
      ++leaves[k];
      leaves.push_back(leaves[k]);
    }
    std::sort(leaves.begin(), leaves.end());
    std::vector<unsigned> symbols(286);
    for (unsigned i = 0; i < 286; ++i) symbols[i] = i;
    std::shuffle(symbols.begin(), symbols.end(), rng);
    if (skewed) {  // shortest: a literal, then a length, then end-of-block
      std::swap(*std::find_if(symbols.begin(), symbols.end(), [](unsigned v) { return v < 256; }),
                symbols[0]);
      std::swap(
          *std::find_if(symbols.begin() + 1, symbols.end(), [](unsigned v) { return v > 256; }),
          symbols[1]);
    }
    std::swap(*std::find(symbols.begin(), symbols.end(), 256u), symbols[skewed ? 2 : 0]);
    std::array<std::uint8_t, 288 + 32> lens{};
    for (std::size_t k = 0; k < leaves.size(); ++k)
      lens[symbols[k]] = static_cast<std::uint8_t>(leaves[k]);
    std::vector<std::uint32_t> table(id::kLitEnough);
    ASSERT_TRUE(id::build_table(lens.data(), 286, id::Alphabet::kLitLen, table.data()));
    std::vector<std::uint64_t> scratch_a(id::kRunScratch), scratch_b(id::kRunScratch);
    const std::uint64_t* a = id::build_run_table(table.data(), lens.data(), scratch_a.data(), true);
    const std::uint64_t* b =
        id::build_run_table(table.data(), lens.data(), scratch_b.data(), false);
    for (unsigned j = 0; j < 1u << id::kLitBits; ++j) {
      ASSERT_EQ(a[j], b[j]) << "case " << c << " index " << j;
      // Decode j code by code with the plain table: the run's literals, then its length.
      unsigned at = 0, count = 0;
      std::uint64_t bytes = 0;
      bool length = false;
      unsigned length_value = 0;
      for (;;) {
        const std::uint32_t e = table[(j >> at) & ((1u << id::kLitBits) - 1)];
        const unsigned l = id::Entry::length(e);
        if (id::Entry::kind(e) == id::Kind::kLiteral && at + l <= id::kLitBits &&
            count < id::kMaxRun) {
          bytes |= std::uint64_t{id::Entry::small(e)} << (8 * count++);
          at += l;
          continue;
        }
        const unsigned extra = id::Entry::small(e);
        // A length joins up to kMaxRun - 1 literals (the sixth literal's byte holds it).
        if (id::Entry::kind(e) == id::Kind::kBase && l > 0 && at + l + extra <= id::kLitBits &&
            count < id::kMaxRun) {
          length = true;
          length_value = id::Entry::base(e) + ((j >> (at + l)) & ((1u << extra) - 1));
          at += l + extra;
        }
        break;
      }
      const std::uint64_t run = a[j];
      if (count == 0 && !length) {
        EXPECT_EQ(run, std::uint64_t{table[j]} << 16) << "case " << c << " index " << j;
        continue;
      }
      EXPECT_EQ(run & 63, at) << "case " << c << " index " << j;
      EXPECT_EQ(run >> 8 & 7, count) << "case " << c << " index " << j;
      EXPECT_EQ((run & id::kRunLength) != 0, length) << "case " << c << " index " << j;
      EXPECT_EQ(run >> 16 & ((std::uint64_t{1} << (8 * count)) - 1), bytes) << "case " << c;
      if (length) {
        EXPECT_EQ((run >> 56) + 3, length_value) << "case " << c << " index " << j;
      }
    }
  }
}

}  // namespace
