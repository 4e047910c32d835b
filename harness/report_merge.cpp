#include "harness/report_merge.hpp"

#include <fmt/format.h>

#include <set>
#include <stdexcept>

#include "common/file_io.hpp"
#include "common/folder_lock.hpp"
#include "harness/escape.hpp"
#include "harness/runner.hpp"
#include "harness/suite.hpp"

namespace aosuite::harness {
namespace {

namespace fs = std::filesystem;

// A shard's case folder as merge copies it: the folder and each of its report files (those
// with valid names) plain, never a link, which would lead out of the shard or leave the merged
// report pointing at a file it does not have. Throws naming the first that is not. Returns
// whether there is a folder to copy.
bool check_case_folder(const fs::path& from) {
  std::error_code ec;
  const fs::file_status st = fs::symlink_status(from, ec);
  if (!fs::exists(st)) return false;
  const auto refuse = [](const fs::path& p) {
    throw std::runtime_error(
        printable(p.string() + ": a link or special file in a shard's report; nothing was merged"));
  };
  if (!fs::is_directory(st)) refuse(from);
  for (const fs::directory_entry& e : fs::directory_iterator(from)) {
    if (valid_name(e.path().filename().string()) && !fs::is_regular_file(e.symlink_status()))
      refuse(e.path());
  }
  return true;
}

// Copies a shard's case folder (check_case_folder): each file written under a temporary name
// and renamed.
void copy_case(const fs::path& from, const fs::path& to) {
  fs::create_directories(to);
  for (const fs::directory_entry& e : fs::directory_iterator(from)) {
    if (valid_name(e.path().filename().string()))
      write_file_atomic(to / e.path().filename(), read_regular_file(e.path()));
  }
}

// Which of the run's shards these parts are, from each results.json's "i/n" (an unsharded run
// is 0/1): all of one count, none twice. Throws naming the folder. Returns the count.
int shard_count(const std::vector<RunResults>& parts, const std::vector<std::string>& dirs,
                std::set<int>& given) {
  int count = 0;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    Selection s;
    try {
      if (!parts[i].shard.empty()) set_shard(s, parts[i].shard);  // "" would read GTEST_*
    } catch (const std::invalid_argument& e) {
      throw std::runtime_error(printable(fmt::format("{}: {}", dirs[i], e.what())));
    }
    if (count != 0 && s.shard_count != count) {
      throw std::runtime_error(
          printable(fmt::format("{}: shard {}/{} is of another run than {} shards", dirs[i],
                                s.shard_index, s.shard_count, count)));
    }
    count = s.shard_count;
    if (!given.insert(s.shard_index).second) {
      throw std::runtime_error(
          printable(fmt::format("{}: shard {}/{} is given twice", dirs[i], s.shard_index, count)));
    }
  }
  return count;
}

}  // namespace

MergedReport merge_reports(const fs::path& out, const std::vector<std::string>& shards,
                           bool partial, bool wait) {
  std::vector<RunResults> parts;
  for (const std::string& dir : shards) {
    parts.push_back(read_results(dir));
    if (parts.back().suite != parts.front().suite) {
      throw std::runtime_error(printable(fmt::format("{}: suite '{}' differs from '{}'", dir,
                                                     parts.back().suite, parts.front().suite)));
    }
  }
  for (const std::string& dir : shards) {
    std::error_code ec;
    if (fs::equivalent(dir, out, ec)) {
      throw std::runtime_error(printable(fmt::format(
          "--out {} is the shard {}; merge into a folder of its own", out.string(), dir)));
    }
  }
  std::set<int> given;
  const int count = shard_count(parts, shards, given);
  std::set<std::string> seen;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    for (const CaseResult& c : parts[i].cases) {
      if (!seen.insert(c.id).second) {
        throw std::runtime_error(
            printable(fmt::format("{}: case '{}' is in two shards", shards[i], c.id)));
      }
    }
  }
  std::string missing;
  for (int i = 0; i < count; ++i) {
    if (!given.count(i)) missing += fmt::format("{}{}/{}", missing.empty() ? "" : ", ", i, count);
  }
  if (!missing.empty() && !partial) {
    throw std::runtime_error(fmt::format(
        "shard{} {} of the run {} missing (--partial merges a part of a run, marked partial)",
        given.size() + 1 < std::size_t(count) ? "s" : "", missing,
        given.size() + 1 < std::size_t(count) ? "are" : "is"));
  }
  std::vector<std::vector<bool>> has_folder(parts.size());
  for (std::size_t i = 0; i < parts.size(); ++i) {
    for (const CaseResult& c : parts[i].cases)
      has_folder[i].push_back(check_case_folder(fs::path(shards[i]) / "cases" / c.id));
  }
  const FolderLock lock(out, wait);
  RunResults merged = parts.front();
  merged.cases.clear();
  merged.shard = missing.empty() ? "" : "partial, missing " + missing;
  merged.approve_prefix =
      merged.bless_prefix + " --from-report --report " + shell_quote(out.string());
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const fs::path dir = shards[i];
    for (std::size_t k = 0; k < parts[i].cases.size(); ++k) {
      CaseResult& c = parts[i].cases[k];
      if (has_folder[i][k]) copy_case(dir / "cases" / c.id, fs::path(out) / "cases" / c.id);
      merged.cases.push_back(std::move(c));
    }
  }
  write_results(out, merged);
  return {std::move(merged), missing};
}

}  // namespace aosuite::harness
