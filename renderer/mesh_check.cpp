#include "renderer/mesh_check.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cstdint>
#include <string>
#include <vector>

#include "compare/image_io.hpp"

namespace aosuite::renderer {
namespace {

// Whitespace-separated tokens of a text, with the line each is on.
class Tokens {
 public:
  // `comment`: a character that starts a comment running to the end of its line (0: none).
  Tokens(std::string_view name, std::string_view text, char comment = 0)
      : name_(name), text_(text), comment_(comment) {}

  // The next token, or empty at the end of the text.
  std::string_view next() {
    for (;;) {
      while (pos_ < text_.size() && is_space(text_[pos_])) line_ += text_[pos_++] == '\n';
      if (!comment_ || pos_ == text_.size() || text_[pos_] != comment_) break;
      rest_of_line();
    }
    const std::size_t start = pos_;
    while (pos_ < text_.size() && !is_space(text_[pos_])) ++pos_;
    return text_.substr(start, pos_ - start);
  }
  // The rest of the current line, consumed with its newline.
  std::string_view rest_of_line() {
    const std::size_t end = std::min(text_.find('\n', pos_), text_.size());
    const std::string_view rest = text_.substr(pos_, end - pos_);
    pos_ = end;
    return rest;
  }
  std::size_t offset() const { return pos_; }
  template <typename T>
  T number(std::string_view what) {
    const std::string_view t = next();
    if (t.empty()) fail(fmt::format("truncated: {} missing", what));
    T v{};
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
    if (ec != std::errc() || end != t.data() + t.size()) {
      fail(fmt::format("'{}' is not a valid {}", t, what));
    }
    return v;
  }
  [[noreturn]] void fail(const std::string& why) const {
    throw FileError(fmt::format("{}:{}: {}", name_, line_, why));
  }

 private:
  static bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }
  std::string_view name_, text_;
  char comment_;
  std::size_t pos_ = 0;
  int line_ = 1;
};

std::string_view as_text(std::span<const unsigned char> bytes) {
  return {reinterpret_cast<const char*>(bytes.data()), bytes.size()};
}

// PLY header: elements, their counts and property layouts.
struct PlyProperty {
  int size = 0;        // bytes of a scalar, or of each list item
  int count_size = 0;  // bytes of a list's length; 0 for a scalar
};
struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;
};
enum class PlyFormat { kAscii, kLittle, kBig };
struct PlyHeader {
  PlyFormat format = PlyFormat::kAscii;
  std::vector<PlyElement> elements;
  std::size_t body = 0;  // offset of the first byte after end_header's newline
};

int ply_type_size(std::string_view t) {
  if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
  if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
  if (t == "int" || t == "uint" || t == "float" || t == "int32" || t == "uint32" ||
      t == "float32") {
    return 4;
  }
  if (t == "double" || t == "float64") return 8;
  return 0;
}

PlyHeader parse_ply_header(Tokens& in) {
  if (const std::string_view magic = in.next(); magic != "ply" && magic != "PLY") {
    in.fail("not a PLY file (no 'ply' magic)");
  }
  PlyHeader h;
  bool has_format = false;
  auto type = [&](std::string_view t) {
    const int size = ply_type_size(t);
    if (size == 0) in.fail(fmt::format("unknown PLY type '{}'", t));
    return size;
  };
  for (std::string_view key = in.next();; key = in.next()) {
    if (key.empty()) in.fail("truncated header (no end_header)");
    if (key == "end_header") break;
    if (key == "comment" || key == "obj_info") {
      in.rest_of_line();
    } else if (key == "format") {
      const std::string_view f = in.next();
      if (f == "ascii") {
        h.format = PlyFormat::kAscii;
      } else if (f == "binary_little_endian") {
        h.format = PlyFormat::kLittle;
      } else if (f == "binary_big_endian") {
        h.format = PlyFormat::kBig;
      } else {
        in.fail(fmt::format("unknown format '{}'", f));
      }
      has_format = true;
      in.rest_of_line();
    } else if (key == "element") {
      PlyElement e{std::string(in.next()), 0, {}};
      e.count = in.number<std::uint64_t>("element count");
      h.elements.push_back(std::move(e));
    } else if (key == "property") {
      if (h.elements.empty()) in.fail("property before any element");
      PlyProperty p;
      if (const std::string_view t = in.next(); t == "list") {
        p.count_size = type(in.next());
        p.size = type(in.next());
      } else {
        p.size = type(t);
      }
      in.rest_of_line();  // the property's name
      h.elements.back().properties.push_back(p);
    } else {
      in.fail(fmt::format("unexpected '{}' in the header", key));
    }
  }
  if (!has_format) in.fail("no format line in the header");
  in.rest_of_line();
  h.body = in.offset() + 1;
  return h;
}

