#include "image/exr_header_walk.hpp"

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <string_view>

namespace aosuite::exr {
namespace {

// Bytes OpenEXR 3.1's reader takes for each attribute type that reads a fixed number whatever
// the declared size says (Imf*Attribute.cpp, readValueFrom). A walk that skipped the declared
// size instead would lose step with OpenEXR on a file whose sizes lie, and miss a later claim.
std::size_t fixed_size(std::string_view type) {
  static constexpr struct {
    std::string_view type;
    std::size_t bytes;
  } kFixed[] = {
      {"box2i", 16},
      {"box2f", 16},
      {"chromaticities", 32},
      {"compression", 1},
      {"deepImageState", 1},
      {"double", 8},
      {"envmap", 1},
      {"float", 4},
      {"int", 4},
      {"keycode", 28},
      {"lineOrder", 1},
      {"m33f", 36},
      {"m33d", 72},
      {"m44f", 64},
      {"m44d", 128},
      {"rational", 8},
      {"tiledesc", 9},
      {"timecode", 8},
      {"v2i", 8},
      {"v2f", 8},
      {"v2d", 16},
      {"v3i", 12},
      {"v3f", 12},
      {"v3d", 24},
  };
  for (const auto& f : kFixed)
    if (f.type == type) return f.bytes;
  return 0;
}

class Walk {
 public:
  Walk(const unsigned char* bytes, std::size_t size) : bytes_(bytes), size_(size) {}

  std::size_t left() const { return size_ - pos_; }
  bool at_nul() const { return pos_ < size_ && bytes_[pos_] == 0; }

  // A name as OpenEXR reads one: up to 255 bytes and a NUL (Name::MAX_LENGTH).
  std::string_view name() {
    const std::size_t most = left() < 256 ? left() : 256;
    const void* nul = std::memchr(bytes_ + pos_, 0, most);
    if (!nul) throw std::runtime_error("a header name is cut off or longer than 255 bytes");
    const std::string_view s(reinterpret_cast<const char*>(bytes_ + pos_),
                             std::size_t(static_cast<const unsigned char*>(nul) - (bytes_ + pos_)));
    pos_ += s.size() + 1;
    return s;
  }

  std::uint32_t u32() {
    take(4);
    const unsigned char* p = bytes_ + pos_ - 4;
    return std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8 | std::uint32_t(p[2]) << 16 |
           std::uint32_t(p[3]) << 24;
  }

  void take(std::size_t n) {
    if (n > left()) throw std::runtime_error("header cut off");
    pos_ += n;
  }

 private:
  const unsigned char* bytes_;
  std::size_t size_, pos_ = 8;  // after the magic number and the version
};

// One attribute's value, taken from the walk as OpenEXR's reader for its type takes it.
void take_value(Walk& walk, std::string_view name, std::string_view type, std::uint32_t size) {
  if (size > walk.left()) {
    throw std::runtime_error("attribute '" + std::string(name) + "' claims " +
                             std::to_string(size) + " bytes, more than the " +
                             std::to_string(walk.left()) + " left in the file");
  }
  if (type == "chlist") {  // channels until an empty name, each 16 bytes; the size unread
    while (!walk.name().empty()) walk.take(16);
  } else if (const std::size_t fixed = fixed_size(type)) {
    walk.take(fixed);
  } else if (type == "floatvector") {  // whole floats only
    walk.take(size / 4 * 4);
  } else if (type == "idmanifest") {  // 8 bytes of uncompressed size, then size - 4 bytes
    if (size < 4) throw std::runtime_error("attribute '" + std::string(name) + "' is too short");
    walk.take(std::size_t(size) + 4);
  } else {  // string, stringvector, preview (which checks its size itself), unknown types
    walk.take(size);
  }
}

}  // namespace

std::vector<std::string> check_attribute_sizes(const unsigned char* bytes, std::size_t size) {
  std::vector<std::string> names;
  if (size < 8) return names;  // OpenEXR refuses it itself
  // Multi-part (version flag 0x1000): headers one after another, and an empty one at the end.
  const bool multipart = (bytes[5] & 0x10) != 0;
  Walk walk(bytes, size);
  while (walk.left() > 0) {
    const std::string_view name = walk.name();
    if (name.empty()) {  // a header's end
      if (!multipart || walk.left() == 0 || walk.at_nul()) return names;
      continue;
    }
    const std::string_view type = walk.name();
    const std::uint32_t declared = walk.u32();
    take_value(walk, name, type, declared);
    names.emplace_back(name);
  }
  return names;
}

}  // namespace aosuite::exr
