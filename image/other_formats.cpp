#include "image/other_formats.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstring>
#include <map>
#include <mutex>
#include <vector>

#include "common/file_io.hpp"
#include "common/printable.hpp"
#include "common/sibling_library.hpp"
#include "image/image_library.hpp"

namespace aosuite {
namespace {

using ReadImage = decltype(aosuite_read_image);

// The reader `library` exports, opened once; nullptr with `why` when it cannot be.
ReadImage* reader(const char* library, std::string& why) {
  struct Entry {
    ReadImage* read = nullptr;
    std::string error;
  };
  static std::map<std::string, Entry> opened;  // images may be decoded on several threads
  static std::mutex lock;
  const std::lock_guard<std::mutex> held(lock);
  auto [it, fresh] = opened.try_emplace(library);
  if (fresh)
    it->second.read = sibling_symbol<ReadImage>(library, "aosuite_read_image", it->second.error);
  why = it->second.error;
  return it->second.read;
}

struct Decoded {
  std::uint64_t max_bytes = 0;
  int width = 0, height = 0, channels = 0, sample = 0;
  std::vector<unsigned char> samples;
  std::string refused;
};

void* allocate(void* user, int width, int height, int channels, int sample) {
  auto& d = *static_cast<Decoded*>(user);
  d.refused = decode_budget_problem(width, height, channels, sample, d.max_bytes);
  if (!d.refused.empty()) return nullptr;
  d.width = width, d.height = height, d.channels = channels, d.sample = sample;
  d.samples.assign(
      std::size_t(width) * std::size_t(height) * std::size_t(channels) * std::size_t(sample), 0);
  return d.samples.data();
}

// OpenImageIO's format names as people write them.
std::string format_label(const std::string& oiio) {
  static const std::map<std::string, std::string> kLabels{
      {"jpeg", "JPEG"},   {"tiff", "TIFF"}, {"webp", "WebP"}, {"hdr", "Radiance HDR"},
      {"targa", "Targa"}, {"bmp", "BMP"},   {"gif", "GIF"}};
  const auto it = kLabels.find(oiio);
  return it == kLabels.end() ? oiio : it->second;
}

// Sample i of channel c as a float in [0, 1] (integers) or as stored (float).
float sample_at(const Decoded& d, std::size_t i, int c) {
  const std::size_t at = i * std::size_t(d.channels) + std::size_t(c);
  if (d.sample == 1) return float(d.samples[at]) / 255.0f;
  if (d.sample == 2) {
    std::uint16_t v;
    std::memcpy(&v, d.samples.data() + 2 * at, 2);
    return float(v) / 65535.0f;
  }
  float v;
  std::memcpy(&v, d.samples.data() + 4 * at, 4);
  return v;
}

}  // namespace

Picture decode_other_format(std::span<const unsigned char> bytes, const std::string& name,
                            std::uint64_t max_bytes) {
  Decoded d;
  d.max_bytes = max_bytes;
  char format[64] = {}, err[512] = {};
  // The codecs library first; OpenImageIO for what it leaves (rare variants), which is then
  // the only reason to load it. A library that cannot be opened
  // leaves the file to the next one, as 2 does.
  int rc = 2;
  std::string unopened;
  for (const char* library : {"libaosuite_codecs.so", "libaosuite_oiio.so"}) {
    if (rc != 2) break;
    std::string why;
    if (ReadImage* read = reader(library, why)) {
      rc = read(bytes.data(), bytes.size(), name.c_str(), &allocate, &d, format, sizeof format, err,
                sizeof err);
    } else {
      unopened = why;
    }
  }
  if (rc == 2) {
    throw FileError(
        fmt::format("{}: cannot read images other than PNG and EXR: {}", name, unopened));
  }
  if (rc != 0) {
    const std::string what = format[0] ? format_label(format) + ": " : std::string();
    throw FileError(printable(fmt::format("{}: {}{} (aosuite reads {})", name, what,
                                          d.refused.empty() ? err : d.refused, kImageFormats)));
  }
  Picture p;
  p.name = name, p.format = format_label(format);
  const std::size_t pixels = std::size_t(d.width) * std::size_t(d.height);
  const bool grey = d.channels <= 2, alpha = d.channels == 2 || d.channels == 4;
  if (d.sample == 1) {
    p.rgba = RgbaImage(d.width, d.height);
    for (std::size_t i = 0; i < pixels; ++i) {
      const unsigned char* in = d.samples.data() + i * std::size_t(d.channels);
      unsigned char* out = p.rgba.data() + 4 * i;
      for (int c = 0; c < 3; ++c) out[c] = in[grey ? 0 : c];
      out[3] = alpha ? in[d.channels - 1] : 255;
    }
    return p;
  }
  // 16-bit and float: R, G, B or grey alone, alpha dropped, as for 16-bit PNG and EXR.
  p.is_float = true;
  FloatImage& f = p.floats;
  f.width = d.width, f.height = d.height, f.channels = grey ? 1 : 3, f.srgb = d.sample == 2;
  f.data.resize(pixels * std::size_t(f.channels));
  for (std::size_t i = 0; i < pixels; ++i)
    for (int c = 0; c < f.channels; ++c)
      f.data[i * std::size_t(f.channels) + std::size_t(c)] = sample_at(d, i, c);
  return p;
}

}  // namespace aosuite
