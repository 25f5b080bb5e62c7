// The pseudo-terminal avrmotion-sim --pty offers as the board's serial port.
//
// Contract
//   - path() is the slave device (/dev/pts/N) a client opens; with a link
//     name, a symlink to it is made there (an existing symlink is replaced,
//     anything else refused) and removed again by the destructor.
//   - The line is raw (cfmakeraw: no echo, no line editing, no CR/LF
//     translation, 8 bits); the settings stay for every client that opens it
//     until a client changes them itself.
//   - client_present() says whether a client has the slave open now. The
//     port keeps no slave descriptor of its own, so the master sees a hangup
//     (POLLHUP) exactly while nobody has it open.
//   - opens() counts the opens of the slave since its last call (inotify
//     IN_OPEN on the device; opens with no close between them, two clients
//     at once, count as one): a client that closes and opens again between
//     two looks (printrun's parity workaround does) is still seen as a new
//     open, which the hangup alone would miss.
//   - read() and write() never block: they move what the kernel takes now.
//
// Why not simavr's uart_pty part (examples/parts/uart_pty.c): it talks to the
// pty from a second thread through FIFOs the simulation also touches, fills
// simavr's UART FIFO as far as XON/XOFF allows instead of pacing the bytes,
// cannot tell when a client opens or closes, prints on standard output
// (where the report goes) and always makes /tmp/simavr-uart0. This class
// keeps its approach (openpty, a raw master) and leaves the timing to the
// simulation loop (pty_run.h).
#pragma once
#include <cstddef>
#include <string>

namespace sim {

class PtyPort {
 public:
  explicit PtyPort(const std::string& link = "");
  ~PtyPort();
  PtyPort(const PtyPort&) = delete;
  PtyPort& operator=(const PtyPort&) = delete;

  const std::string& path() const { return path_; }
  bool client_present() const;
  unsigned opens();
  // What the client wrote, at most `max` bytes; 0 when nothing is there.
  size_t read(char* buf, size_t max);
  // As much of `data` as the pty takes now.
  size_t write(const char* data, size_t n);

 private:
  int master_ = -1;
  int inotify_ = -1;
  std::string path_;
  std::string link_;
};

}  // namespace sim
