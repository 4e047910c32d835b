// Drives an Inflater the way its differential checks against zlib do (tests/inflate_test.cpp,
// fuzz/inflate_fuzz.cpp): the stream handed over in pieces, the output asked for in bands.
#pragma once

#include <algorithm>
#include <cstddef>
#include <span>
#include <vector>

#include "image/inflate.hpp"

namespace aosuite::testing {

struct Inflated {
  std::vector<unsigned char> out;
  bool ended = false, bad = false;
};

// `stream` in pieces of up to `piece` bytes, inflated in bands of up to `band` bytes until it
// ends or is refused, `limit` bytes at most.
inline Inflated inflate_in_pieces(std::span<const unsigned char> stream, Inflater::Path path,
                                  std::size_t piece, std::size_t band, std::size_t limit) {
  std::size_t at = 0;
  Inflater inflater(
      [&]() {
        const std::size_t n = std::min(piece, stream.size() - at);
        at += n;
        return stream.subspan(at - n, n);
      },
      path);
  Inflated r;
  r.out.resize(limit);
  std::size_t got = 0;
  while (got < limit) {
    const std::size_t want = std::min(band, limit - got);
    const std::size_t n = inflater.inflate(r.out.data() + got, want);
    got += n;
    if (n < want) break;
  }
  r.out.resize(got);
  r.ended = inflater.ended(), r.bad = inflater.bad();
  return r;
}

}  // namespace aosuite::testing
