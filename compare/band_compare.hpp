// The common comparison straight from two PNG files, a band of rows at a time: each file is
// inflated on its own thread into a small ring of bands, and a band is counted as soon as
// both files have it. Neither image is ever held whole, so a 4K comparison touches about
// 2 MB instead of 66 MB; on the virtual machines this runs on, fresh memory is what costs
// (png_fast.hpp), and the bands stay in cache between decoding and counting.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include "compare/channel_stats.hpp"
#include "compare/resemble.hpp"

namespace aosuite {

// Rows per band for images `width` pixels wide (about 128 KB of pixels, at least one row).
std::uint32_t band_rows_for(std::uint32_t width);

// Resemble's result for the two files (no diff image), when the options reduce to
// per-channel thresholds (resemble::count_only_thresholds) without a canvas model and both
// files are same-sized PNGs of the fast decoder's kind; otherwise nullopt, and the caller
// decodes them whole.
// analysis_ms covers the decoding too: here it is one pass with the counting.
// Throws FileError, naming the file, for a corrupt one (either file when both are: the
// first error found stops both decoders). With `stats`, the bands' channel statistics of b
// (actual) against a (expected) are added to it while they are in cache.
std::optional<resemble::Result> compare_png_bands(std::span<const unsigned char> a,
                                                  const std::string& name_a,
                                                  std::span<const unsigned char> b,
                                                  const std::string& name_b,
                                                  const resemble::Options& options,
                                                  comparison::ChannelStats* stats = nullptr);

}  // namespace aosuite
