// The comparator's own image type: 8-bit RGBA, rows packed without padding. The comparator
// depends on nothing but the standard library, ISA-L and libspng, because loading
// libopencv_core and its dependencies costs ~6 ms at process start, a fifth of a 1080p
// `aosuite compare`; compare/opencv.hpp views cv::Mat images as these without copying.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace aosuite {

// Images larger than this are refused before any pixel memory is allocated: 2^28 pixels is
// 1 GiB of RGBA8, already far beyond any render this suite makes.
inline constexpr std::uint64_t kMaxImagePixels = std::uint64_t{1} << 28;

// Why width x height pixels of `channels` samples of `sample` bytes cannot be decoded within
// max_bytes ("WxH is over the N-pixel limit", "... needs N MiB decoded, over the N MiB memory
// budget (--memory-limit MIB)"), or "" when they can. Sizes must be positive.
std::string decode_budget_problem(int width, int height, int channels, int sample,
                                  std::uint64_t max_bytes);

struct ImageSize {
  int width = 0, height = 0;
};

// A read-only view of packed RGBA8 pixels owned by someone else.
struct RgbaView {
  const unsigned char* data = nullptr;
  int width = 0, height = 0;

  std::size_t bytes() const { return std::size_t(width) * std::size_t(height) * 4; }
  const unsigned char* row(int y) const { return data + std::size_t(y) * std::size_t(width) * 4; }
};

// Zeroed memory for image-sized buffers, straight from the kernel: transparent huge pages
// and every page faulted in with one call, because on virtual machines first-touch faults
// were most of a decode's time. Copies share the memory, as cv::Mat's do.
class PixelBuffer {
 public:
  PixelBuffer() = default;
  explicit PixelBuffer(std::size_t bytes);  // throws std::bad_alloc
  unsigned char* data() const { return data_.get(); }
  std::size_t size() const { return size_; }

 private:
  std::shared_ptr<unsigned char> data_;
  std::size_t size_ = 0;
};

// An RGBA8 image; its pixels live in a PixelBuffer at least width * height * 4 long, shared
// by copies (copy_of makes a deep copy).
class RgbaImage {
 public:
  RgbaImage() = default;
  RgbaImage(int width, int height);  // transparent black
  // Takes over a buffer already holding the pixels (as the PNG decoder fills it).
  RgbaImage(PixelBuffer pixels, int width, int height);

  int width() const { return width_; }
  int height() const { return height_; }
  bool empty() const { return width_ == 0 || height_ == 0; }
  unsigned char* data() { return pixels_.data(); }
  const unsigned char* data() const { return pixels_.data(); }
  RgbaView view() const { return {pixels_.data(), width_, height_}; }
  operator RgbaView() const { return view(); }  // NOLINT: an image is usable wherever a view is

 private:
  PixelBuffer pixels_;
  int width_ = 0, height_ = 0;
};

RgbaImage copy_of(RgbaView v);

// Float samples, one channel (grey, Y) or three (R, G, B) interleaved, rows packed.
struct FloatImage {
  int width = 0, height = 0;
  int channels = 0;  // 1 or 3
  std::vector<float> data;
  // 16-bit PNGs are sRGB-encoded values v / 65535; EXR holds linear light.
  bool srgb = false;
  const float* row(int y) const {
    return data.data() + std::size_t(y) * std::size_t(width) * std::size_t(channels);
  }
};

}  // namespace aosuite
