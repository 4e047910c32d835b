// Files as the whole project reads and writes them: errors that name the file, reads that
// work on pipes and FIFOs, memory-mapped inputs, and writes that readers only ever see whole.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <stdexcept>
#include <string_view>
#include <utility>
#include <vector>

namespace aosuite {

// An error about one file. what() is a single line that names the file and the problem.
class FileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// How long reading a named FIFO waits for its first byte before giving up (no writer?);
// AOSUITE_FIFO_WAIT_MS overrides it.
inline constexpr int kFifoWaitMs = 5000;

// The most the harness reads of any one file (a case's image, a golden, a report's image, a
// shard's results.json), as `compare --memory-limit` defaults to: a larger one is refused with
// its name, never read until memory runs out.
inline constexpr std::uint64_t kMaxFileBytes = std::uint64_t{1024} << 20;

// The whole file: regular files, pipes, FIFOs and devices alike, read to end-of-file.
// Throws FileError when it is over max_bytes.
std::vector<unsigned char> read_file(const std::filesystem::path& path,
                                     std::uint64_t max_bytes = UINT64_MAX);

// A regular file's bytes, as the harness reads every file of a suite (inputs, files, goldens
// and their variants): a device, FIFO, socket or folder, a link to one included, is refused at
// once, naming the file, and so is a file over max_bytes, before anything is read.
std::vector<unsigned char> read_regular_file(const std::filesystem::path& path,
                                             std::uint64_t max_bytes = kMaxFileBytes);

// Throws FileError naming `path` when a link on the way to it leads out of the folder `root`
// (the suite's folder for its files, the goldens folder for goldens, {out} for a command's
// outputs): a link must not make aosuite read, judge or bless a file it was never pointed at.
// A path with no link on it may lie anywhere. `opt_in` names how to allow it, for the message.
void check_no_link_out(const std::filesystem::path& path, const std::filesystem::path& root,
                       std::string_view opt_in);

// A file's bytes mapped read-only: no copy and no zeroed buffer, which for image-sized files
// is measurable in a command that runs for a few tens of milliseconds.
// Pipes, FIFOs and devices are read to end-of-file instead (read_file), up to max_bytes.
class MappedFile {
 public:
  explicit MappedFile(const std::filesystem::path& path, std::uint64_t max_bytes = UINT64_MAX);
  ~MappedFile();
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;
  std::span<const unsigned char> bytes() const { return {data_, size_}; }

 private:
  const unsigned char* data_ = nullptr;
  std::size_t size_ = 0;
  std::vector<unsigned char> fallback_;  // for what cannot be mapped (pipes, empty files)
  bool mapped_ = true;
};

// Writes via a temporary file in the same directory and rename(2), so readers only ever see
// the old file or the complete new one.
void write_file_atomic(const std::filesystem::path& path, std::span<const unsigned char> bytes);
// Text via write_file_atomic.
void write_text(const std::filesystem::path& path, std::string_view text);

// Several files written all or none: each stage() writes a complete temporary beside its path,
// commit() renames them into place, and whatever was not committed (an error on the way, a later
// stage that failed) is removed, so a command that fails leaves none of its outputs behind.
class StagedFiles {
 public:
  StagedFiles() = default;
  StagedFiles(const StagedFiles&) = delete;
  StagedFiles& operator=(const StagedFiles&) = delete;
  ~StagedFiles();
  void stage(const std::filesystem::path& path, std::span<const unsigned char> bytes);
  void commit();

 private:
  std::vector<std::pair<std::filesystem::path, std::string>> staged_;  // path, its temporary
};

}  // namespace aosuite
