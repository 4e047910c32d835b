// One run at a time in each folder aosuite writes (a report folder, a goldens folder, an
// --expected folder): an exclusive flock(2) on a lock file named after the folder's canonical
// path, kept in the user's runtime folder ($XDG_RUNTIME_DIR/aosuite-locks, else
// /tmp/aosuite-locks-<uid>), so no lock file is left in a user's folder. The lock belongs to the
// path, not to the folder's inode: `rm -rf R && aosuite check ... --report R` in two jobs at
// once makes two folders in turn, and the second run must still wait for the first. The kernel
// drops the lock when its holder ends, however it ends, so a killed run never leaves a folder
// locked: the next run takes it over without asking. Who holds a lock is read from /proc/locks.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>

namespace aosuite {

// Another process holds the folder: the message names the folder and the holder (its pid, when
// it started, its command line).
class FolderBusy : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class FolderLock {
 public:
  // Creates the folder if needed and locks it. When another process holds it: throws FolderBusy
  // at once, or with `wait` blocks until it is free. Throws FileError when the folder or its
  // lock file cannot be made or opened (a file in its place, no permission). A folder made here and
  // still empty when the lock is released is removed: a run that wrote nothing leaves nothing.
  FolderLock(const std::filesystem::path& folder, bool wait);
  ~FolderLock();
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;

 private:
  int fd_ = -1;
  std::string real_;  // the folder's canonical path
  // The folders this lock created: the folder and its ancestors up to made_top_.
  std::filesystem::path made_, made_top_;
};

}  // namespace aosuite
