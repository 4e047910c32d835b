#include "harness/command.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <thread>

#include "common/file_io.hpp"

extern char** environ;

namespace aosuite::harness {

namespace fs = std::filesystem;

namespace {

std::string tail_of(const fs::path& file, std::size_t bytes) {
  std::ifstream in(file, std::ios::binary | std::ios::ate);
  if (!in) return {};
  const std::streamoff size = in.tellg();
  const std::streamoff from =
      size > static_cast<std::streamoff>(bytes) ? size - static_cast<std::streamoff>(bytes) : 0;
  in.seekg(from);
  std::string out(static_cast<std::size_t>(size - from), '\0');
  in.read(out.data(), static_cast<std::streamsize>(out.size()));
  return from > 0 ? "..." + out : out;
}

// What the report keeps of a command's output: its last kKeptOutput bytes, after a line that
// gives the full size (a noisy command once left 200 MB in a report).
constexpr std::size_t kKeptOutput = 64 * 1024;
void keep_tail(const fs::path& file) {
  std::error_code ec;
  const std::uintmax_t size = fs::file_size(file, ec);
  if (ec || size <= kKeptOutput) return;
  const std::string tail = tail_of(file, kKeptOutput).substr(3);
  const std::string text = "[aosuite: " + std::to_string(size) + " bytes written; the last " +
                           std::to_string(kKeptOutput) + " kept]\n" + tail;
  write_file_atomic(file, {reinterpret_cast<const unsigned char*>(text.data()), text.size()});
}

// Frees the disk blocks of all but the last kKeptOutput bytes of an output file the command is
// still writing (a hole punched before them; its size, the count written, stays): a command
// that writes gigabytes to stdout holds a few MiB of disk in the report folder, not gigabytes,
// while it runs. Where the file system has no holes, nothing is freed until keep_tail.
void free_all_but_tail(int fd) {
  constexpr off_t kPunchAbove = 4 << 20;
  struct stat st {};
  if (::fstat(fd, &st) != 0 || static_cast<off_t>(st.st_blocks) * 512 <= kPunchAbove) return;
  const off_t end = (st.st_size - static_cast<off_t>(kKeptOutput) - 1) & ~off_t{4095};
  if (end > 0) (void)::fallocate(fd, FALLOC_FL_PUNCH_HOLE | FALLOC_FL_KEEP_SIZE, 0, end);
}

// argv[0] as execve needs it: a path with '/' as given, else the first executable in PATH.
std::string resolve(const std::string& program) {
  if (program.find('/') != std::string::npos) return program;
  const char* path = std::getenv("PATH");
  std::string dirs = path ? path : "/usr/local/bin:/usr/bin:/bin";
  for (std::size_t at = 0; at <= dirs.size();) {
    const std::size_t end = std::min(dirs.find(':', at), dirs.size());
    const std::string dir = end > at ? dirs.substr(at, end - at) : ".";
    const std::string candidate = dir + "/" + program;
    if (::access(candidate.c_str(), X_OK) == 0 && !fs::is_directory(candidate)) return candidate;
    at = end + 1;
  }
  throw std::runtime_error("cannot run '" + program + "': " + std::strerror(ENOENT));
}

// --- The reaper: a forked copy of this process that owns one command's process tree. -------
// Everything below runs in the forked child of a multithreaded process, so it uses only
// async-signal-safe system calls and stack memory (no allocation, no locks, no exceptions).

// The parent process id in /proc/<pid>/stat ("pid (comm) state ppid ..."; comm may hold
// spaces and parentheses, so the last ')' ends it); -1 when gone or unreadable.
pid_t parent_of(int proc, const char* pid) {
  char path[32];
  std::size_t len = 0;
  for (; pid[len] && len < 20; ++len) path[len] = pid[len];
  std::memcpy(path + len, "/stat", 6);
  const int fd = ::openat(proc, path, O_RDONLY | O_CLOEXEC);
  if (fd < 0) return -1;
  char buf[512];
  const ssize_t n = ::read(fd, buf, sizeof buf - 1);
  ::close(fd);
  if (n <= 0) return -1;
  buf[n] = '\0';
  const char* p = std::strrchr(buf, ')');
  if (!p || p[1] != ' ' || !p[2] || p[3] != ' ') return -1;
  long ppid = 0;
  for (p += 4; *p >= '0' && *p <= '9'; ++p) ppid = ppid * 10 + (*p - '0');
  return static_cast<pid_t>(ppid);
}

// Kills every descendant of this process (by parent links in /proc; as a child subreaper, every
// orphan of the tree, `setsid` or double-forked daemons included, becomes a child here) and
// reaps them, until none is left. Returns the command's wait status if it was reaped here.
void kill_tree(pid_t command, int& command_status) {
  constexpr int kMax = 4096;
  pid_t pids[kMax], parents[kMax];
  bool below[kMax];
  for (;;) {
    int n = 0;
    if (const int dir = ::open("/proc", O_RDONLY | O_DIRECTORY | O_CLOEXEC); dir >= 0) {
      alignas(dirent64) char buf[8192];
      for (long got; (got = ::syscall(SYS_getdents64, dir, buf, sizeof buf)) > 0;) {
        for (long at = 0; at < got;) {
          const auto* e = reinterpret_cast<const dirent64*>(buf + at);
          at += e->d_reclen;
          if (e->d_name[0] < '1' || e->d_name[0] > '9' || n == kMax) continue;
          pids[n] = static_cast<pid_t>(std::atol(e->d_name));
          parents[n++] = parent_of(dir, e->d_name);
        }
      }
      ::close(dir);
    }
    // Descendants: children of this process, then their children, and so on.
    const pid_t self = ::getpid();
    for (int i = 0; i < n; ++i) below[i] = parents[i] == self;
    for (bool grew = true; grew;) {
      grew = false;
      for (int i = 0; i < n; ++i) {
        for (int k = 0; k < n && !below[i]; ++k) {
          if (below[k] && pids[k] == parents[i]) below[i] = grew = true;
        }
      }
    }
    for (int i = 0; i < n; ++i)
      if (below[i] && pids[i] > 1 && pids[i] != self) ::kill(pids[i], SIGKILL);
    int status = 0;
    const pid_t done = ::waitpid(-1, &status, 0);
    if (done < 0 && errno == ECHILD) return;
    if (done == command) command_status = status;
  }
}

[[noreturn]] void reap(pid_t parent, const char* file, char* const* argv, char* const* envp,
                       const char* cwd, int in, int out, int err, int exec_error) {
  ::prctl(PR_SET_CHILD_SUBREAPER, 1);
  ::signal(SIGCHLD, SIG_DFL);  // pending while blocked, for sigwaitinfo (never SIG_IGN's reaping)
  ::prctl(PR_SET_PDEATHSIG, SIGTERM);  // aosuite gone (killed, Ctrl-C): end the command too
  // Out of aosuite's process group: `kill -9 -- -PGID` or `timeout -s KILL` (which signals its
  // whole group) would kill the reaper beside aosuite, before it could end the command. Outside
  // it, only aosuite dies, and its death reaches the reaper as the signal above.
  ::setpgid(0, 0);
  sigset_t wanted, none;
  sigemptyset(&wanted);
  sigemptyset(&none);
  for (int s : {SIGCHLD, SIGTERM, SIGINT, SIGHUP, SIGQUIT}) sigaddset(&wanted, s);
  ::sigprocmask(SIG_SETMASK, &wanted, nullptr);
  if (::getppid() != parent) ::_exit(128 + SIGTERM);  // it died before PDEATHSIG was set
  // Only the command's files stay open here: a folder lock (common/folder_lock.hpp) or any other
  // descriptor of aosuite's must not outlive aosuite in its reaper.
  int keep[] = {in, out, err, exec_error};
  std::sort(std::begin(keep), std::end(keep));
  unsigned from = 3;
  for (const int fd : keep) {
    if (fd >= static_cast<int>(from)) ::syscall(SYS_close_range, from, fd - 1, 0), from = fd + 1;
  }
  ::syscall(SYS_close_range, from, ~0U, 0);
  const pid_t self = ::getpid();
  const pid_t command = ::fork();
  if (command == 0) {
    // The command: its own process group, default signal handling, the files as stdin, stdout
    // and stderr; it dies with the reaper, should the reaper alone be killed.
    ::setpgid(0, 0);
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (::getppid() != self) ::_exit(128 + SIGKILL);  // the reaper died before that was set
    for (int s = 1; s < NSIG; ++s) ::signal(s, SIG_DFL);
    ::sigprocmask(SIG_SETMASK, &none, nullptr);
    if (::dup2(in, 0) < 0 || ::dup2(out, 1) < 0 || ::dup2(err, 2) < 0 || ::chdir(cwd) != 0) {
      const int e = errno;
      (void)!::write(exec_error, &e, sizeof e);
      ::_exit(127);
    }
    ::execve(file, argv, envp);
    const int e = errno;
    (void)!::write(exec_error, &e, sizeof e);
    ::_exit(127);
  }
  ::close(exec_error);  // the parent reads EOF once the command has exec'd (or a failure)
  int status = 0;
  bool exited = command < 0;
  if (command < 0) status = 127 << 8;
  while (!exited) {
    siginfo_t info;
    const int sig = ::sigwaitinfo(&wanted, &info);
    if (sig < 0) continue;
    if (sig != SIGCHLD) {
      kill_tree(command, status);
      ::_exit(128 + sig);
    }
    int reaped = 0;
    for (pid_t done; (done = ::waitpid(-1, &reaped, WNOHANG)) > 0;) {
      if (done == command) status = reaped, exited = true;
    }
  }
  int ignored = 0;
  kill_tree(command, ignored);  // what it left running
  if (WIFSIGNALED(status)) {
    // Ended by a signal: so is the reaper, by the same one (without a core file), so that aosuite
    // tells SIGXFSZ from an exit status of 153.
    const int sig = WTERMSIG(status);
    ::prctl(PR_SET_DUMPABLE, 0);
    ::signal(sig, SIG_DFL);
    ::sigprocmask(SIG_SETMASK, &none, nullptr);
    ::kill(::getpid(), sig);
  }
  ::_exit(WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status));
}

int open_or_throw(const fs::path& path, int flags) {
  const int fd = ::open(path.c_str(), flags | O_CLOEXEC, 0644);
  if (fd < 0) throw FileError(path.string() + ": " + std::strerror(errno));
  return fd;
}

}  // namespace

