// An xxh3 hash of content, for the caches keyed by their inputs (harness renders, ray-traced
// references, PMI maps). Spans and strings are length-prefixed, so "ab"+"c" and "a"+"bc" differ.
#pragma once

#include <fmt/format.h>
#include <xxhash.h>

#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>

#include "common/file_io.hpp"

namespace aosuite {

class ContentHash {
 public:
  ContentHash() : state_(XXH3_createState(), XXH3_freeState) { XXH3_64bits_reset(state_.get()); }

  template <typename T>
  ContentHash& add(std::span<const T> v) {
    add(v.size());
    XXH3_64bits_update(state_.get(), v.data(), v.size_bytes());
    return *this;
  }
  // A span of mutable elements hashes their bytes too, never the span object itself.
  template <typename T>
  requires(!std::is_const_v<T>) ContentHash& add(std::span<T> v) {
    return add(std::span<const T>(v));
  }
  ContentHash& add(std::string_view s) { return add(std::span<const char>(s.data(), s.size())); }
  template <typename T>
  requires std::is_trivially_copyable_v<T> ContentHash& add(const T& v) {
    XXH3_64bits_update(state_.get(), &v, sizeof v);
    return *this;
  }
  // The file's name and bytes; throws FileError if it cannot be read, is not a regular file
  // or is over kMaxFileBytes (common/file_io.hpp).
  ContentHash& add_file(const std::filesystem::path& p) {
    add(p.filename().string());
    const std::vector<unsigned char> bytes = read_regular_file(p);
    return add(std::span<const unsigned char>(bytes));
  }

  std::uint64_t digest() const { return XXH3_64bits_digest(state_.get()); }
  std::string hex() const { return fmt::format("{:016x}", digest()); }

 private:
  std::unique_ptr<XXH3_state_t, XXH_errorcode (*)(XXH3_state_t*)> state_;
};

}  // namespace aosuite
