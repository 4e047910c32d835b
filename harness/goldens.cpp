#include "harness/goldens.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <signal.h>
#include <stdio.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <stdexcept>

#include "common/file_io.hpp"

namespace aosuite::harness {

namespace fs = std::filesystem;

std::string platform_key(std::string_view description) {
  std::string_view renderer = description;
  if (const std::size_t a = description.find(" | "); a != std::string_view::npos) {
    renderer = description.substr(a + 3);
    renderer = renderer.substr(0, renderer.find(" | "));
  }
  std::string key;
  for (const char ch : renderer) {
    if (std::isalnum(static_cast<unsigned char>(ch))) {
      key += static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    } else if (!key.empty() && key.back() != '-') {
      key += '-';
    }
  }
  while (!key.empty() && key.back() == '-') key.pop_back();
  return key.empty() ? "unknown" : key;
}

namespace {

// <image><ext> first, then its variants <image>~<tag><ext> in name order. A missing folder
// holds none; one that exists and cannot be listed is an error, not "no golden yet".
std::vector<fs::path> goldens_in(const fs::path& dir, std::string_view image, std::string_view ext,
                                 bool variants_only = false) {
  std::vector<fs::path> out;
  std::error_code ec;
  fs::directory_iterator it(dir, ec);
  if (ec == std::errc::no_such_file_or_directory) return out;
  const auto fail = [&] {
    throw std::runtime_error(
        fmt::format("{}: cannot read the golden folder: {}", dir.string(), ec.message()));
  };
  if (ec) fail();
  for (; it != fs::directory_iterator(); it.increment(ec)) {
    const std::string name = it->path().filename().string();
    const bool primary = !variants_only && name == std::string(image) + std::string(ext);
    const bool variant = name.starts_with(std::string(image) + "~") && name.ends_with(ext);
    if (primary || variant) out.push_back(it->path());
  }
  if (ec) fail();
  std::sort(out.begin(), out.end(), [](const fs::path& a, const fs::path& b) {
    const bool av = a.filename().string().find('~') != std::string::npos;
    const bool bv = b.filename().string().find('~') != std::string::npos;
    return av != bv ? bv : a < b;
  });
  return out;
}

[[noreturn]] void fail_errno(const fs::path& path, std::string_view what) {
  throw std::runtime_error(fmt::format("{}: {}: {}", path.string(), what, std::strerror(errno)));
}

// Writes `bytes` to a new temporary beside `path` and syncs it; returns the temporary's name.
fs::path write_temporary(const fs::path& path, std::span<const unsigned char> bytes) {
  std::string tmp =
      (path.parent_path() /
       fmt::format(".{}.bless-{}-XXXXXX", path.filename().string(), static_cast<long>(::getpid())))
          .string();
  const int fd = ::mkstemp(tmp.data());
  if (fd < 0) fail_errno(path, "cannot create a temporary file beside it");
  const auto abandon = [&](std::string_view what) {
    const int saved = errno;
    ::close(fd);
    ::unlink(tmp.c_str());
    errno = saved;
    fail_errno(path, what);
  };
  for (std::size_t done = 0; done < bytes.size();) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) abandon("cannot write");
    done += static_cast<std::size_t>(n);
  }
  const mode_t mask = ::umask(0);  // mkstemp creates 0600; give what a plain create would
  ::umask(mask);
  if (::fchmod(fd, 0666 & ~mask) != 0 || ::fsync(fd) != 0) abandon("cannot finish writing");
  if (::close(fd) != 0) {
    const int saved = errno;
    ::unlink(tmp.c_str());
    errno = saved;
    fail_errno(path, "cannot close");
  }
  return tmp;
}

// ".with_ao.png.bless-1234-AbC123" -> 1234; 0 when the name is not one of ours.
long temporary_owner(const std::string& name) {
  const std::size_t at = name.rfind(".bless-");
  if (!name.starts_with(".") || at == std::string::npos) return 0;
  const std::size_t dash = name.find('-', at + 7);
  if (dash == std::string::npos || name.size() - dash - 1 != 6) return 0;
  long pid = 0;
  for (std::size_t i = at + 7; i < dash; ++i) {
    if (!std::isdigit(static_cast<unsigned char>(name[i]))) return 0;
    pid = pid * 10 + (name[i] - '0');
    if (pid > (1L << 30)) return 0;
  }
  return pid;
}

bool legacy_temporary(const std::string& name) {
  const std::size_t at = name.rfind(".tmp-");
  return name.starts_with(".") && at != std::string::npos && name.size() - at == 11;
}

}  // namespace

