// The C entry point of the libraries that read image formats beyond PNG and EXR, which aosuite
// decodes itself: libaosuite_codecs.so (image/codecs_library.cpp: JPEG, WebP, TIFF, HDR, Targa
// and BMP) and libaosuite_oiio.so (image/image_library.cpp: the rarer variants, through
// OpenImageIO). Only
// C types cross the boundary: image/other_formats.cpp opens the library only when a file is
// neither, so a PNG comparison never pays OpenImageIO's start-up.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdio>
#include <string>

extern "C" {

// Decodes an image file held in memory: its first subimage's first `channels` channels (at most
// 4) as samples of `sample` bytes (1: uint8, 2: uint16, 4: float, for anything wider). The
// format comes from the bytes' signature, else from `name`'s extension (Targa has none).
// `allocate(user, width, height, channels, sample)` returns room for width * height * channels
// samples, or nullptr to refuse the size. `format` receives OpenImageIO's format name ("jpeg",
// "tiff", "webp", "hdr", "targa", "bmp", ...). 0 on success; else 1 with a one-line reason in err
// (a refusal by the allocator says only "refused": the allocator keeps its own reason), or 2
// when the file is one the library leaves to another (libaosuite_codecs.so: another format, or
// a variant such as a CMYK JPEG or a tiled TIFF).
int aosuite_read_image(const unsigned char* bytes, std::size_t size, const char* name,
                       void* (*allocate)(void* user, int width, int height, int channels,
                                         int sample),
                       void* user, char* format, std::size_t format_len, char* err,
                       std::size_t err_len);
}

namespace aosuite {

// `text` on one line into a C buffer of `len` bytes (cut to fit): how the libraries fill
// `format` and `err` above.
inline void say(char* out, std::size_t len, std::string text) {
  if (len == 0) return;
  std::replace(text.begin(), text.end(), '\n', ' ');
  std::snprintf(out, len, "%s", text.c_str());
}

}  // namespace aosuite
