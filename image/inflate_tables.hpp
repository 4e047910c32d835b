// Deflate's Huffman decoding tables (RFC 1951 §3.2.2), built as zlib 1.2's inflate_table
// accepts them, and the literal-run table the fast loop (inflate.cpp) reads PNG data with.
//
// A table is indexed by the next `bits` input bits (least significant first). An entry whose
// code is longer than that points at a second-level table indexed by the bits after them.
#pragma once

#include <cstddef>
#include <cstdint>

namespace aosuite::inflate_detail {

// What a code decodes to.
enum class Kind : std::uint32_t {
  kLiteral = 0,  // a byte (literal/length alphabet only)
  kBase = 1,     // a match length, or a distance: base plus extra bits
  kEnd = 2,      // end of block
  kSub = 3,      // the code is longer than the table's bits: see the second-level table
  kInvalid = 4,  // a code zlib refuses when it is read (unused codes of an incomplete set;
                 // fixed codes 286, 287 and distances 30, 31)
};

// Entry layout (32 bits): code length in bits 0-3 (the whole code's, also in second-level
// tables), kind in 4-7, then the literal, or the extra-bit count (second-level bits for kSub)
// in 8-15, and the base (second-level offset for kSub) in 16-31.
struct Entry {
  static constexpr std::uint32_t make(unsigned len, Kind kind, unsigned small, unsigned base) {
    return len | static_cast<std::uint32_t>(kind) << 4 | small << 8 | base << 16;
  }
  static unsigned length(std::uint32_t e) { return e & 15; }
  static Kind kind(std::uint32_t e) { return static_cast<Kind>(e >> 4 & 15); }
  static unsigned small(std::uint32_t e) { return e >> 8 & 255; }
  static unsigned base(std::uint32_t e) { return e >> 16; }
};

constexpr unsigned kLitBits = 9, kDistBits = 8, kCodeLenBits = 7;
// Most entries a complete code can need with those first-level bits (zlib's `enough`).
constexpr std::size_t kLitEnough = 852, kDistEnough = 402, kCodeLenEnough = 128;

enum class Alphabet { kCodeLengths, kLitLen, kDist };

// Builds `table` from `n` code lengths. False where zlib refuses the set: over-subscribed, or
// incomplete unless it is a single code of length 1 (code-length codes must be complete).
// An empty set gives a table of invalid codes (only distances may be empty: a literal/length
// set always has the end-of-block code, and an empty code-length set is refused).
bool build_table(const std::uint8_t* lens, unsigned n, Alphabet alphabet, std::uint32_t* table);

// The fast loop's literal-run table: for each value of the next kLitBits bits, the literals a
// greedy decoder reads from them in a row (up to kMaxRun), and the match length after them
// where its code and extra bits fit too (kRunLength; then up to kMaxRun - 1 literals). Packed
// as `bits used | count << 8 | kRunLength | length's bits << 12 | bytes << 16 | (length - 3)
// << 56`, the bits used alone in the low byte, so that a shift by the entry is a shift by
// them. Where neither a literal nor a length starts, the first-level entry in bits 16-47 and
// the rest 0. `scratch` is kRunScratch entries, the result its last 2^kLitBits.
constexpr std::uint64_t kRunLength = 1u << 11;
constexpr unsigned kMaxRun = 6;
constexpr std::size_t kRunScratch = (std::size_t{2} << kLitBits) - 1;
// `vector` false builds it without AVX2 (what CPUs without it get), for tests.
const std::uint64_t* build_run_table(const std::uint32_t* litlen, const std::uint8_t* lens,
                                     std::uint64_t* scratch, bool vector = true);

}  // namespace aosuite::inflate_detail
