// libaosuite_codecs.so: JPEG (libjpeg-turbo), WebP (libwebp), TIFF (libtiff), Radiance HDR,
// Targa and BMP, the formats renderers write after PNG and EXR, each read with its own library
// (or a few lines here) rather than OpenImageIO, whose Debian build maps OpenCV, FFmpeg, DCMTK and
// OpenVDB into the process (about 350 ms of start-up). Same entry point as libaosuite_oiio.so
// (image/image_library.hpp); returns 2 for a file it leaves to that library (another format, or a
// variant such as a CMYK JPEG or a tiled TIFF). The JPEG and WebP decoders are here, the others in
// codec_*.cpp.

// jpeglib.h uses size_t and FILE without declaring them: their C headers come first.
// clang-format off
#include <stddef.h>
#include <stdio.h>
#include <jpeglib.h>
#include <jerror.h>  // JWRN_JPEG_EOF
// clang-format on
#include <webp/decode.h>

#include <algorithm>
#include <csetjmp>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>

#include "image/codecs.hpp"
#include "image/format_signature.hpp"
#include "image/image_library.hpp"

namespace aosuite::codecs {

// WebP as RGBA, as a canvas holds it (OpenImageIO 2.4 multiplies colour by alpha whatever it
// is asked, which cannot be undone exactly).
int read_webp(const unsigned char* bytes, std::size_t size, Allocate allocate, void* user,
              std::string& why) {
  int width = 0, height = 0;
  if (!WebPGetInfo(bytes, size, &width, &height)) {
    why = "not a WebP image libwebp decodes";
    return 1;
  }
  auto* pixels = static_cast<std::uint8_t*>(allocate(user, width, height, 4, 1));
  if (!pixels) {
    why = "refused";
    return 1;
  }
  const std::size_t stride = std::size_t(width) * 4;
  if (!WebPDecodeRGBAInto(bytes, size, pixels, stride * std::size_t(height), int(stride))) {
    why = "libwebp could not decode it";
    return 1;
  }
  return 0;
}

namespace {

// libjpeg reports a fatal error by calling error_exit, which must not return: it jumps back
// to read_jpeg with the message.
struct JpegError {
  jpeg_error_mgr mgr;
  std::jmp_buf back;
  char message[JMSG_LENGTH_MAX];
};

[[noreturn]] void jpeg_fail(j_common_ptr cinfo) {
  auto* e = reinterpret_cast<JpegError*>(cinfo->err);
  e->mgr.format_message(cinfo, e->message);
  std::longjmp(e->back, 1);
}

// Warnings go unprinted, but one is fatal: libjpeg decodes a cut file to the end by padding it
// with grey, and Pillow refuses it ("image file is truncated"), so aosuite does too.
void jpeg_warn(j_common_ptr cinfo, int level) {
  if (level < 0 && cinfo->err->msg_code == JWRN_JPEG_EOF) jpeg_fail(cinfo);
}

// Reads every scanline and drops it: a CMYK or YCCK file left to OpenImageIO, which pads a cut
// one silently, is first read through to its end here, so jpeg_warn sees the cut.
void read_through(jpeg_decompress_struct& cinfo) {
  cinfo.out_color_space = JCS_CMYK;
  jpeg_start_decompress(&cinfo);
  JSAMPARRAY row = (*cinfo.mem->alloc_sarray)(reinterpret_cast<j_common_ptr>(&cinfo), JPOOL_IMAGE,
                                              cinfo.output_width * 4, 1);
  while (cinfo.output_scanline < cinfo.output_height) jpeg_read_scanlines(&cinfo, row, 1);
  jpeg_finish_decompress(&cinfo);
}

}  // namespace

// Grey as one channel, colour as RGB, with libjpeg's defaults (the accurate integer IDCT and
// fancy upsampling), as Pillow and OpenImageIO decode. CMYK and YCCK go to OpenImageIO.
// Only plain locals live across the setjmp, so longjmp skips no destructor.
int read_jpeg(const unsigned char* bytes, std::size_t size, Allocate allocate, void* user,
              std::string& why) {
  jpeg_decompress_struct cinfo;
  JpegError err;
  cinfo.err = jpeg_std_error(&err.mgr);
  err.mgr.error_exit = jpeg_fail;
  err.mgr.emit_message = jpeg_warn;
  err.message[0] = 0;
  if (setjmp(err.back)) {
    jpeg_destroy_decompress(&cinfo);
    why = err.message;
    return 1;
  }
  jpeg_create_decompress(&cinfo);
  jpeg_mem_src(&cinfo, bytes, static_cast<unsigned long>(size));
  jpeg_read_header(&cinfo, TRUE);
  if (cinfo.jpeg_color_space == JCS_CMYK || cinfo.jpeg_color_space == JCS_YCCK) {
    read_through(cinfo);
    jpeg_destroy_decompress(&cinfo);
    return kNotMine;
  }
  const bool grey = cinfo.jpeg_color_space == JCS_GRAYSCALE;
  cinfo.out_color_space = grey ? JCS_GRAYSCALE : JCS_RGB;
  jpeg_start_decompress(&cinfo);
  const int channels = grey ? 1 : 3;
  auto* pixels = static_cast<unsigned char*>(
      allocate(user, int(cinfo.output_width), int(cinfo.output_height), channels, 1));
  if (!pixels) {
    jpeg_destroy_decompress(&cinfo);
    why = "refused";
    return 1;
  }
  const std::size_t stride = std::size_t(cinfo.output_width) * std::size_t(channels);
  while (cinfo.output_scanline < cinfo.output_height) {
    JSAMPROW row = pixels + std::size_t(cinfo.output_scanline) * stride;
    jpeg_read_scanlines(&cinfo, &row, 1);
  }
  jpeg_finish_decompress(&cinfo);
  jpeg_destroy_decompress(&cinfo);
  return 0;
}

namespace {

// The decoder for the file's format, or none (GIF and unknown bytes: OpenImageIO's).
using Decoder = int (*)(const unsigned char*, std::size_t, Allocate, void*, std::string&);
Decoder decoder_for(FileFormat f, const char*& format) {
  switch (f) {
    case FileFormat::kJpeg:
      return format = "jpeg", read_jpeg;
    case FileFormat::kWebp:
      return format = "webp", read_webp;
    case FileFormat::kTiff:
      return format = "tiff", read_tiff;
    case FileFormat::kHdr:
      return format = "hdr", read_hdr;
    case FileFormat::kBmp:
      return format = "bmp", read_bmp;
    case FileFormat::kTarga:
      return format = "targa", read_tga;
    case FileFormat::kGif:
    case FileFormat::kUnknown:
      break;
  }
  return nullptr;
}

}  // namespace
}  // namespace aosuite::codecs

extern "C" int aosuite_read_image(const unsigned char* bytes, std::size_t size, const char* file,
                                  aosuite::codecs::Allocate allocate, void* user, char* format,
                                  std::size_t format_len, char* err, std::size_t err_len) {
  namespace cd = aosuite::codecs;
  const char* name = "";
  const cd::Decoder decode =
      cd::decoder_for(aosuite::format_from_signature(bytes, size, file ? file : ""), name);
  if (!decode) return cd::kNotMine;
  std::string why;
  const int rc = decode(bytes, size, allocate, user, why);
  if (rc == cd::kNotMine) return rc;
  aosuite::say(format, format_len, name);
  aosuite::say(err, err_len, why);
  return rc;
}
