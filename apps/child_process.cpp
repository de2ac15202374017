#include "apps/child_process.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "core/errors.hpp"

namespace bemshape::apps {

ChildProcess::ChildProcess(const std::vector<std::string>& argv) {
  // Everything the child needs is prepared before fork(): between fork() and exec() only
  // async-signal-safe calls are allowed (this process may have other threads).
  std::vector<char*> arguments;
  arguments.reserve(argv.size() + 1);
  for (const std::string& a : argv)
    arguments.push_back(const_cast<char*>(a.c_str()));
  arguments.push_back(nullptr);
  int pipe_fds[2];
  // O_CLOEXEC: a sibling started later must not inherit this pipe's write end, or the pipe
  // would not reach its end when this child ends.
  if (::pipe2(pipe_fds, O_CLOEXEC) != 0)
    throw ResourceError(std::string("cannot create a pipe for a part's process: ") +
                        std::strerror(errno));
  const pid_t parent = ::getpid();
  start_ = Clock::now();
  pid_ = ::fork();
  if (pid_ < 0) {
    const int error = errno;
    ::close(pipe_fds[0]);
    ::close(pipe_fds[1]);
    throw ResourceError(std::string("cannot start a process for a part: ") + std::strerror(error));
  }
  if (pid_ == 0) {
    ::prctl(PR_SET_PDEATHSIG, SIGTERM);
    if (::getppid() != parent)  // the parent died before prctl took effect
      ::_exit(127);
    // A process group of its own: a Ctrl-C at the terminal reaches the parent alone, which
    // passes one signal on (a second SIGINT would end a bemshape run at once, uncleanly).
    ::setpgid(0, 0);
    const int null_fd = ::open("/dev/null", O_WRONLY);
    if (null_fd < 0 || ::dup2(null_fd, STDOUT_FILENO) < 0 || ::dup2(pipe_fds[1], STDERR_FILENO) < 0)
      ::_exit(127);
    ::execv(arguments[0], arguments.data());
    ::_exit(127);
  }
  ::close(pipe_fds[1]);
  error_fd_ = pipe_fds[0];
  ::fcntl(error_fd_, F_SETFL, ::fcntl(error_fd_, F_GETFL) | O_NONBLOCK);
}

ChildProcess::~ChildProcess() {
  if (!ended_ && pid_ > 0) {
    ::kill(pid_, SIGKILL);
    int status = 0;
    while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
    }
  }
  if (error_fd_ >= 0)
    ::close(error_fd_);
}

void ChildProcess::read_errors() {
  if (error_fd_ < 0)
    return;
  char buffer[4096];
  for (;;) {
    const ssize_t n = ::read(error_fd_, buffer, sizeof buffer);
    if (n > 0) {
      errors_.append(buffer, static_cast<std::size_t>(n));
      if (errors_.size() > kKeptErrorBytes)
        errors_.erase(0, errors_.size() - kKeptErrorBytes);
      continue;
    }
    if (n < 0 && errno == EINTR)
      continue;
    if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK))
      return;
    ::close(error_fd_);  // end of the pipe, or an error that will not clear
    error_fd_ = -1;
    return;
  }
}

bool ChildProcess::try_reap() {
  if (ended_)
    return true;
  int status = 0;
  rusage usage{};
  const pid_t r = ::wait4(pid_, &status, WNOHANG, &usage);
  if (r != pid_)
    return false;
  ended_ = true;
  end_ = Clock::now();
  peak_resident_bytes_ = static_cast<std::size_t>(usage.ru_maxrss) * 1024;  // ru_maxrss: KiB
  if (WIFEXITED(status)) {
    exit_code_ = WEXITSTATUS(status);
  } else if (WIFSIGNALED(status)) {
    end_signal_ = WTERMSIG(status);
  }
  // The child has ended: the rest of its output is in the pipe (still read without
  // blocking, in case a process it started holds the pipe open).
  read_errors();
  return true;
}

void ChildProcess::send(int signal) {
  if (!ended_ && pid_ > 0)
    ::kill(pid_, signal);
}

double ChildProcess::seconds() const {
  return std::chrono::duration<double>((ended_ ? end_ : Clock::now()) - start_).count();
}

}  // namespace bemshape::apps
