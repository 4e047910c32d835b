// The TIFF reader from a second angle: baseline files written byte by byte here (either byte
// order, several strips, 8/16-bit and float samples), against the samples put in, where
// pillow_formats.py compares with Pillow's decoding of files Pillow wrote.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "image/codecs.hpp"

namespace aosuite::codecs {
namespace {

struct Decoded {
  int width = 0, height = 0, channels = 0, sample = 0;
  std::vector<unsigned char> pixels;
};

void* allocate(void* user, int width, int height, int channels, int sample) {
  auto* d = static_cast<Decoded*>(user);
  d->width = width, d->height = height, d->channels = channels, d->sample = sample;
  d->pixels.assign(std::size_t(width) * std::size_t(height) * std::size_t(channels * sample), 0);
  return d->pixels.data();
}

// A baseline TIFF: header, the strips' bytes, then one IFD whose values that do not fit in
// four bytes follow it. Tags are given in ascending order, as the format requires.
class TiffWriter {
 public:
  explicit TiffWriter(bool big_endian) : big_(big_endian) {
    bytes_ = big_ ? std::vector<unsigned char>{'M', 'M', 0, 42}
                  : std::vector<unsigned char>{'I', 'I', 42, 0};
    put32(bytes_, 0);  // the IFD's offset, set by file()
  }
  // Strip data, in the file's byte order already; returns its offset.
  std::uint32_t data(const std::vector<unsigned char>& b) {
    const auto at = static_cast<std::uint32_t>(bytes_.size());
    bytes_.insert(bytes_.end(), b.begin(), b.end());
    return at;
  }
  void entry(std::uint16_t tag, std::uint16_t type, std::vector<std::uint32_t> values) {
    entries_.push_back({tag, type, std::move(values)});
  }
  std::vector<unsigned char> file() {
    std::vector<unsigned char> out = bytes_;
    const auto ifd = static_cast<std::uint32_t>(out.size());
    set32(out, 4, ifd);
    std::vector<unsigned char> extra;
    const std::uint32_t extra_at = ifd + 2 + 12 * std::uint32_t(entries_.size()) + 4;
    put16(out, std::uint16_t(entries_.size()));
    for (const Entry& e : entries_) {
      std::vector<unsigned char> v;
      for (const std::uint32_t x : e.values) e.type == 3 ? put16(v, std::uint16_t(x)) : put32(v, x);
      put16(out, e.tag), put16(out, e.type), put32(out, std::uint32_t(e.values.size()));
      if (v.size() <= 4) {
        v.resize(4, 0);
        out.insert(out.end(), v.begin(), v.end());
      } else {
        put32(out, extra_at + std::uint32_t(extra.size()));
        extra.insert(extra.end(), v.begin(), v.end());
      }
    }
    put32(out, 0);  // no next IFD
    out.insert(out.end(), extra.begin(), extra.end());
    return out;
  }
  void put16(std::vector<unsigned char>& v, std::uint16_t x) const {
    const unsigned char b[2] = {static_cast<unsigned char>(x), static_cast<unsigned char>(x >> 8)};
    big_ ? v.insert(v.end(), {b[1], b[0]}) : v.insert(v.end(), {b[0], b[1]});
  }
  void put32(std::vector<unsigned char>& v, std::uint32_t x) const {
    for (int i = 0; i < 4; ++i)
      v.push_back(static_cast<unsigned char>(x >> (big_ ? 24 - 8 * i : 8 * i)));
  }