CommandOutcome run_command(const std::vector<std::string>& argv, const fs::path& cwd,
                           const fs::path& stdout_file, const fs::path& stderr_file,
                           double timeout_seconds, const std::vector<std::string>& env) {
  if (argv.empty()) throw std::runtime_error("empty command");
  // Everything the forked reaper needs is made here, before the fork.
  const std::string file = resolve(argv[0]);
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  std::vector<char*> envp;
  for (const std::string& e : env) envp.push_back(const_cast<char*>(e.c_str()));
  for (char** e = environ; e && *e; ++e) envp.push_back(*e);
  envp.push_back(nullptr);
  const std::string dir = cwd.string();
  const int in = open_or_throw("/dev/null", O_RDONLY);
  const int out = open_or_throw(fs::absolute(stdout_file), O_WRONLY | O_CREAT | O_TRUNC);
  const int err = open_or_throw(fs::absolute(stderr_file), O_WRONLY | O_CREAT | O_TRUNC);
  int exec_pipe[2];
  if (::pipe2(exec_pipe, O_CLOEXEC) != 0) throw std::runtime_error("pipe failed");
  const pid_t parent = ::getpid();
  const pid_t reaper = ::fork();
  if (reaper == 0)
    reap(parent, file.c_str(), args.data(), envp.data(), dir.c_str(), in, out, err, exec_pipe[1]);
  for (int fd : {in, exec_pipe[1]}) ::close(fd);
  struct Close {
    int a, b;
    ~Close() { ::close(a), ::close(b); }
  } outputs{out, err};  // kept here to free their old blocks while the command writes
  if (reaper < 0) {
    ::close(exec_pipe[0]);
    throw std::runtime_error("cannot run '" + argv[0] + "': fork failed");
  }
  int exec_errno = 0;
  ssize_t got;
  while ((got = ::read(exec_pipe[0], &exec_errno, sizeof exec_errno)) < 0 && errno == EINTR) {
  }
  ::close(exec_pipe[0]);

  CommandOutcome o;
  const auto deadline = std::chrono::steady_clock::now() +
                        std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                            std::chrono::duration<double>(timeout_seconds));
  auto pause = std::chrono::microseconds(200);
  int status = 0;
  for (;;) {
    const pid_t done = ::waitpid(reaper, &status, WNOHANG);
    if (done == reaper) break;
    if (done < 0 && errno != EINTR) throw std::runtime_error("waitpid failed");
    if (std::chrono::steady_clock::now() >= deadline) {
      ::kill(reaper, SIGTERM);  // the reaper ends the command's whole tree, then itself
      ::waitpid(reaper, &status, 0);
      o.timed_out = true;
      break;
    }
    std::this_thread::sleep_for(pause);
    pause = std::min(pause * 2, std::chrono::microseconds(20000));
    free_all_but_tail(out);
    free_all_but_tail(err);
  }
  if (got == sizeof exec_errno) {
    throw std::runtime_error("cannot run '" + argv[0] + "': " + std::strerror(exec_errno));
  }
  o.exit_status = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  if (WIFSIGNALED(status) && !o.timed_out) o.signal = WTERMSIG(status);
  o.stderr_tail = tail_of(stderr_file, 4096);
  keep_tail(stdout_file);
  keep_tail(stderr_file);
  return o;
}

}  // namespace aosuite::harness
