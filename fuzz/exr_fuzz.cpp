// EXR reading (image/exr_library.cpp's aosuite_read_exr, compiled in: the fuzz build has no
// libaosuite_exr.so beside its programs) on any bytes: an image of the size it asked room for,
// or a refusal with a one-line reason; never a crash, and never more memory than allowed.
#include <cstring>
#include <string>
#include <vector>

#include "fuzz/fuzz_util.hpp"
#include "image/exr_library.hpp"

namespace {

struct Room {
  std::vector<float> pixels;
  int width = 0, height = 0, channels = 0;
};

// As image/exr_file.cpp's allocator: positive sizes, 1 or 3 channels, a budget (4 Mi floats
// here: mutated headers claim huge windows, and filling them would be most of the run).
float* allocate(void* user, int width, int height, int channels) {
  auto& room = *static_cast<Room*>(user);
  if (width <= 0 || height <= 0 || (channels != 1 && channels != 3)) {
    aosuite::fuzz::fail("allocate asked for an impossible image");
  }
  const std::size_t n = std::size_t(width) * std::size_t(height) * std::size_t(channels);
  if (n > (std::size_t{4} << 20)) return nullptr;
  room.pixels.assign(n, -1.0f);
  room.width = width, room.height = height, room.channels = channels;
  return room.pixels.data();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Room room;
  char err[512] = {};
  const int rc = aosuite_read_exr(data, size, &allocate, &room, err, sizeof err);
  if (rc != 0 && rc != 1) aosuite::fuzz::fail("aosuite_read_exr returned neither 0 nor 1");
  if (rc == 1 && room.pixels.empty() && err[0] == '\0') aosuite::fuzz::fail("refused in silence");
  if (rc == 0 && room.pixels.empty()) aosuite::fuzz::fail("an image without pixels");
  return 0;
}
