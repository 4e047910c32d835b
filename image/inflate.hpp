// A zlib stream's inflate (RFC 1950, 1951) for PNG image data, read a piece at a time and
// written a band at a time, that accepts and refuses exactly what zlib 1.2's inflate does.
//
// Why not ISA-L's: PNG encoders' matches are mostly a pixel or two back (every match in a
// noisy RGBA image is 4 or 8 bytes back), and ISA-L copies those through memory it has just
// written, 16 bytes at a time: each load waits for the store before it to retire (58% of
// its time on the 4K peers-bench pair, `perf annotate`). Here the last 8 bytes written are
// also kept in a register, so such a match is one shuffle and one store; and literals, most
// of a noisy image's codes (2 bits each there), are read up to 6 per table lookup, with the
// match length after them. Smooth images, whose matches are long and rows back, inflate
// 10-20% slower than with ISA-L (bench/README.md).
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>

namespace aosuite {

class Inflater {
 public:
  // Hands over the next piece of the stream; empty once there is none.
  using Source = std::function<std::span<const unsigned char>()>;
  // kFast needs AVX2 and BMI2 and falls back to kCareful without them; kCareful decodes a
  // code at a time (what kFast does near the ends of its buffers), for tests.
  enum class Path { kFast, kCareful };

  explicit Inflater(Source source, Path path = Path::kFast);
  ~Inflater();
  Inflater(Inflater&&) noexcept;
  Inflater& operator=(Inflater&&) noexcept;

  // Inflates into out[0, n): n bytes, or fewer where the stream ends or is bad (see bad()).
  // Reaching the stream's end reads and checks its Adler-32 too, so ask for a byte more than
  // expected to learn whether it ends there.
  std::size_t inflate(unsigned char* out, std::size_t n);
  bool ended() const;    // the whole stream was read and its checksum matched
  bool bad() const;      // zlib would refuse the stream (truncated, invalid, or a bad checksum)
  bool ran_out() const;  // bad, with all of the input read: most likely truncated

 private:
  struct State;
  std::unique_ptr<State> s_;
};

}  // namespace aosuite
