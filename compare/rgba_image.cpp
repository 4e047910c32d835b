#include "compare/rgba_image.hpp"

#include <sys/mman.h>

#include <cstdint>
#include <cstring>
#include <new>
#include <stdexcept>

namespace aosuite {

PixelBuffer::PixelBuffer(std::size_t bytes) {
  if (bytes == 0) return;
  void* p = ::mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (p == MAP_FAILED) throw std::bad_alloc();
  data_ = {static_cast<unsigned char*>(p), [bytes](unsigned char* q) { ::munmap(q, bytes); }};
  size_ = bytes;
  constexpr std::uintptr_t kHuge = std::uintptr_t{2} << 20;
  const auto begin = reinterpret_cast<std::uintptr_t>(p);
  const std::uintptr_t first = (begin + kHuge - 1) & ~(kHuge - 1);
  const std::uintptr_t last = (begin + bytes) & ~(kHuge - 1);
  if (last > first) ::madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);
  // Linux >= 5.14; on older kernels this fails harmlessly and pages fault in when touched.
  ::madvise(p, bytes, MADV_POPULATE_WRITE);
}

RgbaImage::RgbaImage(int width, int height)
    : RgbaImage(PixelBuffer(std::size_t(width) * std::size_t(height) * 4), width, height) {}

RgbaImage::RgbaImage(PixelBuffer pixels, int width, int height)
    : pixels_(std::move(pixels)), width_(width), height_(height) {
  if (width < 0 || height < 0 || pixels_.size() < view().bytes()) {
    throw std::invalid_argument("RgbaImage: buffer smaller than width x height x 4");
  }
}

RgbaImage copy_of(RgbaView v) {
  RgbaImage out(v.width, v.height);
  if (v.bytes()) std::memcpy(out.data(), v.data, v.bytes());
  return out;
}

}  // namespace aosuite
