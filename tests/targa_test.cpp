// The Targa reader from a second angle: files written byte by byte here, against pixels worked
// out by hand from the format's rules, where pillow_formats.py compares with Pillow's decoding.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "image/codecs.hpp"

namespace aosuite::codecs {
namespace {

struct Decoded {
  int width = 0, height = 0, channels = 0;
  std::vector<unsigned char> pixels;
};

void* allocate(void* user, int width, int height, int channels, int sample) {
  auto* d = static_cast<Decoded*>(user);
  d->width = width, d->height = height, d->channels = channels;
  d->pixels.assign(std::size_t(width) * std::size_t(height) * std::size_t(channels * sample), 0);
  return d->pixels.data();
}

// An 18-byte header: image type, size, bits per pixel, descriptor (0x20: top row first).
std::vector<unsigned char> header(int type, int width, int height, int bits, int descriptor) {
  std::vector<unsigned char> h(18, 0);
  h[2] = static_cast<unsigned char>(type);
  h[12] = static_cast<unsigned char>(width), h[14] = static_cast<unsigned char>(height);
  h[16] = static_cast<unsigned char>(bits), h[17] = static_cast<unsigned char>(descriptor);
  return h;
}

int decode(const std::vector<unsigned char>& file, Decoded& d, std::string& why) {
  return read_tga(file.data(), file.size(), allocate, &d, why);
}

// A run-length packet may run across rows: a 3x2 grey image, bottom row first, as one run of 4
// pixels of 7 and a raw packet of 2 (8, 9), is 7 7 7 / 7 8 9 from the bottom: top row 7 8 9.
TEST(Targa, ARunAcrossRowsAndTheBottomRowFirst) {
  std::vector<unsigned char> f = header(11, 3, 2, 8, 0);
  for (int b : {0x83, 7, 0x01, 8, 9}) f.push_back(static_cast<unsigned char>(b));
  Decoded d;
  std::string why;
  ASSERT_EQ(decode(f, d, why), 0) << why;
  EXPECT_EQ(d.channels, 1);
  EXPECT_EQ(d.pixels, (std::vector<unsigned char>{7, 8, 9, 7, 7, 7}));
}

// True colour is stored B, G, R, A; with the top row first it is read in order.
TEST(Targa, ColourIsStoredBgrAndTheTopRowFirstIsKept) {
  std::vector<unsigned char> f = header(2, 2, 1, 32, 0x20);
  for (int b : {10, 20, 30, 40, 50, 60, 70, 80}) f.push_back(static_cast<unsigned char>(b));
  Decoded d;
  std::string why;
  ASSERT_EQ(decode(f, d, why), 0) << why;
  EXPECT_EQ(d.channels, 4);
  EXPECT_EQ(d.pixels, (std::vector<unsigned char>{30, 20, 10, 40, 70, 60, 50, 80}));
}

// Damaged files are refused with the reason, never read past their end.
TEST(Targa, DamageIsRefusedWithTheReason) {
  struct Bad {
    std::vector<unsigned char> file;
    std::string why;
  };
  std::vector<Bad> bad;
  std::vector<unsigned char> run_past = header(11, 2, 1, 8, 0);
  for (int b : {0x82, 5})
    run_past.push_back(static_cast<unsigned char>(b));  // 3 pixels into a 2-pixel image
  bad.push_back({run_past, "a run-length packet runs past the image"});
  std::vector<unsigned char> cut = header(11, 4, 1, 8, 0);
  cut.push_back(0x03);  // a raw packet of 4 with no pixels after it
  bad.push_back({cut, "the pixel data ends early"});
  bad.push_back({header(3, 4, 4, 8, 0), "the pixel data ends early"});
  bad.push_back({header(2, 0, 4, 24, 0), "an empty image"});
  bad.push_back({std::vector<unsigned char>(10, 0), "shorter than a Targa header"});
  for (const Bad& b : bad) {
    Decoded d;
    std::string why;
    EXPECT_EQ(decode(b.file, d, why), 1) << b.why;
    EXPECT_EQ(why, b.why);
  }
  // Right-to-left and colour-mapped images are another reader's.
  Decoded d;
  std::string why;
  EXPECT_EQ(decode(header(2, 1, 1, 24, 0x10), d, why), kNotMine);
  EXPECT_EQ(decode(header(1, 1, 1, 8, 0), d, why), kNotMine);
}

}  // namespace
}  // namespace aosuite::codecs
