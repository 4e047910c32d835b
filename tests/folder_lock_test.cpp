// The folder lock from a second angle: FolderLock itself, held by a forked process, where the
// CLI tests and the fault trials go through whole runs. The lock belongs to the folder's path:
// a recreated folder and a link to it are still held; the holder is named; the kernel frees the
// lock when the holder is killed; a folder the lock made and nothing wrote is removed.
#include "common/folder_lock.hpp"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <string>

namespace aosuite {
namespace {

namespace fs = std::filesystem;

// A process that locks `folder`, says so through a pipe, and waits to be killed.
pid_t hold(const fs::path& folder) {
  int ready[2];
  EXPECT_EQ(::pipe(ready), 0);
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::close(ready[0]);
    FolderLock lock(folder, false);
    const char ok = 1;
    if (::write(ready[1], &ok, 1) != 1) ::_exit(1);
    for (;;) ::pause();
  }
  ::close(ready[1]);
  char ok = 0;
  EXPECT_EQ(::read(ready[0], &ok, 1), 1);
  ::close(ready[0]);
  return pid;
}

std::string busy_message(const fs::path& folder) {
  try {
    FolderLock lock(folder, false);
  } catch (const FolderBusy& e) {
    return e.what();
  }
  return "";
}

class FolderLockTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("aosuite-lock-" + std::to_string(::getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(FolderLockTest, APathStaysHeldThroughRecreationAndLinksUntilItsHolderIsKilled) {
  const fs::path r = dir_ / "R";
  const pid_t holder = hold(r);
  EXPECT_NE(busy_message(r).find(std::to_string(holder)), std::string::npos) << busy_message(r);
  fs::remove_all(r);  // rm -rf R: a new folder, a new inode, the same path
  fs::create_directories(r);
  EXPECT_FALSE(busy_message(r).empty());
  fs::create_directory_symlink(r, dir_ / "link");
  EXPECT_FALSE(busy_message(dir_ / "link").empty());
  ::kill(holder, SIGKILL);
  ::waitpid(holder, nullptr, 0);
  EXPECT_EQ(busy_message(r), "");  // freed by the kernel: taken over at once
}

TEST_F(FolderLockTest, AFolderItMadeAndNothingWroteIsRemoved) {
  const fs::path made = dir_ / "a" / "b";
  {
    FolderLock lock(made, false);
    EXPECT_TRUE(fs::is_directory(made));
  }
  EXPECT_FALSE(fs::exists(dir_ / "a"));
  const fs::path kept = dir_ / "kept";
  {
    FolderLock lock(kept, false);
    std::FILE* f = std::fopen((kept / "x").c_str(), "w");
    ASSERT_NE(f, nullptr);
    std::fclose(f);
  }
  EXPECT_TRUE(fs::exists(kept / "x"));
}

}  // namespace
}  // namespace aosuite
