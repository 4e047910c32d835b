// libaosuite_exr.so: reading and writing float EXR images with OpenEXR. It lives in its own
// library, opened only when an EXR is read or written (image/exr_file.cpp), so that PNG-only
// processes never load it; only C types cross the boundary. (It used OpenImageIO once, whose
// ~260 libraries took ~360 ms to load: more than the FLIP of a 1080p pair.)
#include "image/exr_library.hpp"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfThreading.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include "common/cpu_set.hpp"
#include "image/exr_header_walk.hpp"

namespace {

void set_error(char* err, std::size_t err_len, const std::string& what) {
  std::snprintf(err, err_len, "%s", what.c_str());
}

// The file's bytes, already in memory (mapped or read from a pipe), as OpenEXR's input stream.
class MemoryStream : public Imf::IStream {
 public:
  MemoryStream(const unsigned char* bytes, std::size_t size)
      : Imf::IStream("EXR"), bytes_(bytes), size_(size) {}
  bool read(char c[], int n) override {
    if (n < 0 || std::uint64_t(n) > size_ - pos_)
      throw std::runtime_error("unexpected end of file");
    std::memcpy(c, bytes_ + pos_, std::size_t(n));
    pos_ += std::uint64_t(n);
    return pos_ < size_;
  }
  std::uint64_t tellg() override { return pos_; }
  void seekg(std::uint64_t pos) override {
    if (pos > size_) throw std::runtime_error("seek past the end of the file");
    pos_ = pos;
  }

 private:
  const unsigned char* bytes_;
  std::uint64_t size_, pos_ = 0;
};

// The channels a comparison reads: R, G, B when all three exist, else Y (luminance), by name
// as OpenEXR stores them (layers aside: "diffuse.R" does not count).
std::vector<std::string> channels_to_read(const Imf::ChannelList& list) {
  const auto has = [&](const char* name) { return list.findChannel(name) != nullptr; };
  if (has("R") && has("G") && has("B")) return {"R", "G", "B"};
  if (has("Y")) return {"Y"};
  return {};
}

std::string channel_names(const Imf::ChannelList& list) {
  std::string out;
  for (auto it = list.begin(); it != list.end(); ++it)
    out += (out.empty() ? "" : ", ") + std::string(it.name());
  return out.empty() ? "none" : out;
}

}  // namespace

// The entry points' contracts are in image/exr_library.hpp.
extern "C" __attribute__((visibility("default"))) int aosuite_write_exr(const char* path, int width,
                                                                        int height, int channels,
                                                                        const float* pixels,
                                                                        char* err,
                                                                        std::size_t err_len) {
  try {
    Imf::Header header(width, height);
    Imf::FrameBuffer fb;
    static constexpr const char* kGrey[] = {"Y"};
    static constexpr const char* kColour[] = {"R", "G", "B"};
    const std::size_t n = channels == 3 ? 3 : 1;
    for (std::size_t c = 0; c < n; ++c) {
      const char* name = n == 3 ? kColour[c] : kGrey[0];
      header.channels().insert(name, Imf::Channel(Imf::FLOAT));
      fb.insert(name,
                Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(const_cast<float*>(pixels + c)),
                           sizeof(float) * n, sizeof(float) * n * std::size_t(width)));
    }
    Imf::OutputFile out(path, header);
    out.setFrameBuffer(fb);
    out.writePixels(height);
    return 0;
  } catch (const std::exception& e) {
    set_error(err, err_len, e.what());
    return 1;
  }
}

extern "C" __attribute__((visibility("default"))) int aosuite_read_exr(
    const unsigned char* bytes, std::size_t size,
    float* (*allocate)(void* user, int width, int height, int channels), void* user, char* err,
    std::size_t err_len) {
  try {
    MemoryStream stream(bytes, size);
    // Line blocks decompress on every core: zip-compressed floats are most of a read.
    static const int threads = [] {
      // The pool's threads may run wherever the process may, whichever thread reads first.
      const aosuite::MainThreadCpus everywhere;
      const int n = aosuite::usable_cpus();
      Imf::setGlobalThreadCount(n);
      // OpenEXR sizes its tables from the header before any pixel is read: a 300-byte file
      // claiming a huge window would take gigabytes. No side over 32768 (aosuite refuses more
      // than 2^28 pixels anyway) keeps a header's claims cheap to refuse.
      Imf::Header::setMaxImageSize(32768, 32768);
      Imf::Header::setMaxTileSize(32768, 32768);
      return n;
    }();
    aosuite::exr::check_attribute_sizes(bytes, size);
    Imf::InputFile in(stream, threads);
    const Imath::Box2i window = in.header().dataWindow();
    const std::vector<std::string> names = channels_to_read(in.header().channels());
    if (names.empty()) {
      set_error(err, err_len,
                "EXR has no R, G, B or Y channel (it has: " +
                    channel_names(in.header().channels()) + ")");
      return 1;
    }
    const long long w = (long long)window.max.x - window.min.x + 1;
    const long long h = (long long)window.max.y - window.min.y + 1;
    const int n = int(names.size());
    if (w <= 0 || h <= 0 || w > (1 << 30) || h > (1 << 30)) {
      set_error(err, err_len, "EXR has an impossible data window");
      return 1;
    }
    float* pixels = allocate(user, int(w), int(h), n);
    if (!pixels) {
      set_error(err, err_len,
                "EXR's " + std::to_string(w) + "x" + std::to_string(h) + " data window with " +
                    std::to_string(n) + " channel(s) was refused (too large to read)");
      return 1;
    }
    // Slices are addressed from the data window's origin, which need not be (0, 0). Slice::Make
    // moves the base pointer there in integer arithmetic: `pixels - min * stride` as pointer
    // arithmetic is undefined once it leaves the buffer, and wraps below address 0 for a window
    // far from the origin (exr_fuzz, fuzz/corpus/exr/window_far_from_origin.exr).
    const std::size_t xs = sizeof(float) * std::size_t(n), ys = xs * std::size_t(w);
    Imf::FrameBuffer fb;
    for (int c = 0; c < n; ++c)
      fb.insert(names[std::size_t(c)], Imf::Slice::Make(Imf::FLOAT, pixels + c, window, xs, ys));
    in.setFrameBuffer(fb);
    in.readPixels(window.min.y, window.max.y);
    return 0;
  } catch (const std::exception& e) {
    set_error(err, err_len, std::string("not a readable EXR file (") + e.what() + ")");
    return 1;
  }
}
