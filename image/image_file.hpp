// Reading an image file of any format aosuite reads into a Picture: the one entry point of the
// readers (PNG and EXR here, the others through image/other_formats.hpp).
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>

#include "image/picture.hpp"

namespace aosuite {

// The file as a Picture: PNG of any kind (16-bit ones as float), EXR (through
// libaosuite_exr.so, opened on the first EXR), or any other format OpenImageIO reads (through
// libaosuite_oiio.so). Throws FileError naming the file and the problem (and, for a file that
// is no image aosuite reads, the formats it reads). `max_bytes` bounds the file and the
// decoded pixels alike.
Picture read_picture(const std::filesystem::path& path, std::uint64_t max_bytes = UINT64_MAX);
Picture decode_picture(std::span<const unsigned char> bytes, const std::string& name,
                       std::uint64_t max_bytes = UINT64_MAX);

// A file's canvas_rgba8(), through the fast PNG decoder for PNGs.
RgbaImage decode_rgba8(std::span<const unsigned char> bytes, const std::string& name,
                       std::uint64_t max_bytes = UINT64_MAX);

}  // namespace aosuite
