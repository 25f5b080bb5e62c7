// The host at the other end of the firmware's UART: it sends a script of
// command lines with the protocol's flow control (one line in flight; the next
// line leaves after the line's answer came back), paced at the real byte
// time of the baud rate, and records everything the firmware prints.
// The answers in both styles (docs/protocol.md): grbl's `ok` or `error:N`
// (the reason: the `[MSG:...]` line before it), Marlin's `ok` (`ok <report>`,
// M105's, too), which answers a refused line when an `Error:<reason>` line
// (and `Resend:`) came right before it: the answer is then the Error line.
//
// The first line the firmware prints is its banner (`Grbl 1.1h ...` or
// Marlin's `start`, then a line naming the firmware); nothing is sent before
// both of its lines are in. After the last script line the host sends WAIT
// (M400 to an image without the direct commands; not counted as a script
// line), so finished() becomes true only once all motion has ended. A line
// added once finished() is true is sent at once, and a new WAIT after it.
//
// Relay mode (avrmotion-sim --pty, pty_run.h): the lines come from a client
// program instead of a script. The host then sends nothing of its own; it
// hands the client's bytes to the UART at the same byte rate, records each
// line they complete as sent (its first byte's cycle), and pairs the
// firmware's answers with those lines in order, as the firmware answers them.
#pragma once
#include <cstdint>
#include <deque>
#include <string>
#include <vector>

struct avr_t;
struct avr_irq_t;

namespace sim {

struct Response {
  std::string line;     // the script line
  std::string answer;   // "ok" (or "ok <report>"), "error:N" (grbl) or "Error:<reason>" (Marlin)
  std::string reason;   // a refusal's text, in either style
  uint64_t sent_cycle;  // first byte handed to the UART
  uint64_t answer_cycle;
};

class SerialHost {
 public:
  SerialHost(avr_t* avr, uint32_t baud);

  void add_line(const std::string& line);
  // What is sent after the script to wait for the motion's end: WAIT, or
  // M400 on an image without the direct commands (Machine sets it).
  void set_wait_line(const std::string& line) { wait_line_ = line; }
  // Sends bytes at the line's byte rate without waiting for any answer, as a
  // sender that ignores the flow control would (for flood tests).
  // `together` bytes at once every `together` byte times: the same rate,
  // but the UART's receive buffer holds two at a time, as it does when the
  // MCU takes its bytes late (its receive interrupt held off by others).
  void send_raw(const std::string& bytes, uint8_t together = 1);
  bool finished() const { return finished_; }

  // Relay mode: call before the run, then relay() the client's bytes as they
  // come. relay_backlog() is what is queued and not handed to the UART yet.
  void relay_only() { relay_ = true; }
  void relay(const char* bytes, size_t n) { send_raw(std::string(bytes, n)); }
  size_t relay_backlog() const { return raw_.size() - raw_pos_; }
  // Shortest time between two send_raw()/relay() slots handed to the UART
  // (cycles; 0 until two were): never below the byte time.
  uint64_t min_byte_interval() const { return min_byte_interval_; }
  // The cycle the last send_raw()/relay() byte was handed to the UART (0
  // before one was).
  uint64_t last_byte_cycle() const { return last_byte_cycle_; }
  // The MCU was reset (Machine::reset()): bytes not handed over yet are
  // dropped, and so are the firmware's half-printed line and the client's
  // half-sent one; lines still waiting for an answer never get one. Returns
  // the number of bytes dropped.
  size_t on_reset();
  bool banner_seen() const { return !received_.empty() && received_.size() >= banner_lines_; }  // all of its lines
  size_t banner_lines() const { return banner_lines_; }

  const std::string& banner() const;
  const std::vector<std::string>& received() const { return received_; }
  // The cycle each received line ended (its '\n'), one per received() line.
  const std::vector<uint64_t>& received_cycles() const { return received_cycles_; }
  const std::vector<Response>& responses() const { return responses_; }
  size_t lines_sent() const { return lines_sent_; }
  size_t lines_pending() const { return script_.size(); }  // added, not sent yet
  size_t lines_ok() const;
  static bool is_ok(const std::string& answer);  // "ok" or "ok <report>"
  std::vector<std::string> errors() const;
  std::vector<std::string> reasons() const;  // each error's reason, in order
  // Lines that are neither the banner's two nor an answer's final line
  // (pos, info lines, a refusal's reason line).
  std::vector<std::string> messages() const;
  bool marlin() const { return marlin_; }
  // The firmware has changed its style since its banner (the setting
  // `$200` of an image with both, docs/protocol.md): its answers from now on
  // are read in the other style. A script line `$200=0` or `$200=1` that is
  // answered `ok` does this by itself; set_marlin() is for the other ways
  // (a power cycle, a block put into the EEPROM).
  void set_marlin(bool marlin) { marlin_ = marlin; }
  size_t banner_lines_ = 2;  // 1 for the lathe's one-line banner

 private:
  static void on_output(avr_irq_t* irq, uint32_t value, void* self);
  static uint64_t on_byte_slot(avr_t* avr, uint64_t when, void* self);
  static uint64_t on_raw_slot(avr_t* avr, uint64_t when, void* self);
  void on_line(const std::string& line);
  bool answer_of(std::string& answer, std::string& reason) const;
  void relay_byte(char c, uint64_t cycle);
  void send_next();

  avr_t* avr_;
  uint64_t byte_cycles_;
  avr_irq_t* input_irq_;
  std::deque<std::string> script_;
  std::string outgoing_;
  size_t outgoing_pos_ = 0;
  std::string raw_;
  size_t raw_pos_ = 0;
  uint8_t raw_together_ = 1;
  bool awaiting_answer_ = false;
  bool wait_sent_ = false;
  std::string wait_line_ = "WAIT";
  bool finished_ = false;
  size_t lines_sent_ = 0;
  bool relay_ = false;
  bool marlin_ = false;  // the banner was Marlin's
  std::string relay_line_;        // the client's line being handed over
  uint64_t relay_line_cycle_ = 0;  // its first byte's cycle
  size_t next_answer_ = 0;        // the first relayed line without an answer
  uint64_t last_byte_cycle_ = 0;
  uint64_t min_byte_interval_ = 0;
  std::string partial_;
  std::vector<std::string> received_;
  std::vector<uint64_t> received_cycles_;
  std::vector<Response> responses_;
};

}  // namespace sim
