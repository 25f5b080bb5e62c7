#include "pty_port.h"

#include <fcntl.h>
#include <poll.h>
#include <pty.h>
#include <sys/inotify.h>
#include <sys/stat.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace sim {

namespace {

std::runtime_error sys_error(const std::string& what) {
  return std::runtime_error(what + ": " + std::strerror(errno));
}

}  // namespace

PtyPort::PtyPort(const std::string& link) {
  int slave = -1;
  char name[256];
  if (openpty(&master_, &slave, name, nullptr, nullptr) != 0) throw sys_error("cannot open a pseudo-terminal");
  path_ = name;
  const auto fail = [this](const std::runtime_error& e) {
    if (inotify_ >= 0) close(inotify_);
    close(master_);
    throw e;
  };
  termios tio;
  const bool raw = tcgetattr(slave, &tio) == 0 && (cfmakeraw(&tio), tcsetattr(slave, TCSANOW, &tio) == 0);
  close(slave);  // from now on the master hangs up exactly while no client has it open
  inotify_ = inotify_init1(IN_NONBLOCK | IN_CLOEXEC);
  if (!raw || fcntl(master_, F_SETFL, fcntl(master_, F_GETFL) | O_NONBLOCK) != 0 || inotify_ < 0 ||
      inotify_add_watch(inotify_, path_.c_str(), IN_OPEN | IN_CLOSE) < 0)
    fail(sys_error("cannot set up " + path_));
  if (link.empty()) return;
  struct stat st;
  if (lstat(link.c_str(), &st) == 0 && !S_ISLNK(st.st_mode))
    fail(std::runtime_error(link + " exists and is not a symlink: not replacing it"));
  unlink(link.c_str());
  if (symlink(path_.c_str(), link.c_str()) != 0) fail(sys_error("cannot make the link " + link));
  link_ = link;
}

PtyPort::~PtyPort() {
  if (!link_.empty()) {
    char target[256];
    const ssize_t n = readlink(link_.c_str(), target, sizeof target - 1);
    if (n >= 0 && path_ == std::string(target, size_t(n))) unlink(link_.c_str());  // still ours
  }
  close(inotify_);
  close(master_);
}

bool PtyPort::client_present() const {
  pollfd p{master_, POLLIN, 0};
  return poll(&p, 1, 0) >= 0 && !(p.revents & POLLHUP);
}

// The closes are watched too, only so that open, close, open are three events:
// inotify merges an event with an identical one still unread before it.
unsigned PtyPort::opens() {
  unsigned n = 0;
  alignas(inotify_event) char events[1024];
  for (ssize_t got; (got = ::read(inotify_, events, sizeof events)) > 0;) {
    for (ssize_t at = 0; at < got;) {
      const auto* e = reinterpret_cast<const inotify_event*>(events + at);
      n += (e->mask & IN_OPEN) != 0;
      at += ssize_t(sizeof(inotify_event) + e->len);
    }
  }
  return n;
}

size_t PtyPort::read(char* buf, size_t max) {
  const ssize_t n = ::read(master_, buf, max);
  return n > 0 ? size_t(n) : 0;  // EAGAIN: nothing yet; EIO: no client
}

size_t PtyPort::write(const char* data, size_t n) {
  const ssize_t w = ::write(master_, data, n);
  return w > 0 ? size_t(w) : 0;  // EAGAIN: the client does not read
}

}  // namespace sim
