#include <tiffio.h>

#include <algorithm>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>

#include "image/codecs.hpp"

namespace aosuite::codecs {
namespace {

// libtiff reads through these from the bytes in memory.
struct Memory {
  const unsigned char* data;
  toff_t size, at = 0;
};

tmsize_t read_at(thandle_t h, void* out, tmsize_t n) {
  auto& m = *static_cast<Memory*>(h);
  const toff_t left = m.at < m.size ? m.size - m.at : 0;
  const toff_t take = n < 0 ? 0 : std::min<toff_t>(left, static_cast<toff_t>(n));
  std::memcpy(out, m.data + m.at, take);
  m.at += take;
  return static_cast<tmsize_t>(take);
}
tmsize_t no_write(thandle_t, void*, tmsize_t) { return 0; }
toff_t seek(thandle_t h, toff_t offset, int whence) {
  auto& m = *static_cast<Memory*>(h);
  m.at = whence == SEEK_SET ? offset : whence == SEEK_CUR ? m.at + offset : m.size + offset;
  return m.at;
}
int no_close(thandle_t) { return 0; }
toff_t size_of(thandle_t h) { return static_cast<Memory*>(h)->size; }
int no_map(thandle_t, void**, toff_t*) { return 0; }
void no_unmap(thandle_t, void*, toff_t) {}

// libtiff's first error, kept for `why`; warnings unprinted.
int keep_error(TIFF*, void* user, const char* module, const char* format, va_list ap) {
  auto& why = *static_cast<std::string*>(user);
  if (!why.empty()) return 1;
  char line[512];
  std::vsnprintf(line, sizeof line, format, ap);
  why = std::string(module ? module : "libtiff") + ": " + line;
  return 1;
}
int quiet(TIFF*, void*, const char*, const char*, va_list) { return 1; }

template <typename T>
T tag(TIFF* t, ttag_t name, T otherwise) {
  T v = otherwise;
  return TIFFGetFieldDefaulted(t, name, &v) ? v : otherwise;
}

}  // namespace

int read_tiff(const unsigned char* bytes, std::size_t size, Allocate allocate, void* user,
              std::string& why) {
  Memory memory{bytes, size};
  TIFFOpenOptions* options = TIFFOpenOptionsAlloc();
  TIFFOpenOptionsSetErrorHandlerExtR(options, keep_error, &why);
  TIFFOpenOptionsSetWarningHandlerExtR(options, quiet, nullptr);
  const std::unique_ptr<TIFF, void (*)(TIFF*)> t(
      TIFFClientOpenExt("TIFF", "rm", &memory, read_at, no_write, seek, no_close, size_of, no_map,
                        no_unmap, options),
      TIFFClose);
  TIFFOpenOptionsFree(options);
  if (!t) {
    if (why.empty()) why = "libtiff cannot open it";  // not every refusal calls the handler
    return 1;
  }
  const auto width = tag<std::uint32_t>(t.get(), TIFFTAG_IMAGEWIDTH, 0);
  const auto height = tag<std::uint32_t>(t.get(), TIFFTAG_IMAGELENGTH, 0);
  const auto channels = tag<std::uint16_t>(t.get(), TIFFTAG_SAMPLESPERPIXEL, 1);
  const auto bits = tag<std::uint16_t>(t.get(), TIFFTAG_BITSPERSAMPLE, 1);
  const auto format = tag<std::uint16_t>(t.get(), TIFFTAG_SAMPLEFORMAT, SAMPLEFORMAT_UINT);
  const auto planar = tag<std::uint16_t>(t.get(), TIFFTAG_PLANARCONFIG, PLANARCONFIG_CONTIG);
  const auto photometric = tag<std::uint16_t>(t.get(), TIFFTAG_PHOTOMETRIC, PHOTOMETRIC_RGB);
  const bool sample_kind = (format == SAMPLEFORMAT_UINT && (bits == 8 || bits == 16)) ||
                           (format == SAMPLEFORMAT_IEEEFP && bits == 32);
  const bool layout = !TIFFIsTiled(t.get()) && planar == PLANARCONFIG_CONTIG &&
                      (photometric == PHOTOMETRIC_MINISBLACK || photometric == PHOTOMETRIC_RGB) &&
                      channels >= 1 && channels <= 4;
  if (!sample_kind || !layout) return kNotMine;
  if (width == 0 || height == 0 || width > INT32_MAX || height > INT32_MAX) {
    why = "an empty or oversized image";
    return 1;
  }
  const int sample = bits / 8;
  const std::size_t row = std::size_t(width) * channels * std::size_t(sample);
  if (static_cast<std::uint64_t>(TIFFScanlineSize64(t.get())) != row) return kNotMine;
  auto* pixels = static_cast<unsigned char*>(
      allocate(user, static_cast<int>(width), static_cast<int>(height), channels, sample));
  if (!pixels) {
    why = "refused";
    return 1;
  }
  for (std::uint32_t y = 0; y < height; ++y) {
    if (TIFFReadScanline(t.get(), pixels + std::size_t(y) * row, y, 0) < 0) {
      if (why.empty()) why = "cannot read row " + std::to_string(y);
      return 1;
    }
  }
  return 0;
}

}  // namespace aosuite::codecs
