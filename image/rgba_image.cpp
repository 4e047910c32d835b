#include "image/rgba_image.hpp"

#include <fmt/format.h>
#include <sys/mman.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <new>
#include <stdexcept>
#include <string>

namespace aosuite {
namespace {

// Rounding a buffer up to whole huge pages only pays where the kernel will back them with
// huge pages; with transparent huge pages off it would fault in up to 4x the 4 KB pages.
bool huge_pages_available() {
  static const bool yes = [] {
    std::ifstream f("/sys/kernel/mm/transparent_hugepage/enabled");
    std::string modes;
    std::getline(f, modes);
    return f && modes.find("[never]") == std::string::npos;
  }();
  return yes;
}

}  // namespace

PixelBuffer::PixelBuffer(std::size_t bytes) {
  if (bytes == 0) return;
  // Every buffer is populated in one call (below): on these VMs a 4 KB page faulted on first
  // touch costs about 10 us, and one fault per page was 4.7 ms of a 1080p decode. Buffers of
  // 2 MB and more are also whole, aligned 2 MB pages, as cheap as populating 4 KB pages when
  // the guest's memory is backed by the host (0.2 ms for 2 MB) but 6 ms when it is not (two
  // runs in four of `aosuite compare` at 1080p, strace -T); smaller ones, a band ring, stay
  // in 4 KB pages: 0.4 ms for 1.3 MB, every run. The rounding wastes under one huge page.
  constexpr std::size_t kHuge = std::size_t{2} << 20;
  if (bytes > SIZE_MAX - 2 * kHuge) throw std::bad_alloc();
  const bool huge = bytes >= kHuge && huge_pages_available();
  const std::size_t mapped = huge ? (bytes + kHuge - 1) / kHuge * kHuge : bytes;
  const std::size_t slack = huge ? kHuge : 0;
  void* raw =
      ::mmap(nullptr, mapped + slack, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (raw == MAP_FAILED) throw std::bad_alloc();
  auto* p = static_cast<unsigned char*>(raw);
  if (huge) {  // keep the aligned part, give back the rest
    const auto begin = reinterpret_cast<std::uintptr_t>(raw);
    const std::size_t head = ((begin + kHuge - 1) & ~(kHuge - 1)) - begin;
    if (head) ::munmap(p, head);
    if (slack - head) ::munmap(p + head + mapped, slack - head);
    p += head;
    ::madvise(p, mapped, MADV_HUGEPAGE);
  }
  data_ = {p, [mapped](unsigned char* q) { ::munmap(q, mapped); }};
  size_ = bytes;
  // Linux >= 5.14; on older kernels this fails harmlessly and pages fault in when touched.
  ::madvise(p, mapped, MADV_POPULATE_WRITE);
}

RgbaImage::RgbaImage(int width, int height)
    : RgbaImage(PixelBuffer(std::size_t(width) * std::size_t(height) * 4), width, height) {}

RgbaImage::RgbaImage(PixelBuffer pixels, int width, int height)
    : pixels_(std::move(pixels)), width_(width), height_(height) {
  if (width < 0 || height < 0 || pixels_.size() < view().bytes()) {
    throw std::invalid_argument("RgbaImage: buffer smaller than width x height x 4");
  }
}

std::string decode_budget_problem(int width, int height, int channels, int sample,
                                  std::uint64_t max_bytes) {
  const std::uint64_t pixels = std::uint64_t(width) * std::uint64_t(height);
  if (pixels > kMaxImagePixels) {
    return fmt::format("{}x{} is over the {}-pixel limit", width, height, kMaxImagePixels);
  }
  const std::uint64_t bytes = pixels * std::uint64_t(channels) * std::uint64_t(sample);
  if (bytes <= max_bytes) return "";
  return fmt::format(
      "{}x{} with {} channel(s) needs {} MiB decoded, over the {} MiB memory budget "
      "(--memory-limit MIB)",
      width, height, channels, (bytes + (1 << 20) - 1) >> 20, max_bytes >> 20);
}

RgbaImage copy_of(RgbaView v) {
  RgbaImage out(v.width, v.height);
  if (v.bytes()) std::memcpy(out.data(), v.data, v.bytes());
  return out;
}

}  // namespace aosuite