void check_ply_ascii(const PlyHeader& h, Tokens& in) {
  for (const PlyElement& e : h.elements) {
    for (std::uint64_t i = 0; i < e.count; ++i) {
      const std::string what = fmt::format("element '{}' {} of {}", e.name, i + 1, e.count);
      for (const PlyProperty& p : e.properties) {
        const std::uint64_t n = p.count_size ? in.number<std::uint64_t>(what) : 1;
        for (std::uint64_t k = 0; k < n; ++k) in.number<double>(what);
      }
    }
  }
}

// Unsigned integer of `size` bytes at `p` in the file's byte order.
std::uint64_t read_uint(const unsigned char* p, int size, bool big) {
  std::uint64_t v = 0;
  for (int i = 0; i < size; ++i) v |= std::uint64_t{p[big ? size - 1 - i : i]} << (8 * i);
  return v;
}

void check_ply_binary(std::string_view name, const PlyHeader& h,
                      std::span<const unsigned char> bytes) {
  std::size_t pos = h.body;
  const bool big = h.format == PlyFormat::kBig;
  for (const PlyElement& e : h.elements) {
    // Consumes `n` items of `size` bytes; the division keeps a lying count from overflowing.
    auto need = [&](std::uint64_t n, int size, std::uint64_t i) {
      if (n > (bytes.size() - pos) / static_cast<std::uint64_t>(size)) {
        throw FileError(fmt::format("{}: truncated: element '{}' {} of {} is cut off", name, e.name,
                                    i + 1, e.count));
      }
      pos += static_cast<std::size_t>(n) * static_cast<std::size_t>(size);
    };
    // Lists are walked item by item; each consumes at least one byte, so a lying count
    // cannot loop longer than the file is long.
    for (std::uint64_t i = 0; i < e.count && !e.properties.empty(); ++i) {
      for (const PlyProperty& p : e.properties) {
        if (!p.count_size) {
          need(1, p.size, i);
          continue;
        }
        need(1, p.count_size, i);
        need(read_uint(bytes.data() + pos - p.count_size, p.count_size, big), p.size, i);
      }
    }
  }
}

}  // namespace

void check_ply(std::string_view name, std::span<const unsigned char> bytes) {
  Tokens in(name, as_text(bytes));
  const PlyHeader h = parse_ply_header(in);
  if (h.body > bytes.size()) in.fail("truncated: no data after end_header");
  if (h.format == PlyFormat::kAscii) return check_ply_ascii(h, in);
  check_ply_binary(name, h, bytes);
}

void check_off(std::string_view name, std::span<const unsigned char> bytes) {
  Tokens in(name, as_text(bytes), '#');
  const std::string_view magic = in.next();
  // Variants with colours or normals (COFF, NOFF, CNOFF) keep the face layout; other
  // variants are left to the reader.
  if (magic != "OFF" && magic != "COFF" && magic != "NOFF" && magic != "CNOFF") return;
  const auto vertices = in.number<std::uint64_t>("vertex count");
  const auto faces = in.number<std::uint64_t>("face count");
  in.rest_of_line();  // the edge count, unused
  for (std::uint64_t i = 0; i < vertices; ++i) {
    const std::string what = fmt::format("vertex {} of {}", i + 1, vertices);
    for (int k = 0; k < 3; ++k) in.number<double>(what);
    in.rest_of_line();
  }
  for (std::uint64_t i = 0; i < faces; ++i) {
    const std::string what = fmt::format("face {} of {}", i + 1, faces);
    const auto n = in.number<std::uint64_t>(what);
    for (std::uint64_t k = 0; k < n; ++k) {
      if (in.number<std::uint64_t>(what) >= vertices) {
        in.fail(fmt::format("{}: vertex index out of range (the file has {} vertices)", what,
                            vertices));
      }
    }
    in.rest_of_line();  // an optional face colour
  }
}

}  // namespace aosuite::renderer
