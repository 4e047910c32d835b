// Four rows of 4-byte pixels unfiltered at once with AVX2, one row per 64-bit lane, for
// png_unfilter.cpp. A pixel of Sub, Average or Paeth waits for the one to its left, so one
// row is a chain of dependent steps; four rows in one vector make four chains for the price
// of one, where two rows in SSE lanes made two.
#pragma once

#include <cstddef>

namespace aosuite {

// Rows need this many pixels for the four-row kernel (its lead-in is 7 steps).
constexpr std::size_t kQuadMinPixels = 8;

bool quad_unfilter_supported();

// Unfilters the four rows whose filter bytes are at raw, raw + (len + 1), ... (any filter
// types, already checked) into out, out + len, ...; `prev` is the unfiltered row above.
// `len` is a multiple of 4 of at least 4 * kQuadMinPixels. The four output rows must end at
// or before raw (unfilter_rows's kUnfilterRoomRows).
void unfilter_quad(const unsigned char* raw, unsigned char* out, const unsigned char* prev,
                   std::size_t len);

}  // namespace aosuite
