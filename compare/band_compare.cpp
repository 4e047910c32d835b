#include "compare/band_compare.hpp"

#include <array>
#include <condition_variable>
#include <exception>
#include <future>
#include <mutex>
#include <thread>

#include "compare/count_kernel.hpp"
#include "compare/png_fast.hpp"

namespace aosuite {
namespace {

// A band's pixels per image: large enough that ISA-L's per-call cost (about 64 KB of history
// copied) is a few per cent, small enough that a band read is still in L2 when counted.
constexpr std::size_t kBandBytes = 128 << 10;
// Bands in flight per image: a decoder may run this many bands ahead of the counting.
constexpr std::uint32_t kSlots = 4;

// Two decoders meet here. Band i goes into slot i % kSlots of both images; whichever
// decoder finishes a band second counts it and frees its slot for band i + kSlots.
class Rendezvous {
 public:
  Rendezvous() {
    for (std::uint32_t s = 0; s < kSlots; ++s) free_for_[s] = s;
  }
  // Waits until band i's slot is free; false when the other decoder failed.
  bool wait_for_slot(std::uint32_t band) {
    std::unique_lock lock(m_);
    cv_.wait(lock, [&] { return failed_ || free_for_[band % kSlots] == band; });
    return !failed_;
  }
  // True for the second decoder to arrive with band i: it counts the band, then frees it.
  bool arrive(std::uint32_t band) {
    std::lock_guard lock(m_);
    return ++arrived_[band % kSlots] == 2;
  }
  void free_slot(std::uint32_t band) {
    {
      std::lock_guard lock(m_);
      arrived_[band % kSlots] = 0;
      free_for_[band % kSlots] = band + kSlots;
    }
    cv_.notify_all();
  }
  void fail(std::exception_ptr e) {
    {
      std::lock_guard lock(m_);
      if (!error_) error_ = std::move(e);
      failed_ = true;
    }
    cv_.notify_all();
  }
  void rethrow() const {
    if (error_) std::rethrow_exception(error_);
  }

 private:
  std::mutex m_;
  std::condition_variable cv_;
  std::array<std::uint32_t, kSlots> free_for_{};
  std::array<int, kSlots> arrived_{};
  bool failed_ = false;
  std::exception_ptr error_;
};

}  // namespace

std::uint32_t band_rows_for(std::uint32_t width) {
  return std::max<std::uint32_t>(1,
                                 static_cast<std::uint32_t>(kBandBytes / (std::size_t{width} * 4)));
}

std::optional<resemble::Result> compare_png_bands(std::span<const unsigned char> a,
                                                  const std::string& name_a,
                                                  std::span<const unsigned char> b,
                                                  const std::string& name_b,
                                                  const resemble::Options& options) {
  const auto start = std::chrono::steady_clock::now();
  // The files' pixels are what is compared only without a canvas model.
  const std::optional<std::array<int, 4>> min_delta = resemble::count_only_thresholds(options);
  if (!min_delta || options.canvas_alpha != CanvasAlpha::kNone) return std::nullopt;
  // Opening checks every chunk's CRC: one file on each thread.
  auto opening_b = std::async(std::launch::async, [&] { return PngRows::open(b, name_b); });
  std::array<std::optional<PngRows>, 2> png = {PngRows::open(a, name_a), opening_b.get()};
  if (!png[0] || !png[1] || png[0]->width() != png[1]->width() ||
      png[0]->height() != png[1]->height()) {
    return std::nullopt;
  }
  const std::uint32_t w = png[0]->width(), h = png[0]->height();
  const std::uint32_t band_rows = band_rows_for(w);
  const std::uint32_t bands = (h + band_rows - 1) / band_rows;
  // Both rings in one buffer: a few huge-page faults rather than hundreds of small ones.
  const std::array<std::size_t, 2> slot_bytes = {png[0]->band_bytes(band_rows),
                                                 png[1]->band_bytes(band_rows)};
  const PixelBuffer rings((slot_bytes[0] + slot_bytes[1]) * kSlots);
  auto slot = [&](int i, std::uint32_t band) {
    return rings.data() + (i ? slot_bytes[0] * kSlots : 0) + (band % kSlots) * slot_bytes[i];
  };

  Rendezvous meet;
  std::array<MismatchTally, 2> tally;
  auto decode = [&](int i) {
    try {
      for (std::uint32_t band = 0; band < bands; ++band) {
        const std::uint32_t y0 = band * band_rows, rows = std::min(band_rows, h - y0);
        if (!meet.wait_for_slot(band)) return;
        png[i]->read(slot(i, band), rows);
        if (!meet.arrive(band)) continue;
        tally[i].merge(count_band(slot(0, band), slot(1, band), static_cast<int>(w),
                                  static_cast<int>(rows), static_cast<int>(y0), *min_delta));
        meet.free_slot(band);
      }
    } catch (...) {
      meet.fail(std::current_exception());
    }
  };
  {
    std::jthread other(decode, 1);
    decode(0);
  }
  meet.rethrow();
  tally[0].merge(tally[1]);
  const ImageSize size{static_cast<int>(w), static_cast<int>(h)};
  return resemble::result_from_tally(tally[0], size, size, start);
}

}  // namespace aosuite
