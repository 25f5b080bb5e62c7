// For the pty tests: avrmotion-sim started as a child process, and a client
// that talks to its pseudo-terminal as a serial-port program does.
//
// Nothing here sleeps to synchronise: every wait is a poll() on data (the
// port, the child's standard error) that returns as soon as the data is
// there; its timeout (kGuardMs) only keeps a broken run from hanging the
// suite, and a wait that hits it fails the test.
#pragma once
#include <gtest/gtest.h>

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <string>
#include <vector>

namespace ptytest {

constexpr int kGuardMs = 30000;

// Waits for `fd` to be readable (or hung up); false after kGuardMs.
inline bool wait_readable(int fd) {
  pollfd p{fd, POLLIN, 0};
  return poll(&p, 1, kGuardMs) == 1;
}

// avrmotion-sim with `args`, standard error on a pipe.
class SimProcess {
 public:
  explicit SimProcess(const std::vector<std::string>& args) {
    int err[2];
    if (pipe(err) != 0) return;
    pid_ = fork();
    if (pid_ == 0) {
      dup2(err[1], 2);
      close(err[0]);
      close(err[1]);
      std::vector<char*> argv{const_cast<char*>(AVRMOTION_SIM_EXE)};
      for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
      argv.push_back(nullptr);
      execv(AVRMOTION_SIM_EXE, argv.data());
      _exit(127);
    }
    close(err[1]);
    err_ = err[0];
  }
  ~SimProcess() {
    if (pid_ > 0 && status_ < 0) {
      kill(pid_, SIGKILL);
      waitpid(pid_, nullptr, 0);
    }
    if (err_ >= 0) close(err_);
  }
  // The next line of its standard error ("" at its end or after the guard).
  std::string stderr_line() {
    for (;;) {
      const size_t nl = err_text_.find('\n', err_pos_);
      if (nl != std::string::npos) {
        const std::string line = err_text_.substr(err_pos_, nl - err_pos_);
        err_pos_ = nl + 1;
        return line;
      }
      if (!read_stderr()) return "";
    }
  }
  // The pseudo-terminal's path, from "avrmotion-sim: pty /dev/pts/N ...".
  std::string pty_path() {
    const std::string prefix = "avrmotion-sim: pty ";
    for (std::string l = stderr_line(); !l.empty(); l = stderr_line()) {
      if (l.rfind(prefix, 0) == 0) return l.substr(prefix.size(), l.find(' ', prefix.size()) - prefix.size());
    }
    return "";
  }
  // Waits for the process to end (its standard error closes); its exit
  // status, or -1 if it did not end within the guard.
  int wait_exit() {
    while (read_stderr()) {
    }
    int st = 0;
    if (!eof_ || waitpid(pid_, &st, 0) != pid_) return -1;
    status_ = WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
    return status_;
  }
  void signal(int sig) { kill(pid_, sig); }
  const std::string& stderr_text() const { return err_text_; }

 private:
  bool read_stderr() {
    if (!wait_readable(err_)) return false;
    char buf[4096];
    const ssize_t n = read(err_, buf, sizeof buf);
    eof_ = n <= 0;
    if (eof_) return false;
    err_text_.append(buf, size_t(n));
    return true;
  }
  pid_t pid_ = -1;
  int err_ = -1;
  int status_ = -1;
  bool eof_ = false;
  std::string err_text_;
  size_t err_pos_ = 0;
};

// One client session on the port: open, lines in and out, close.
class Client {
 public:
  explicit Client(const std::string& path) : fd_(open(path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK)) {}
  ~Client() { close_port(); }
  bool is_open() const { return fd_ >= 0; }
  void close_port() {
    if (fd_ >= 0) close(fd_);
    fd_ = -1;
  }
  void send(const std::string& bytes) {
    for (size_t at = 0; at < bytes.size();) {
      pollfd p{fd_, POLLOUT, 0};
      if (poll(&p, 1, kGuardMs) != 1) return;
      const ssize_t n = write(fd_, bytes.data() + at, bytes.size() - at);
      if (n > 0) at += size_t(n);
    }
  }
  // The next line (CR/LF stripped); "<timeout>" after the guard, "<closed>"
  // when the simulator has gone.
  std::string line() {
    for (;;) {
      const size_t nl = in_.find('\n');
      if (nl != std::string::npos) {
        std::string l = in_.substr(0, nl);
        in_.erase(0, nl + 1);
        if (!l.empty() && l.back() == '\r') l.pop_back();
        return l;
      }
      if (!wait_readable(fd_)) return "<timeout>";
      char buf[512];
      const ssize_t n = read(fd_, buf, sizeof buf);
      if (n > 0) in_.append(buf, size_t(n));
      else if (n == 0 || errno != EAGAIN) return "<closed>";
    }
  }
  // Sends `l` and reads up to its answer ("ok" / "error: ..."): one line in
  // flight. `info` gets the lines before the answer.
  std::string command(const std::string& l, std::vector<std::string>* info = nullptr) {
    send(l + "\n");
    for (;;) {
      const std::string a = line();
      if (a == "ok" || a.rfind("error", 0) == 0 || a[0] == '<') return a;
      if (info) info->push_back(a);
    }
  }

 private:
  int fd_;
  std::string in_;
};

}  // namespace ptytest
