// libaosuite_oiio.so: other image formats through OpenImageIO (image/image_library.hpp).
#include "image/image_library.hpp"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <memory>
#include <string>

#include "image/format_signature.hpp"

namespace {

// The extension OpenImageIO's reader registry knows the format by, from the file's signature.
// Anything unrecognised is no image (OpenImageIO's EXR reader, handed two bytes named .exr, spun
// forever); WebP is the codecs library's alone (OpenImageIO 2.4 multiplies its colour by alpha).
std::string extension_from_signature(const unsigned char* b, std::size_t n, const char* name) {
  switch (aosuite::format_from_signature(b, n, name)) {
    case aosuite::FileFormat::kJpeg:
      return "jpg";
    case aosuite::FileFormat::kTiff:
      return "tif";
    case aosuite::FileFormat::kHdr:
      return "hdr";
    case aosuite::FileFormat::kBmp:
      return "bmp";
    case aosuite::FileFormat::kGif:
      return "gif";
    case aosuite::FileFormat::kTarga:
      return "tga";
    case aosuite::FileFormat::kWebp:
    case aosuite::FileFormat::kUnknown:
      break;
  }
  return "";
}

}  // namespace

using aosuite::say;

extern "C" int aosuite_read_image(const unsigned char* bytes, std::size_t size, const char* name,
                                  void* (*allocate)(void*, int, int, int, int), void* user,
                                  char* format, std::size_t format_len, char* err,
                                  std::size_t err_len) {
  try {
    const std::string ext = extension_from_signature(bytes, size, name);
    if (ext.empty()) {
      say(err, err_len, "not an image: no signature of a format aosuite reads");
      return 1;
    }
    // The bytes, never the file: a pipe or FIFO has been read already, and what was checked is
    // what is decoded. The name only tells OpenImageIO which reader to use.
    OIIO::Filesystem::IOMemReader memory(const_cast<unsigned char*>(bytes), size);
    // Colour samples as stored, never multiplied by alpha (what a PNG holds, and a canvas shows).
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    void* proxy = &memory;  // for readers that open again (TIFF does, for some layouts)
    config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
    std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::open("image." + ext, &config, &memory);
    if (!in) {
      // OpenImageIO names the stand-in "image.<ext>": say the file's own name instead.
      std::string why = OIIO::geterror();
      const std::string stand_in = "image." + ext, own = std::filesystem::path(name).filename();
      for (std::size_t at; (at = why.find(stand_in)) != std::string::npos;)
        why.replace(at, stand_in.size(), own);
      say(err, err_len, "cannot be read as ." + ext + ": " + why);
      return 1;
    }
    say(format, format_len, in->format_name());
    const OIIO::ImageSpec& spec = in->spec();
    const int channels = std::min(spec.nchannels, 4);
    const OIIO::TypeDesc stored = spec.format;
    const int sample = stored == OIIO::TypeDesc::UINT8    ? 1
                       : stored == OIIO::TypeDesc::UINT16 ? 2
                                                          : 4;
    if (spec.width <= 0 || spec.height <= 0 || channels <= 0) {
      say(err, err_len, "an empty image");
      return 1;
    }
    void* pixels = allocate(user, spec.width, spec.height, channels, sample);
    if (!pixels) {
      say(err, err_len, "refused");
      return 1;
    }
    const OIIO::TypeDesc as = sample == 1   ? OIIO::TypeDesc::UINT8
                              : sample == 2 ? OIIO::TypeDesc::UINT16
                                            : OIIO::TypeDesc::FLOAT;
    if (!in->read_image(0, 0, 0, channels, as, pixels)) {
      say(err, err_len, std::string(in->format_name()) + ": " + in->geterror());
      return 1;
    }
    return 0;
  } catch (const std::exception& e) {
    say(err, err_len, e.what());
    return 1;
  }
}
