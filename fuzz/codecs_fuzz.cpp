// The codecs library's entry point (image/codecs_library.cpp with the TIFF and HDR decoders,
// compiled in) on any bytes: 0 with an image of the size it asked room for, 1 with a one-line
// reason, or 2 (left to OpenImageIO); never a crash, and never more memory than allowed. The
// hand-written RGBE, Targa and BMP readers are the ones to watch; libjpeg, libtiff and libwebp
// come along.
#include <cstring>
#include <string>
#include <vector>

#include "fuzz/fuzz_util.hpp"
#include "image/image_library.hpp"

namespace {

struct Room {
  std::vector<unsigned char> bytes;
};

// As image/other_formats.cpp's allocator: positive sizes, 1 to 4 channels of 1, 2 or 4 bytes,
// a budget (16 MiB here: mutated headers claim huge images).
void* allocate(void* user, int width, int height, int channels, int sample) {
  auto& room = *static_cast<Room*>(user);
  if (width <= 0 || height <= 0 || channels < 1 || channels > 4 ||
      (sample != 1 && sample != 2 && sample != 4))
    aosuite::fuzz::fail("allocate asked for an impossible image");
  const std::size_t n =
      std::size_t(width) * std::size_t(height) * std::size_t(channels) * std::size_t(sample);
  if (n > (std::size_t{16} << 20)) return nullptr;
  room.bytes.assign(n, 0xAB);
  return room.bytes.data();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Room room;
  char format[64] = {}, err[512] = {};
  const int rc =
      // Named .tga: bytes with no signature then go to the Targa reader, which has none.
      aosuite_read_image(data, size, "x.tga", &allocate, &room, format, sizeof format, err,
                         sizeof err);
  if (rc < 0 || rc > 2) aosuite::fuzz::fail("aosuite_read_image returned neither 0, 1 nor 2");
  if (rc == 1 && err[0] == '\0') aosuite::fuzz::fail("failed in silence");
  if (rc == 0 && room.bytes.empty()) aosuite::fuzz::fail("an image without pixels");
  if (rc != 2 && format[0] == '\0') aosuite::fuzz::fail("no format named");
  return 0;
}
