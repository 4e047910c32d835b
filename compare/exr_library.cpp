// libaosuite_exr.so: the one use of OpenImageIO, reading and writing float EXR images.
// Loading libOpenImageIO takes about 360 ms here (it links some 260 libraries), so it lives in
// its own library that is opened only when an EXR is read or written (compare/exr_file.cpp);
// only C types cross the boundary.
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

namespace {

void set_error(char* err, std::size_t err_len, const std::string& what) {
  std::snprintf(err, err_len, "%s", what.c_str());
}

// The channels a comparison reads: R, G, B when all three exist, else Y (luminance), by name
// as OpenEXR stores them (layers aside: "diffuse.R" does not count).
std::vector<int> channels_to_read(const OIIO::ImageSpec& spec) {
  auto find = [&](const char* name) {
    const auto& names = spec.channelnames;
    const auto it = std::find(names.begin(), names.end(), name);
    return it == names.end() ? -1 : int(it - names.begin());
  };
  const int r = find("R"), g = find("G"), b = find("B"), y = find("Y");
  if (r >= 0 && g >= 0 && b >= 0) return {r, g, b};
  if (y >= 0) return {y};
  return {};
}

std::string channel_list(const OIIO::ImageSpec& spec) {
  std::string out;
  for (const std::string& n : spec.channelnames) out += (out.empty() ? "" : ", ") + n;
  return out.empty() ? "none" : out;
}

}  // namespace

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
  set_error(err, err_len, OIIO::geterror());
  return 1;
}

// Reads the first image of an EXR held in memory as float R, G, B (or Y alone), interleaved.
// `allocate(user, width, height, channels)` returns room for width * height * channels
// floats, or nullptr to refuse the size (err then says why, as the allocator wrote it).
// 0 on success, else 1 with the reason in err.
extern "C" __attribute__((visibility("default"))) int aosuite_read_exr(
    const unsigned char* bytes, std::size_t size,
    float* (*allocate)(void* user, int width, int height, int channels), void* user, char* err,
    std::size_t err_len) {
  OIIO::Filesystem::IOMemReader memory(bytes, size);
  // The proxy goes in as a configuration hint, as OpenImageIO 2.x documents it; the name only
  // picks the format.
  OIIO::ImageSpec config;
  void* proxy = &memory;
  config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
  auto in = OIIO::ImageInput::open("image.exr", &config);
  if (!in) {
    set_error(err, err_len, "not a readable EXR file (" + OIIO::geterror() + ")");
    return 1;
  }
  const OIIO::ImageSpec& spec = in->spec();
  const std::vector<int> channels = channels_to_read(spec);
  if (channels.empty()) {
    set_error(err, err_len, "EXR has no R, G, B or Y channel (it has: " + channel_list(spec) + ")");
    return 1;
  }
  const int n = int(channels.size());
  float* pixels = allocate(user, spec.width, spec.height, n);
  if (!pixels) return 1;
  // Channels in the order wanted: Y alone, or R, G, B, which OpenEXR stores alphabetically
  // (B, G, R) but OIIO reorders into R, G, B first; read each one into its own slot.
  std::vector<float> plane(std::size_t(spec.width) * std::size_t(spec.height));
  for (int c = 0; c < n; ++c) {
    if (!in->read_image(0, 0, channels[c], channels[c] + 1, OIIO::TypeDesc::FLOAT, plane.data())) {
      set_error(err, err_len, "cannot read the EXR's pixels (" + in->geterror() + ")");
      return 1;
    }
    for (std::size_t i = 0; i < plane.size(); ++i) pixels[i * n + c] = plane[i];
  }
  return 0;
}
