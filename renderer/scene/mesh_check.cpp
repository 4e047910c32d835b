#include "renderer/scene/mesh_check.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "common/file_io.hpp"
#include "common/printable.hpp"
#include "renderer/scene/text_tokens.hpp"

namespace aosuite::renderer {
namespace {

using text::parse;
using text::Tokens;

// The space- or tab-separated words of one line, as assimp splits a line of values.
std::vector<std::string_view> words(std::string_view l) {
  std::vector<std::string_view> out;
  for (std::size_t i = 0; i < l.size();) {
    while (i < l.size() && (l[i] == ' ' || l[i] == '\t')) ++i;
    const std::size_t start = i;
    while (i < l.size() && l[i] != ' ' && l[i] != '\t') ++i;
    if (i > start) out.push_back(l.substr(start, i - start));
  }
  return out;
}

std::string_view as_text(std::span<const unsigned char> bytes) {
  return {reinterpret_cast<const char*>(bytes.data()), bytes.size()};
}

// PLY header: elements, their counts and property layouts.
struct PlyProperty {
  int size = 0;        // bytes of a scalar, or of each list item
  int count_size = 0;  // bytes of a list's length; 0 for a scalar
  std::string name;
};
struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;
  int line = 0;  // of its declaration
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
    if (size == 0) in.fail(fmt::format("unknown PLY type '{}'", t.substr(0, 64)));
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
        in.fail(fmt::format("unknown format '{}'", f.substr(0, 64)));
      }
      has_format = true;
      in.rest_of_line();
    } else if (key == "element") {
      PlyElement e{std::string(in.next()), 0, {}, in.line()};
      e.count = in.number<std::uint64_t>([] { return "element count"; });
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
      p.name = std::string(in.next());
      in.rest_of_line();
      h.elements.back().properties.push_back(p);
    } else {
      in.fail(fmt::format("unexpected '{}' in the header", key.substr(0, 64)));
    }
  }
  if (!has_format) in.fail("no format line in the header");
  // assimp reads a missing coordinate as 0: a mesh flattened onto a plane, drawn.
  for (const PlyElement& e : h.elements) {
    if (e.name != "vertex") continue;
    for (const char* axis : {"x", "y", "z"}) {
      if (std::ranges::none_of(e.properties, [&](const PlyProperty& p) { return p.name == axis; }))
        in.fail_at(e.line, fmt::format("element 'vertex' has no property '{}'", axis));
    }
  }
  in.rest_of_line();
  h.body = in.offset() + 1;
  return h;
}

// Refuses a header whose element counts add up to more entries than `room` (lines or bytes
// after the header) can hold, before anything loops over a count or allocates for one: a
// count of 2^64-1 is refused at once, and assimp never sizes its element lists from it.
void check_counts(const Tokens& in, const PlyHeader& h, std::uint64_t room, std::string_view unit,
                  int last_line) {
  std::uint64_t left = room;
  for (const PlyElement& e : h.elements) {
    if (e.count > left) {
      in.fail_at(last_line,
                 fmt::format("truncated: element '{}' {} of {} is missing (the header, line {}, "
                             "declares more entries than the {} {} after it)",
                             e.name, left + 1, e.count, e.line, room, unit));
    }
    left -= e.count;
  }
}

// A value of an ASCII PLY entry, if assimp reads it as a whole word too. Its number reader
// (fast_atoreal_move) reads an integer part or exponent of 2^64 or more as 0 and stays where it
// was, so the next value would be read from the same digits (mesh_fuzz: a list length read from
// a 25-digit coordinate, 26 GB); a fraction's digits are read only as far as they matter.
std::optional<double> parse_ply_value(std::string_view word) {
  for (std::size_t i = 0; i < word.size();) {
    const std::size_t start = i;
    while (i < word.size() && word[i] >= '0' && word[i] <= '9') ++i;
    if (i == start) {
      ++i;
    } else if ((start == 0 || word[start - 1] != '.') &&
               !parse<std::uint64_t>(word.substr(start, i - start))) {
      return std::nullopt;
    }
  }
  return parse<double>(word);
}

