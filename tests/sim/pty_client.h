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

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <regex>
#include <string>
#include <vector>

namespace ptytest {

constexpr int kGuardMs = 30000;

// A number of avrmotion-sim's JSON report: `key` inside the object `object`
// ("" = anywhere first), e.g. ("X", "steps") for axes.X.steps.
inline double report_number(const std::string& json, const std::string& object, const std::string& key) {
  const std::regex re((object.empty() ? "" : "\"" + object + "\": \\{[^}]*?") + "\"" + key + "\": ([-0-9.e+]+)");
  std::smatch m;
  return std::regex_search(json, m, re) ? std::atof(m[1].str().c_str()) : -1e300;
}

inline std::string report_string(const std::string& json, const std::string& key) {
  const std::regex re("\"" + key + "\": (\"[^\"]*\"|\\[[^\\]]*\\])");
  std::smatch m;
  return std::regex_search(json, m, re) ? m[1].str() : "<missing>";
}

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
  // Sends `l` and reads up to its answer: one line in flight. `info` gets
  // the lines before the answer. The answer is grbl's `ok` / `error:N`, or
  // Marlin's `ok`, which answers a refusal when an `Error:` line (and a
  // `Resend:`) came just before it: the answer is then that Error line.
  std::string command(const std::string& l, std::vector<std::string>* info = nullptr) {
    send(l + "\n");
    return answer(info);
  }
  std::string answer(std::vector<std::string>* info = nullptr) {
    std::string refusal;
    for (;;) {
      const std::string a = line();
      if (a == "ok" || a.rfind("ok ", 0) == 0) return refusal.empty() ? a : refusal;
      if (a.rfind("error:", 0) == 0 || a[0] == '<') return a;
      if (a.rfind("Resend:", 0) != 0) refusal = a.rfind("Error:", 0) == 0 ? a : "";
      if (info) info->push_back(a);
    }
  }
  // The two banner lines: grbl's `Grbl 1.1h ['$' for help]` or Marlin's
  // `start`, then the firmware's name, board and clock (`[MSG:...]`,
  // `echo:...`).
  std::string banner() {
    const std::string first = line();
    return first + "\n" + line();
  }

 private:
  int fd_;
  std::string in_;
};

// grbl's streaming by character counting (as its stream.py does): as many
// lines in flight as their bytes, line ends included, fit `limit`; every
// answer (`ok`, `error:N`) frees the oldest line's bytes. Info lines
// (`[MSG:...]`) are no answers.
struct Streamed {
  size_t answered = 0, errors = 0, most_lines = 0, most_bytes = 0;
  std::string failure;  // a timeout or the port closing
};
inline Streamed stream_counting(Client& c, const std::vector<std::string>& lines, size_t limit) {
  Streamed r;
  std::vector<size_t> in_flight;  // bytes of each unanswered line, oldest first
  size_t bytes = 0, next = 0;
  while (r.answered < lines.size()) {
    while (next < lines.size() && bytes + lines[next].size() + 1 <= limit) {
      c.send(lines[next] + "\n");
      in_flight.push_back(lines[next].size() + 1);
      bytes += in_flight.back();
      ++next;
    }
    r.most_lines = std::max(r.most_lines, in_flight.size());
    r.most_bytes = std::max(r.most_bytes, bytes);
    const std::string a = c.line();
    if (a[0] == '<') {
      r.failure = a;
      return r;
    }
    const bool error = a.rfind("error:", 0) == 0;
    if (a != "ok" && !error) continue;
    r.errors += error;
    bytes -= in_flight.front();
    in_flight.erase(in_flight.begin());
    ++r.answered;
  }
  return r;
}

}  // namespace ptytest
