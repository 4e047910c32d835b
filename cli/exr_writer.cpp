// libaosuite_exr.so: the one use of OpenImageIO, writing float EXR images. Loading
// libOpenImageIO takes about 360 ms here (it links some 260 libraries), so it lives in its own
// library that libaosuite_gl.so opens only when a command writes an EXR (write_exr in
// gl_command_util.cpp); only C types cross the boundary.
#include <OpenImageIO/imageio.h>

#include <cstdio>
#include <string>

// Writes a one-channel float image to `path` (EXR by its extension). 0 on success, else 1
// with the reason in err.
extern "C" __attribute__((visibility("default"))) int aosuite_write_exr(
    const char* path, int width, int height, const float* pixels, char* err, std::size_t err_len) {
  auto out = OIIO::ImageOutput::create(path);
  const OIIO::ImageSpec spec(width, height, 1, OIIO::TypeDesc::FLOAT);
  if (out && out->open(path, spec) && out->write_image(OIIO::TypeDesc::FLOAT, pixels) &&
      out->close()) {
    return 0;
  }
  std::snprintf(err, err_len, "%s", OIIO::geterror().c_str());
  return 1;
}