std::vector<ReadGolden> read_goldens(const std::vector<fs::path>& files) {
  std::vector<ReadGolden> out;
  for (const fs::path& f : files) {
    ReadGolden& g = out.emplace_back();
    g.file = f;
    try {
      g.bytes = read_regular_file(f);
    } catch (const std::exception& e) {
      g.error = e.what();
    }
  }
  return out;
}

std::vector<fs::path> accepted_goldens(const fs::path& case_dir, std::string_view image,
                                       std::string_view ext, std::string_view platform) {
  std::vector<fs::path> generic = goldens_in(case_dir, image, ext);
  if (platform.empty()) return generic;
  std::vector<fs::path> out = goldens_in(case_dir / platform, image, ext);
  if (out.empty()) return generic;
  for (const fs::path& g : generic) {
    if (g.filename().string().find('~') != std::string::npos) out.push_back(g);
  }
  return out;
}

fs::path golden_path(const fs::path& case_dir, std::string_view image, std::string_view ext,
                     std::string_view platform, std::string_view tag) {
  const std::string name = fmt::format("{}{}{}{}", image, tag.empty() ? "" : "~", tag, ext);
  return platform.empty() ? case_dir / name : case_dir / platform / name;
}

void replace_goldens(const std::vector<GoldenWrite>& files) {
  for (const auto& [path, bytes] : files) {
    std::error_code ec;
    const fs::file_status st = fs::symlink_status(path, ec);
    if (!ec && fs::exists(st) && !fs::is_regular_file(st)) {
      throw std::runtime_error(path.string() + ": is not a file; nothing was replaced");
    }
    fs::create_directories(path.parent_path(), ec);
    if (ec) {
      throw std::runtime_error(fmt::format("{}: cannot create the folder: {}",
                                           path.parent_path().string(), ec.message()));
    }
  }
  std::vector<fs::path> temporaries;
  try {
    for (const auto& [path, bytes] : files) temporaries.push_back(write_temporary(path, bytes));
  } catch (const std::exception& e) {
    for (const fs::path& t : temporaries) ::unlink(t.c_str());
    throw std::runtime_error(std::string(e.what()) + "; nothing was replaced");
  }
  for (std::size_t i = 0; i < files.size(); ++i) {
    if (::rename(temporaries[i].c_str(), files[i].first.c_str()) != 0) {
      const int saved = errno;
      for (std::size_t k = i; k < files.size(); ++k) ::unlink(temporaries[k].c_str());
      errno = saved;
      fail_errno(files[i].first, fmt::format("cannot rename into place ({} of {} files of this "
                                             "case were already replaced)",
                                             i, files.size()));
    }
  }
}

namespace {

// The staged folder's tree: `from`'s sub-folders made again and its files hard-linked (copied
// where the file system cannot link), our temporaries left out.
void stage_copy(const fs::path& from, const fs::path& to) {
  std::error_code ec;
  fs::directory_iterator it(from, ec);
  if (ec == std::errc::no_such_file_or_directory) return;
  if (ec)
    throw std::runtime_error(from.string() + ": cannot read the golden folder: " + ec.message());
  for (; it != fs::directory_iterator(); it.increment(ec)) {
    const fs::path p = it->path(), target = to / p.filename();
    const std::string name = p.filename().string();
    if (temporary_owner(name) > 0) continue;
    const fs::file_status st = it->symlink_status(ec);
    if (fs::is_directory(st)) {
      fs::create_directory(target);
      stage_copy(p, target);
    } else if (fs::is_regular_file(st)) {
      if (::link(p.c_str(), target.c_str()) != 0) fs::copy_file(p, target);
    }
  }
  if (ec)
    throw std::runtime_error(from.string() + ": cannot read the golden folder: " + ec.message());
}

// A new file at `path` (replacing a link to the old one: the old golden is never written to).
void write_new(const fs::path& path, std::span<const unsigned char> bytes) {
  fs::create_directories(path.parent_path());
  if (::unlink(path.c_str()) != 0 && errno != ENOENT) fail_errno(path, "cannot replace");
  const fs::path tmp = write_temporary(path, bytes);
  if (::rename(tmp.c_str(), path.c_str()) != 0) {
    const int saved = errno;
    ::unlink(tmp.c_str());
    errno = saved;
    fail_errno(path, "cannot write");
  }
}

void sync_folder(const fs::path& dir) {
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY);
  if (fd >= 0) ::fsync(fd), ::close(fd);
}

}  // namespace

