#pragma once
// One program run in a child process, as `bemshape check-all` runs each part: started with
// its standard output discarded and its standard error captured through a pipe, watched
// without blocking (the caller polls many children at once), signalled, and reaped with its
// resource usage. The child is a process of its own, so its crash, its memory refusal or its
// kill by the kernel ends it alone; it gets SIGTERM should this process die first (Linux's
// PR_SET_PDEATHSIG), so no part runs on unobserved. It runs in a process group of its own,
// so a Ctrl-C at the terminal reaches the parent only, which decides what the children get.

#include <sys/types.h>

#include <chrono>
#include <cstddef>
#include <string>
#include <vector>

namespace bemshape::apps {

class ChildProcess {
 public:
  using Clock = std::chrono::steady_clock;

  /// Starts argv[0] (a path, not searched in PATH) with the arguments argv[1..]. Throws
  /// ResourceError if no process can be made (fork or pipe refused).
  explicit ChildProcess(const std::vector<std::string>& argv);
  /// Kills (SIGKILL) and reaps a child still running: a ChildProcess never leaves one behind.
  ~ChildProcess();
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  /// The read end of the standard-error pipe while it is open (for poll()), else -1.
  int error_fd() const { return error_fd_; }
  /// Reads what the child wrote to standard error without blocking; closes the pipe at its
  /// end. Keeps the last kKeptErrorBytes.
  void read_errors();
  /// Reaps the child if it has ended (never blocks); true once it has.
  bool try_reap();
  /// Sends `signal` to the child if it is still running.
  void send(int signal);

  bool ended() const { return ended_; }
  /// After the end: the exit code, or -1 if a signal ended the child.
  int exit_code() const { return exit_code_; }
  /// After the end: the signal that ended the child, 0 if it exited.
  int end_signal() const { return end_signal_; }
  /// After the end: the child's peak resident memory [bytes] (wait4's ru_maxrss).
  std::size_t peak_resident_bytes() const { return peak_resident_bytes_; }
  /// Wall seconds since the start (until the end, once reaped).
  double seconds() const;
  /// What the child wrote to standard error (its last kKeptErrorBytes).
  const std::string& errors() const { return errors_; }

  /// Standard error kept per child [bytes]: bemshape's error lines are short and come last;
  /// a child writing without end must not grow this process.
  static constexpr std::size_t kKeptErrorBytes = 16384;

 private:
  pid_t pid_ = -1;
  int error_fd_ = -1;
  bool ended_ = false;
  int exit_code_ = -1;
  int end_signal_ = 0;
  std::size_t peak_resident_bytes_ = 0;
  Clock::time_point start_ = Clock::now();
  Clock::time_point end_{};
  std::string errors_;
};

}  // namespace bemshape::apps
