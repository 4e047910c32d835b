// A fast decoder for the PNGs renderers and screenshot tools actually write: 8-bit RGB or
// RGBA, not interlaced. Inflate is most of a compare's run time, so the whole stream goes
// through ISA-L's one-call inflate: 14.0 ms for a 1080p image here, against 18.7 ms for
// libdeflate and about twice that for zlib's streaming inflate inside libspng. Every other
// kind of PNG goes to libspng.
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