void replace_case_goldens(const fs::path& case_dir, const std::vector<GoldenWrite>& files) {
  const fs::path parent = case_dir.parent_path();
  std::error_code ec;
  const fs::file_status st = fs::symlink_status(case_dir, ec);
  if (!ec && fs::exists(st) && !fs::is_directory(st)) {
    throw std::runtime_error(case_dir.string() + ": is not a folder; nothing was replaced");
  }
  const bool exists = fs::exists(st);
  fs::create_directories(parent, ec);
  if (ec) {
    throw std::runtime_error(
        fmt::format("{}: cannot create the folder: {}", parent.string(), ec.message()));
  }
  std::string staged = (parent / fmt::format(".{}.bless-{}-XXXXXX", case_dir.filename().string(),
                                             static_cast<long>(::getpid())))
                           .string();
  if (!::mkdtemp(staged.data())) fail_errno(case_dir, "cannot create a folder beside it");
  try {
    for (const auto& [path, bytes] : files) {
      const fs::path rel = path.lexically_relative(case_dir);
      if (rel.empty() || *rel.begin() == "..") {
        throw std::runtime_error(path.string() + ": not inside " + case_dir.string());
      }
      const fs::file_status f = fs::symlink_status(path, ec);
      if (!ec && fs::exists(f) && !fs::is_regular_file(f)) {
        throw std::runtime_error(path.string() + ": is not a file");
      }
    }
    stage_copy(case_dir, staged);
    for (const auto& [path, bytes] : files) {
      write_new(fs::path(staged) / path.lexically_relative(case_dir), bytes);
      sync_folder((fs::path(staged) / path.lexically_relative(case_dir)).parent_path());
    }
    sync_folder(staged);
    // The one step that changes what readers see. Without RENAME_EXCHANGE (a file system that
    // lacks it) the folder is moved aside first: a reader may then briefly find no goldens
    // (NEW, a failure), never a mix.
    if (exists &&
        ::renameat2(AT_FDCWD, staged.c_str(), AT_FDCWD, case_dir.c_str(), RENAME_EXCHANGE) != 0) {
      if (errno != EINVAL && errno != ENOSYS) fail_errno(case_dir, "cannot replace");
      const std::string aside = fmt::format("{}-old", staged);
      if (::rename(case_dir.c_str(), aside.c_str()) != 0) fail_errno(case_dir, "cannot move aside");
      if (::rename(staged.c_str(), case_dir.c_str()) != 0) {
        const int saved = errno;
        ::rename(aside.c_str(), case_dir.c_str());
        errno = saved;
        fail_errno(case_dir, "cannot replace");
      }
      staged = aside;
    } else if (!exists && ::renameat2(AT_FDCWD, staged.c_str(), AT_FDCWD, case_dir.c_str(),
                                      RENAME_NOREPLACE) != 0) {
      fail_errno(case_dir, "cannot create");
    }
  } catch (const std::exception& e) {
    fs::remove_all(staged, ec);
    throw std::runtime_error(std::string(e.what()) + "; nothing was replaced");
  }
  sync_folder(parent);
  if (exists) fs::remove_all(staged, ec);  // the old case, now under the staged name
}

int remove_stale_temporaries(const fs::path& case_dir) {
  int removed = 0;
  std::error_code ec;
  // Staged or replaced copies of this case beside it (.<case>.bless-<pid>-XXXXXX[-old]).
  const std::string prefix = fmt::format(".{}.bless-", case_dir.filename().string());
  for (const fs::directory_entry& e : fs::directory_iterator(case_dir.parent_path(), ec)) {
    std::string name = e.path().filename().string();
    if (!name.starts_with(prefix) || !e.is_directory(ec) || e.is_symlink(ec)) continue;
    if (name.ends_with("-old")) name.resize(name.size() - 4);
    const long pid = temporary_owner(name);
    if (pid > 0 && ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH &&
        fs::remove_all(e.path(), ec) > 0) {
      ++removed;
    }
  }
  std::vector<fs::path> dirs{case_dir};
  for (const fs::directory_entry& e : fs::directory_iterator(case_dir, ec)) {
    if (e.is_directory(ec) && !e.is_symlink(ec)) dirs.push_back(e.path());
  }
  const auto now = fs::file_time_type::clock::now();
  for (const fs::path& dir : dirs) {
    for (const fs::directory_entry& e : fs::directory_iterator(dir, ec)) {
      const std::string name = e.path().filename().string();
      bool stale = false;
      if (const long pid = temporary_owner(name); pid > 0) {
        stale = ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH;
      } else if (legacy_temporary(name)) {
        std::error_code tec;
        const auto when = fs::last_write_time(e.path(), tec);
        stale = !tec && now - when > std::chrono::minutes(1);
      }
      if (stale && e.is_regular_file(ec) && fs::remove(e.path(), ec)) ++removed;
    }
  }
  return removed;
}

}  // namespace aosuite::harness
