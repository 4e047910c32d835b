// What the fuzz targets share: a failure that libFuzzer reports with its input, the check that
// messages are escaped, and a scratch folder for the parsers that read files.
#pragma once

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include "common/printable.hpp"

namespace aosuite::fuzz {

// Aborts, so libFuzzer saves the input as a crash: for a broken property rather than a
// sanitizer report.
[[noreturn]] inline void fail(std::string_view what) {
  std::fprintf(stderr, "fuzz property broken: %.*s\n", static_cast<int>(what.size()), what.data());
  std::abort();
}

// Messages that quote a file must be escaped (a mutated file's bytes must not reach a
// terminal raw): printable() leaves them unchanged.
inline void expect_printable(std::string_view message) {
  if (printable(message) != message) fail(std::string("unescaped message: ") + printable(message));
}

// A folder of this process's own under $TMPDIR (fuzz/run.sh points it into build-fuzz/),
// removed at exit.
inline const std::filesystem::path& scratch() {
  struct Dir {
    std::filesystem::path path;
    Dir() {
      std::string tmpl = (std::filesystem::temp_directory_path() / "aosuite-fuzz-XXXXXX").string();
      if (!::mkdtemp(tmpl.data())) fail("cannot create a scratch folder");
      path = tmpl;
    }
    ~Dir() {
      std::error_code ec;
      std::filesystem::remove_all(path, ec);
    }
  };
  static const Dir dir;
  return dir.path;
}

inline void write_file(const std::filesystem::path& path, std::string_view bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc)
      .write(bytes.data(), std::streamsize(bytes.size()));
}

inline std::string_view as_text(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

}  // namespace aosuite::fuzz
