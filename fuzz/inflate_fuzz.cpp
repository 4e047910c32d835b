// The inflater (image/inflate.hpp) against zlib's inflate on any bytes: it accepts exactly
// the streams zlib accepts, with zlib's bytes, and where zlib refuses it refuses too, after the
// same bytes; on both of its paths, with the stream in pieces and the output in bands.
// Input: one byte choosing the piece and band sizes, then the zlib stream.
#include <zlib.h>

#include <algorithm>
#include <array>
#include <vector>

#include "fuzz/fuzz_util.hpp"
#include "image/inflate.hpp"
#include "tests/inflate_harness.hpp"

namespace {

namespace fuzz = aosuite::fuzz;
using aosuite::Inflater;

constexpr std::size_t kLimit = 1 << 18;  // output compared (a stream may inflate 1032 times)

struct Verdict {
  std::vector<unsigned char> out;
  bool accepted = false;
};

Verdict zlib_inflate(std::span<const unsigned char> stream) {
  z_stream z{};
  if (inflateInit2(&z, 15) != Z_OK) fuzz::fail("inflateInit2");
  Verdict v;
  v.out.resize(kLimit);
  z.next_in = const_cast<unsigned char*>(stream.data());
  z.avail_in = static_cast<uInt>(stream.size());
  z.next_out = v.out.data();
  z.avail_out = static_cast<uInt>(kLimit);
  const int status = inflate(&z, Z_FINISH);
  v.out.resize(kLimit - z.avail_out);
  v.accepted = status == Z_STREAM_END;
  inflateEnd(&z);
  return v;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  static constexpr std::array<std::size_t, 4> kPieces = {1, 7, 300, kLimit};
  static constexpr std::array<std::size_t, 4> kBands = {1, 333, 4096, kLimit};
  const std::size_t piece = kPieces[data[0] & 3], band = kBands[data[0] >> 2 & 3];
  const std::span<const unsigned char> stream(data + 1, size - 1);
  const Verdict expected = zlib_inflate(stream);
  const bool whole = expected.out.size() < kLimit;  // else only the first kLimit bytes compare
  for (const Inflater::Path path : {Inflater::Path::kFast, Inflater::Path::kCareful}) {
    const aosuite::testing::Inflated got =
        aosuite::testing::inflate_in_pieces(stream, path, piece, band, kLimit);
    if (got.ended && got.bad) fuzz::fail("both ended and bad");
    if (!whole) {
      if (!std::equal(got.out.begin(), got.out.end(), expected.out.begin()))
        fuzz::fail("bytes differ");
      continue;
    }
    if (got.ended != expected.accepted)
      fuzz::fail(got.ended ? "accepted what zlib refuses" : "refused what zlib accepts");
    if (!got.ended && !got.bad) fuzz::fail("neither ended nor bad");
    if (got.out != expected.out) fuzz::fail("bytes differ from zlib's");
  }
  return 0;
}