 private:
  struct Entry {
    std::uint16_t tag, type;
    std::vector<std::uint32_t> values;
  };
  void set32(std::vector<unsigned char>& v, std::size_t at, std::uint32_t x) const {
    std::vector<unsigned char> b;
    put32(b, x);
    std::memcpy(v.data() + at, b.data(), 4);
  }
  bool big_;
  std::vector<unsigned char> bytes_;
  std::vector<Entry> entries_;
};

constexpr std::uint16_t kShort = 3, kLong = 4;

// Width, height, bits, (no) compression, photometric, strips, samples, rows per strip, strip
// sizes, planar configuration, sample format: a whole baseline IFD.
std::vector<unsigned char> baseline(TiffWriter& w, int width, int height, int channels, int bits,
                                    int format,
                                    const std::vector<std::vector<unsigned char>>& strips,
                                    int rows_per_strip, std::uint32_t last_strip_at = 0) {
  std::vector<std::uint32_t> offsets, sizes;
  for (const auto& s : strips)
    offsets.push_back(w.data(s)), sizes.push_back(std::uint32_t(s.size()));
  if (last_strip_at) offsets.back() = last_strip_at;  // a strip the file does not hold
  w.entry(256, kLong, {std::uint32_t(width)});
  w.entry(257, kLong, {std::uint32_t(height)});
  w.entry(258, kShort, std::vector<std::uint32_t>(std::size_t(channels), std::uint32_t(bits)));
  w.entry(259, kShort, {1});
  w.entry(262, kShort, {channels >= 3 ? 2u : 1u});
  w.entry(273, kLong, offsets);
  w.entry(277, kShort, {std::uint32_t(channels)});
  w.entry(278, kLong, {std::uint32_t(rows_per_strip)});
  w.entry(279, kLong, sizes);
  w.entry(284, kShort, {1});
  w.entry(339, kShort, std::vector<std::uint32_t>(std::size_t(channels), std::uint32_t(format)));
  return w.file();
}

int decode(const std::vector<unsigned char>& file, Decoded& d, std::string& why) {
  return read_tiff(file.data(), file.size(), allocate, &d, why);
}

// RGB in three one-row strips, little-endian: the rows come out in order, samples as written.
TEST(Tiff, ColourInOneRowStripsReadsRowsInOrder) {
  TiffWriter w(false);
  const std::vector<std::vector<unsigned char>> rows = {
      {1, 2, 3, 4, 5, 6}, {7, 8, 9, 10, 11, 12}, {13, 14, 15, 16, 17, 18}};
  const std::vector<unsigned char> f = baseline(w, 2, 3, 3, 8, 1, rows, 1);
  Decoded d;
  std::string why;
  ASSERT_EQ(decode(f, d, why), 0) << why;
  EXPECT_EQ(d.width, 2);
  EXPECT_EQ(d.height, 3);
  EXPECT_EQ(d.channels, 3);
  EXPECT_EQ(d.sample, 1);
  std::vector<unsigned char> want;
  for (int i = 1; i <= 18; ++i) want.push_back(static_cast<unsigned char>(i));
  EXPECT_EQ(d.pixels, want);
}

// 16-bit samples written big-endian come out as the same numbers in this machine's order.
TEST(Tiff, SixteenBitBigEndianSamplesKeepTheirValues) {
  for (const bool big : {true, false}) {
    TiffWriter w(big);
    const std::vector<std::uint16_t> values = {0, 1, 256, 0x1234, 0xfffe, 65535};
    std::vector<unsigned char> strip;
    for (const std::uint16_t v : values) w.put16(strip, v);
    const std::vector<unsigned char> f = baseline(w, 3, 2, 1, 16, 1, {strip}, 2);
    Decoded d;
    std::string why;
    ASSERT_EQ(decode(f, d, why), 0) << why;
    EXPECT_EQ(d.sample, 2);
    std::vector<std::uint16_t> got(values.size());
    ASSERT_EQ(d.pixels.size(), got.size() * 2);
    std::memcpy(got.data(), d.pixels.data(), d.pixels.size());
    EXPECT_EQ(got, values) << (big ? "big-endian" : "little-endian");
  }
}

// 32-bit float samples (grey and alpha) keep their bits, negative and above 1 included.
TEST(Tiff, FloatSamplesKeepTheirBits) {
  TiffWriter w(true);
  const std::vector<float> values = {-0.5f, 0.0f, 0.25f, 1.0f, 3.5f, 1e-8f, 65504.0f, 2.0f};
  std::vector<unsigned char> strip;
  for (const float v : values) {
    std::uint32_t bits = 0;
    std::memcpy(&bits, &v, 4);
    w.put32(strip, bits);
  }
  const std::vector<unsigned char> f = baseline(w, 2, 2, 2, 32, 3, {strip}, 2);
  Decoded d;
  std::string why;
  ASSERT_EQ(decode(f, d, why), 0) << why;
  EXPECT_EQ(d.channels, 2);
  EXPECT_EQ(d.sample, 4);
  std::vector<float> got(values.size());
  ASSERT_EQ(d.pixels.size(), got.size() * 4);
  std::memcpy(got.data(), d.pixels.data(), d.pixels.size());
  EXPECT_EQ(got, values);
}

// Layouts it leaves to OpenImageIO (signed samples, 4-bit grey) are kNotMine, not misread; a
// strip the file does not hold is an error that says so.
TEST(Tiff, OtherLayoutsAreNotMineAndACutStripIsAnError) {
  {
    TiffWriter w(false);
    const std::vector<unsigned char> f = baseline(w, 2, 1, 1, 8, 2, {{1, 2}}, 1);  // int8
    Decoded d;
    std::string why;
    EXPECT_EQ(decode(f, d, why), kNotMine);
  }
  {
    TiffWriter w(false);
    const std::vector<unsigned char> f = baseline(w, 2, 1, 1, 4, 1, {{0x12}}, 1);
    Decoded d;
    std::string why;
    EXPECT_EQ(decode(f, d, why), kNotMine);
  }
  {
    // Two one-row strips, the second said to lie 1000 bytes past the end of the file.
    TiffWriter w(false);
    const std::vector<unsigned char> f =
        baseline(w, 4, 2, 1, 8, 1, {{1, 2, 3, 4}, {5, 6, 7, 8}}, 1, 100000);
    Decoded d;
    std::string why;
    EXPECT_EQ(decode(f, d, why), 1);
    EXPECT_FALSE(why.empty());
  }
}

}  // namespace
}  // namespace aosuite::codecs
