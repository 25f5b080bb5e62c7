#include "pty_run.h"

#include <avr_uart.h>
#include <sim_avr.h>
#include <sim_irq.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <limits>
#include <string>
#include <thread>

#include "report.h"

namespace sim {

namespace {

using Clock = std::chrono::steady_clock;

// Client bytes queued in the simulator at most (5.6 ms of bytes at 115200
// baud): enough that the UART never waits for the next slice's read, small
// enough that a fast writer is held back by the pty, not by our memory.
constexpr size_t kBacklog = 64;
// A paced run this far behind its schedule starts the schedule again.
constexpr double kMaxLag = 0.1;

volatile std::sig_atomic_t g_signal = 0;
void on_signal(int sig) { g_signal = sig; }

// The firmware's UART output, collected between two writes to the pty.
struct Outbox {
  std::string bytes;
  static void on_byte(avr_irq_t*, uint32_t value, void* self) {
    static_cast<Outbox*>(self)->bytes += char(value);
  }
};

// Simulated time follows wall-clock time at `pace` (0: not paced) from an
// anchor; a new pace or a lag beyond kMaxLag sets a new anchor.
class Pacer {
 public:
  Pacer(const Machine& m, PtyStats& stats) : m_(m), stats_(stats) {}
  void restart(double pace) {
    pace_ = pace;
    wall_ = Clock::now();
    cycle_ = m_.cycles();
  }
  void keep_pace() {
    if (pace_ <= 0) return;
    const double sim_s = double(m_.cycles() - cycle_) / (double(m_.f_cpu()) * pace_);
    const Clock::time_point due = wall_ + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(sim_s));
    const double lag = std::chrono::duration<double>(Clock::now() - due).count();
    if (lag > stats_.max_lag_s) stats_.max_lag_s = lag;
    if (lag > kMaxLag) restart(pace_);
    else if (lag < 0) std::this_thread::sleep_until(due);
  }

 private:
  const Machine& m_;
  PtyStats& stats_;
  double pace_ = 1;
  Clock::time_point wall_;
  uint64_t cycle_ = 0;
};

// What run_pty() attaches, detached again however it ends (a SimulatorFault
// included).
struct Attached {
  Outbox out;
  avr_irq_t* tx;
  explicit Attached(Machine& m) : tx(avr_io_getirq(m.avr(), AVR_IOCTL_UART_GETIRQ('0'), UART_IRQ_OUTPUT)) {
    g_signal = 0;
    std::signal(SIGINT, on_signal);
    std::signal(SIGTERM, on_signal);
    avr_irq_register_notify(tx, &Outbox::on_byte, &out);
  }
  ~Attached() {
    avr_irq_unregister_notify(tx, &Outbox::on_byte, &out);
    std::signal(SIGINT, SIG_DFL);
    std::signal(SIGTERM, SIG_DFL);
  }
};

}  // namespace

RunEnd run_pty(Machine& m, PtyPort& port, const PtyOptions& options, PtyStats& stats) {
  m.serial().relay_only();
  Attached attached(m);
  Outbox& out = attached.out;

  // Held in reset: nothing runs until a client is there.
  unsigned first = 0;
  while (!(first = port.opens()) && !g_signal) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  const Clock::time_point first_open = Clock::now();
  const uint64_t start = m.cycles();
  const uint64_t end_cycle = options.budget ? start + options.budget : std::numeric_limits<uint64_t>::max();
  const uint64_t slice = std::max<uint32_t>(1, m.f_cpu() / 1000);  // 1 ms of simulated time
  const uint64_t linger = uint64_t(options.linger_s * m.f_cpu());
  Pacer pacer(m, stats);
  pacer.restart(options.speed);
  bool connected = port.client_present();
  stats.sessions = first;
  uint64_t closed_at = start, read_total = 0;
  Clock::time_point last_progress = first_open;
  RunEnd end = RunEnd::interrupted;
  char buf[kBacklog];
  while (!g_signal) {
    const unsigned opens = port.opens();
    const bool present = port.client_present();
    if (opens) {  // a new client, even one that closed again already: the auto-reset
      stats.bytes_dropped_at_reset += m.reset();
      stats.bytes_discarded += out.bytes.size();  // the last client's, never sent
      out.bytes.clear();
      stats.sessions += opens;
      pacer.restart(present ? options.speed : 1);
      if (!present) closed_at = m.cycles();
    } else if (!present && connected) {  // gone: what it had not read yet is dropped below
      closed_at = m.cycles();
      pacer.restart(1);
    }
    connected = present;
    if (!connected && m.cycles() - closed_at >= linger) {
      end = RunEnd::done;
      break;
    }
    // Read whether or not the client is still there: what it wrote before
    // closing still goes down the line, as a serial port drains on close.
    for (size_t n; m.serial().relay_backlog() < kBacklog &&
                   (n = port.read(buf, kBacklog - m.serial().relay_backlog())) > 0;) {
      m.serial().relay(buf, n);
      read_total += n;
    }
    if (connected) {
      const size_t w = port.write(out.bytes.data(), out.bytes.size());
      stats.bytes_from_avr += w;
      out.bytes.erase(0, w);
    } else {
      stats.bytes_discarded += out.bytes.size();
      out.bytes.clear();
    }
    if (m.cycles() >= end_cycle) {
      end = RunEnd::budget_spent;
      break;
    }
    if (m.run([] { return false; }, std::min(slice, end_cycle - m.cycles())) == RunEnd::cpu_stopped) {
      end = RunEnd::cpu_stopped;
      break;
    }
    pacer.keep_pace();
    if (options.progress && Clock::now() - last_progress >= std::chrono::seconds(1)) {
      *options.progress << progress_line(m) << std::endl;
      last_progress = Clock::now();
    }
  }
  if (connected) stats.bytes_from_avr += port.write(out.bytes.data(), out.bytes.size());
  if (options.progress) *options.progress << progress_line(m) << std::endl;
  stats.bytes_to_avr = read_total - stats.bytes_dropped_at_reset - m.serial().relay_backlog();
  stats.min_byte_interval = m.serial().min_byte_interval();
  stats.wall_seconds = std::chrono::duration<double>(Clock::now() - first_open).count();
  stats.simulated_seconds = double(m.cycles() - start) / m.f_cpu();
  return end;
}

}  // namespace sim
