// Reversing PNG's row filters (None, Sub, Up, Average, Paeth) for 8-bit RGB and RGBA rows,
// the part of a decode that is not inflate.
#pragma once

#include <cstddef>
#include <cstdint>

namespace aosuite {

// The widest kernels the CPU has (four RGBA rows at once with AVX2), or at most the SSE4.1
// ones (two rows at once): for tests and benchmarks of the narrower path.
enum class UnfilterKernels { kBest, kSse41 };

// Rows of room between the unfiltered rows and the filtered ones when unfiltering in place:
// rows are unfiltered up to four at once, each a few pixels behind the one above, so a group's
// output must end before its filtered rows begin (output row y + 2 starts where the filtered
// row y ends, and row y is still being read when row y + 2 starts).
constexpr std::size_t kUnfilterRoomRows = 4;

// Unfilters `rows` rows of `len` bytes, `bpp` (3 or 4) bytes a pixel. Row y was inflated at
// raw + y * (len + 1): its filter type (0..4, already checked), then its bytes; it becomes
// packed at out + y * len. `prev` is the unfiltered row above row 0 (zeros above an image's
// first row).
// In place: raw may lie in out's buffer from out + kUnfilterRoomRows * len on. Each byte of
// out is written only after every byte of raw at or below its address has been read.
void unfilter_rows(const unsigned char* raw, unsigned char* out, const unsigned char* prev,
                   std::size_t len, int bpp, std::uint32_t rows,
                   UnfilterKernels kernels = UnfilterKernels::kBest);

}  // namespace aosuite
