// Which image format a file's first bytes say it is (Targa, which has no signature, by its
// extension): one rule for libaosuite_codecs.so and libaosuite_oiio.so, which each route the
// file by it. Header-only: each library carries its own copy.
#pragma once

#include <algorithm>
#include <cctype>
#include <cstddef>
#include <cstring>
#include <string>
#include <string_view>

namespace aosuite {

enum class FileFormat { kUnknown, kJpeg, kWebp, kTiff, kHdr, kBmp, kGif, kTarga };

inline FileFormat format_from_signature(const unsigned char* b, std::size_t n,
                                        std::string_view name) {
  const auto starts = [&](const char* magic, std::size_t at = 0) {
    const std::size_t len = std::strlen(magic);
    return n >= at + len && std::memcmp(b + at, magic, len) == 0;
  };
  if (n >= 3 && b[0] == 0xFF && b[1] == 0xD8 && b[2] == 0xFF) return FileFormat::kJpeg;
  if (starts("RIFF") && starts("WEBP", 8)) return FileFormat::kWebp;
  if (n >= 4 && ((b[0] == 'I' && b[1] == 'I' && b[2] == 42 && b[3] == 0) ||
                 (b[0] == 'M' && b[1] == 'M' && b[2] == 0 && b[3] == 42)))
    return FileFormat::kTiff;
  if (starts("#?RADIANCE") || starts("#?RGBE")) return FileFormat::kHdr;
  if (starts("BM")) return FileFormat::kBmp;
  if (starts("GIF8")) return FileFormat::kGif;
  std::string ext(name.substr(std::min(name.size(), name.rfind('.'))));
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".tga" ? FileFormat::kTarga : FileFormat::kUnknown;
}

}  // namespace aosuite