// ASCII PLY as assimp 5.2 reads it (PlyParser.cpp, IOStreamBuffer::getNextLine): an entry
// per line, whose values are the space- or tab-separated words of that line (words after its
// last property are ignored). A line ends at \r or \n; reading the next line first skips to
// past the next \n if it stands on a line end, which passes over the \n of a \r\n, or over one
// empty line after a \n. A list's length is checked against the words left on its line: assimp
// allocates for the length before reading the items, so a lying length, or one read from the
// wrong word, would otherwise take gigabytes. assimp also ends lines at a lone \r, \f or NUL:
// those are refused, so that the checks and assimp cut the text alike.
void check_ply_ascii(const PlyHeader& h, Tokens& in, std::string_view text, int last_line) {
  const auto line_of = [&](std::size_t pos) {
    return 1 + static_cast<int>(std::count(text.begin(), text.begin() + long(pos), '\n'));
  };
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\0' || c == '\f' || (c == '\r' && (i + 1 == text.size() || text[i + 1] != '\n'))) {
      in.fail_at(line_of(i), "a NUL, form feed or lone carriage return (assimp ends a line there)");
    }
  }
  // One entry per line: no more entries than lines, before any count is looped over.
  const std::string_view body = text.substr(h.body);
  const auto lines = static_cast<std::uint64_t>(std::count(body.begin(), body.end(), '\n')) +
                     (!body.empty() && body.back() != '\n');
  check_counts(in, h, lines, "lines", last_line);
  // Where assimp stands after the end_header line: past its \r if it ends in \r\n.
  std::size_t pos = h.body >= 2 && text[h.body - 2] == '\r' ? h.body - 1 : h.body;
  // The line being read, as a text editor numbers it: newlines are counted up to `counted`.
  std::size_t counted = pos;
  int line = line_of(pos);
  const auto next_line = [&] {
    if (pos < text.size() && (text[pos] == '\r' || text[pos] == '\n')) {
      pos = std::min(text.find('\n', pos), text.size()) + 1;
    }
    const std::size_t start = std::min(pos, text.size());
    const std::size_t end = std::min(text.find_first_of("\r\n", start), text.size());
    pos = end + 1;
    line += static_cast<int>(
        std::count(text.begin() + long(counted), text.begin() + long(start), '\n'));
    counted = start;
    return text.substr(start, end - start);
  };
  for (const PlyElement& e : h.elements) {
    for (std::uint64_t i = 0; i < e.count && !e.properties.empty(); ++i) {
      const std::vector<std::string_view> w = words(next_line());
      const auto fail = [&](const std::string& why) {
        in.fail_at(line, fmt::format("element '{}' {} of {}: {}", e.name, i + 1, e.count, why));
      };
      std::size_t k = 0;
      const auto value = [&](auto parse_word, const char* what) {
        if (k == w.size()) fail(fmt::format("the line ends before its {}", what));
        const auto v = parse_word(w[k]);
        if (!v) fail(fmt::format("'{}' is not a valid {}", w[k].substr(0, 64), what));
        ++k;
        return *v;
      };
      for (const PlyProperty& p : e.properties) {
        const std::uint64_t n = p.count_size ? value(parse<std::uint64_t>, "list length") : 1;
        if (n > w.size() - k) {
          fail(fmt::format("a list of {} values with {} left on its line", n, w.size() - k));
        }
        for (std::uint64_t j = 0; j < n; ++j) value(parse_ply_value, "value");
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
        throw FileError(printable(fmt::format("{}: truncated: element '{}' {} of {} is cut off",
                                              name, e.name, i + 1, e.count)));
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
  const std::string_view text = as_text(bytes);
  Tokens in(name, text);
  const PlyHeader h = parse_ply_header(in);
  if (h.body > bytes.size()) in.fail("truncated: no data after end_header");
  const int last_line = 1 + static_cast<int>(std::count(text.begin(), text.end(), '\n'));
  if (h.format == PlyFormat::kAscii) return check_ply_ascii(h, in, text, last_line);
  // No more entries than bytes (an entry of no properties counts as one, so a file cannot
  // declare 2^64 empty ones either).
  check_counts(in, h, bytes.size() - h.body, "bytes", last_line);
  check_ply_binary(name, h, bytes);
}

// A number as assimp's OBJ reader takes one: a float, with a sign of either kind.
bool obj_number(std::string_view w) {
  if (w.starts_with('+')) w.remove_prefix(1);
  return parse<float>(w).has_value() || parse<double>(w).has_value();
}

void check_obj(std::string_view name, std::span<const unsigned char> bytes) {
  const std::string_view text = as_text(bytes);
  const Tokens in(name, text);
  std::string logical;  // a line and the lines a trailing backslash joins to it
  int first = 1, line = 0;
  for (std::size_t pos = 0; pos < text.size();) {
    const std::size_t end = std::min(text.find('\n', pos), text.size());
    std::string_view l = text.substr(pos, end - pos);
    pos = end + 1, ++line;
    if (l.ends_with('\r')) l.remove_suffix(1);
    if (logical.empty()) first = line;
    if (l.ends_with('\\')) {
      logical.append(l.substr(0, l.size() - 1)).push_back(' ');
      if (pos < text.size()) continue;
    } else {
      logical.append(l);
    }
    const std::vector<std::string_view> w = words(logical);
    const std::size_t needed = w.empty()                     ? 0
                               : w[0] == "v" || w[0] == "vn" ? 3
                               : w[0] == "vt"                ? 1
                                                             : 0;
    for (std::size_t k = 1; k <= needed; ++k) {
      if (k >= w.size()) {
        in.fail_at(first, fmt::format("'{}' has {} of its {} numbers", w[0], w.size() - 1, needed));
      }
      if (!obj_number(w[k])) {
        in.fail_at(first, fmt::format("'{}' is not a number ('{}' line, value {})",
                                      w[k].substr(0, 64), w[0], k));
      }
    }
    logical.clear();
  }
}

void mend_ply_header_end(std::string_view name, std::vector<unsigned char>& bytes) {
  Tokens in(name, as_text(bytes));
  const PlyHeader h = parse_ply_header(in);
  const std::size_t end = h.body - 1;  // end_header's newline
  if (h.format == PlyFormat::kAscii || h.body >= bytes.size() || bytes[h.body] != '\n' ||
      (end > 0 && bytes[end - 1] == '\r')) {
    return;
  }
  bytes.insert(bytes.begin() + long(end), '\r');
}

// OFF as assimp 5.2 reads it: the header as tokens ([ST][C][N][4][n]OFF, the dimension for
// nOFF, then the vertex, face and edge counts; '#' comments between them), then one vertex or
// face per line, where a line ends at \n, \r or \f, empty lines are skipped, '#' starts no
// comment, and nothing after a NUL byte is read. It clamps out-of-range indices to the last
// vertex, drops faces of 0 or more than 9 vertices, reads garbage as 0 and allocates what the
// counts say, so each of those is refused here, with the line.
void check_off(std::string_view name, std::span<const unsigned char> bytes) {
  const std::string_view text = as_text(bytes);
  Tokens in(name, text, '#');
  if (const std::size_t nul = text.find('\0'); nul != std::string_view::npos) {
    in.fail_at(1 + static_cast<int>(std::count(text.begin(), text.begin() + nul, '\n')),
               "a NUL byte (assimp reads nothing after it)");
  }
  std::string_view magic = in.next();
  const std::string_view header = magic;
  const auto prefix = [&](std::string_view p) {
    const bool has = magic.starts_with(p);
    if (has) magic.remove_prefix(p.size());
    return has;
  };
  prefix("ST"), prefix("C"), prefix("N");
  const bool homogeneous = prefix("4"), has_dimension = prefix("n");
  std::uint64_t dimensions = 3;
  // assimp also takes a file with no header, but reads a first count that begins with 4 as the
  // 4OFF prefix ("42 80 0" as 2 vertices): refused.
  if (magic != "OFF") {
    in.fail(fmt::format("not an OFF file: '{}' is not an OFF header ([ST][C][N][4][n]OFF)",
                        header.substr(0, 64)));
  }
  const auto count = [&](const char* what) {
    return in.number<std::uint64_t>([&] { return what; });
  };
  if (has_dimension) {
    dimensions = count("nOFF dimension");
    if (dimensions < 1 || dimensions > 3) in.fail("the nOFF dimension must be 1, 2 or 3");
  }
  const std::uint64_t vertices = count("vertex count");
  const std::uint64_t faces = count("face count");
  count("edge count");
  if (vertices == 0) in.fail("no vertices");
  if (faces == 0) in.fail("no faces");

  // The body begins at the next token: spaces, line ends and comment lines are skipped.
  std::size_t pos = in.offset();
  int line = in.line();
  for (;;) {
    while (pos < text.size() &&
           (text[pos] == ' ' || text[pos] == '\t' || text[pos] == '\r' || text[pos] == '\n')) {
      line += text[pos++] == '\n';
    }
    if (pos == text.size() || text[pos] != '#') break;
    while (pos < text.size() && text[pos] != '\n') ++pos;
  }
  // The body's lines as assimp cuts them, with the line number a text editor shows.
  struct Line {
    std::string_view text;
    int number;
  };
  const auto is_end = [](char c) { return c == '\n' || c == '\r' || c == '\f'; };
  const auto next_line = [&]() -> std::optional<Line> {
    if (pos == text.size()) return std::nullopt;
    const std::size_t start = pos;
    while (pos < text.size() && !is_end(text[pos])) ++pos;
    const Line l{text.substr(start, pos - start), line};
    while (pos < text.size() && is_end(text[pos])) line += text[pos++] == '\n';
    return l;
  };
  // Counted first, so no count runs past the file (nor allocates for more than it holds).
  const std::size_t body = pos;
  const int body_line = line;
  std::uint64_t lines = 0;
  int last_line = line;
  while (const auto l = next_line()) {
    ++lines;
    last_line = l->number;
    if (l->text.size() >= 4096) {
      in.fail_at(l->number, "a line longer than 4095 characters (assimp cuts it in two)");
    }
  }
  if (vertices > lines || faces > lines - vertices) {
    in.fail_at(last_line, lines < vertices ? fmt::format("truncated: vertex {} of {} is missing",
                                                         lines + 1, vertices)
                                           : fmt::format("truncated: face {} of {} is missing",
                                                         lines - vertices + 1, faces));
  }
  pos = body, line = body_line;

  const std::size_t coordinates = dimensions + (homogeneous ? 1 : 0);
  for (std::uint64_t i = 0; i < vertices; ++i) {
    const Line l = *next_line();
    const auto w = words(l.text);
    for (std::size_t k = 0; k < coordinates; ++k) {
      if (k >= w.size()) {
        in.fail_at(l.number, fmt::format("vertex {} of {}: {} coordinates expected, {} found",
                                         i + 1, vertices, coordinates, w.size()));
      }
      if (!parse<double>(w[k])) {
        in.fail_at(l.number, fmt::format("'{}' is not a valid vertex {} of {}", w[k].substr(0, 64),
                                         i + 1, vertices));
      }
    }
  }
  for (std::uint64_t i = 0; i < faces; ++i) {
    const Line l = *next_line();
    const auto w = words(l.text);
    const auto what = [&] { return fmt::format("face {} of {}", i + 1, faces); };
    const auto n = w.empty() ? std::nullopt : parse<std::uint64_t>(w[0]);
    if (!n) {
      in.fail_at(l.number, fmt::format("{}: '{}' is not a vertex count", what(),
                                       w.empty() ? "" : w[0].substr(0, 64)));
    }
    if (*n < 1 || *n > 9) {
      in.fail_at(l.number,
                 fmt::format("{}: {} vertices (assimp reads faces of 1 to 9)", what(), *n));
    }
    if (w.size() < *n + 1) {
      in.fail_at(l.number, fmt::format("truncated: {} has {} of its {} vertex indices", what(),
                                       w.size() - 1, *n));
    }
    for (std::size_t k = 1; k <= *n; ++k) {
      const auto index = parse<std::uint64_t>(w[k]);
      if (!index) {
        in.fail_at(l.number,
                   fmt::format("'{}' is not a valid {} vertex index", w[k].substr(0, 64), what()));
      }
      if (*index >= vertices) {
        in.fail_at(l.number,
                   fmt::format("{}: vertex index {} out of range (the file has {} vertices)",
                               what(), *index, vertices));
      }
    }
  }
}

}  // namespace aosuite::renderer
