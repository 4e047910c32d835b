// PNG I/O for the comparator: 8-bit RGBA in, 8-bit RGBA out (files: common/file_io.hpp).
// libspng keeps the PNG path free of OpenImageIO's ~350 ms process start-up cost.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <stdexcept>
#include <vector>

#include "common/file_io.hpp"
#include "image/rgba_image.hpp"

namespace aosuite {

// Decodes any PNG (grey, palette, 16-bit, tRNS, ...) to RGBA8. No gamma or colour
// management is applied. `name` is only used in error messages. (compare/opencv.hpp has
// the cv::Mat forms.)
RgbaImage decode_png(std::span<const unsigned char> png, const std::string& name);
// The decoder for every kind (libspng), which decode_png uses for what the fast one leaves:
// it accepts and refuses exactly the files the fast one does (png_layout.hpp has the rule).
RgbaImage decode_png_general(std::span<const unsigned char> png, const std::string& name);
RgbaImage read_png(const std::filesystem::path& path);
// A 16-bit PNG kept at 16 bits: R, G, B (or grey alone) as v / 65535, alpha dropped
// (image/picture.hpp reads every kind of file).
FloatImage decode_png16(std::span<const unsigned char> png, const std::string& name);
// Checks that the PNG decodes, as decode_png would, and returns its size; for the common
// 8-bit RGB(A) kind it skips unfiltering the pixels nobody will look at.
ImageSize check_png(std::span<const unsigned char> png, const std::string& name);

std::vector<unsigned char> encode_png_rgba8(RgbaView rgba, int compression_level);
// compression_level 1..9 (zlib); 3 is the usual speed/size knee for diff images.
void write_png_rgba8(const std::filesystem::path& path, RgbaView rgba, int compression_level = 3);

}  // namespace aosuite
