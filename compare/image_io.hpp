// PNG and file I/O for the comparator: 8-bit RGBA in, 8-bit RGBA out, nothing else.
// libspng keeps the PNG path free of OpenImageIO's ~350 ms process start-up cost.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <stdexcept>
#include <vector>

#include "compare/rgba_image.hpp"

namespace aosuite {

// An error about one file. what() is a single line that names the file and the problem.
class FileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Images larger than this are refused before any pixel memory is allocated: 2^28 pixels is
// 1 GiB of RGBA8, already far beyond any render this suite makes.
inline constexpr std::uint64_t kMaxImagePixels = std::uint64_t{1} << 28;

// How long reading a named FIFO waits for its first byte before giving up (no writer?);
// AOSUITE_FIFO_WAIT_MS overrides it.
inline constexpr int kFifoWaitMs = 5000;

// The whole file: regular files, pipes, FIFOs and devices alike, read to end-of-file.
// Throws FileError when it is over max_bytes.
std::vector<unsigned char> read_file(const std::filesystem::path& path,
                                     std::uint64_t max_bytes = UINT64_MAX);

// A file's bytes mapped read-only: no copy and no zeroed buffer, which for image-sized files
// is measurable in a command that runs for a few tens of milliseconds.
// Pipes, FIFOs and devices are read to end-of-file instead (read_file), up to max_bytes.
class MappedFile {
 public:
  explicit MappedFile(const std::filesystem::path& path, std::uint64_t max_bytes = UINT64_MAX);
  ~MappedFile();
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;
  std::span<const unsigned char> bytes() const { return {data_, size_}; }

 private:
  const unsigned char* data_ = nullptr;
  std::size_t size_ = 0;
  std::vector<unsigned char> fallback_;  // for what cannot be mapped (pipes, empty files)
  bool mapped_ = true;
};

// Writes via a temporary file in the same directory and rename(2), so readers only ever see
// the old file or the complete new one.
void write_file_atomic(const std::filesystem::path& path, std::span<const unsigned char> bytes);

// Decodes any PNG (grey, palette, 16-bit, tRNS, ...) to RGBA8. No gamma or colour
// management is applied. `name` is only used in error messages. (compare/opencv.hpp has
// the cv::Mat forms.)
RgbaImage decode_png(std::span<const unsigned char> png, const std::string& name);
// The decoder for every kind (libspng), which decode_png uses for what the fast one leaves:
// it accepts and refuses exactly the files the fast one does (png_layout.hpp has the rule).
RgbaImage decode_png_general(std::span<const unsigned char> png, const std::string& name);
RgbaImage read_png(const std::filesystem::path& path);
struct FloatImage;
// A 16-bit PNG kept at 16 bits: R, G, B (or grey alone) as v / 65535, alpha dropped
// (compare/picture.hpp reads every kind of file).
FloatImage decode_png16(std::span<const unsigned char> png, const std::string& name);
// Checks that the PNG decodes, as decode_png would, and returns its size; for the common
// 8-bit RGB(A) kind it skips unfiltering the pixels nobody will look at.
ImageSize check_png(std::span<const unsigned char> png, const std::string& name);

std::vector<unsigned char> encode_png_rgba8(RgbaView rgba, int compression_level);
// compression_level 1..9 (zlib); 3 is the usual speed/size knee for diff images.
void write_png_rgba8(const std::filesystem::path& path, RgbaView rgba, int compression_level = 3);

}  // namespace aosuite
