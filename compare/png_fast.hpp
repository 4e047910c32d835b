// A fast decoder for the PNGs renderers and screenshot tools actually write: 8-bit RGB or
// RGBA, not interlaced. libdeflate inflates the whole stream in one call, about twice as
// fast as zlib's streaming inflate inside libspng, which made decode most of a compare's
// run time. Every other kind of PNG goes to libspng.
#pragma once

#include <optional>
#include <span>
#include <string>

#include "compare/rgba_image.hpp"

namespace aosuite {

// Decodes, or returns nullopt when the file is of a kind this decoder leaves to libspng.
// Throws FileError for a corrupt or truncated file of its own kind.
std::optional<RgbaImage> decode_png_fast(std::span<const unsigned char> png,
                                         const std::string& name);

// Everything decode_png_fast checks (chunk CRCs, the zlib stream and its checksum, the row
// filters) without unfiltering the pixels; the image's size.
std::optional<ImageSize> check_png_fast(std::span<const unsigned char> png,
                                        const std::string& name);

}  // namespace aosuite
