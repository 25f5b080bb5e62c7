// A simulated board: one firmware ELF running on libsimavr, with its outputs
// decoded, its UART attached to a SerialHost and the measurements later tests
// and benchmarks rely on.
//
// Measurements
//   - axes():          position and the cycle of every step, per axis;
//   - latch():         every byte the shield's 74HC595 latched, with its cycle;
//   - isr_stats():     per interrupt vector: entries, total and longest cycles,
//                      counted from the vector's entry to its RETI (the
//                      interrupt response before the vector and RETI's own
//                      cycles are not included; see docs/simulator.md);
//   - stack_bytes():   stack high-water mark, found by painting the free RAM
//                      between the end of .bss and RAMEND before reset and
//                      looking for the deepest overwritten byte;
//   - watch_pin():     raw edges of any pin, with cycle stamps.
//   - watch_pwm():     duty (OCR value) of a timer's PWM channel, logged when
//                      the firmware writes an OCR in a PWM mode and the value
//                      changed (simavr's TIMER_IRQ_OUT_PWM0/1), cycle-stamped.
// A board whose descriptor names a heater starts with its thermistor's ADC
// input at 25 C (sim/thermal_plant.h drives it from a hot end instead), one
// with endstops with every switch open (sim/endstops.h closes them).
// run() always ends: when the stop condition holds, when the cycle budget is
// spent (a hung image fails a test instead of hanging CI) or when the core
// stops or crashes. A run in which simavr reported an error does not end
// normally at all: run() throws SimulatorFault (below).
#pragma once
#include <cstdarg>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "../core/board/descriptor.h"
#include "axis_decoder.h"
#include "board_info.h"
#include "serial_host.h"

struct avr_t;
struct avr_irq_t;

namespace sim {

struct IsrStats {
  uint64_t count = 0;
  uint64_t total_cycles = 0;
  uint64_t max_cycles = 0;
};

struct PinEdge {
  uint64_t cycle;
  bool level;
};

struct PwmSample {
  uint64_t cycle;
  uint16_t duty;
};

// interrupted: a pty run ended by SIGINT or SIGTERM (pty_run.h).
enum class RunEnd { done, budget_spent, cpu_stopped, interrupted };

// simavr reports what it could not simulate only as an error-level log line,
// and runs on: a dropped event ("CYCLE: avr_cycle_timer_insert: ran out of
// timers (64)!" - a timer or UART stops for the rest of the run), an invalid
// memory access, a bad opcode. Such a run proves nothing, so run() throws
// this (avrmotion-sim and avrmotion-bench exit with status 2 and the message,
// a test fails), on the first error and on every later run of the machine.
class SimulatorFault : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Machine {
 public:
  explicit Machine(const std::string& elf_path);
  ~Machine();
  Machine(const Machine&) = delete;
  Machine& operator=(const Machine&) = delete;

  const am::BoardDescriptor& board() const { return board_; }
  const std::string& elf_path() const { return elf_path_; }
  avr_t* avr() { return avr_; }
  uint64_t cycles() const;
  uint32_t f_cpu() const { return board_.f_cpu; }

  SerialHost& serial() { return *serial_; }
  const std::vector<AxisTrace>& axes() const { return axes_; }
  const AxisTrace* axis(char name) const;
  const Latch595Model* latch() const { return latch_.get(); }

  // Resets the MCU as its RESET pin would (the auto-reset of a board whose
  // host opens the port, pty_run.h): registers, peripherals and pending
  // events as at power-on, RAM as it was (the startup code clears .bss).
  // Simulated time, the decoded positions and every measurement go on: the
  // motors do not move on a reset. Returns the host bytes dropped
  // (SerialHost::on_reset()). A reset clears simavr's cycle timers: a model
  // that runs on one asks to be told (after_reset()) and registers it again.
  size_t reset();
  void after_reset(std::function<void()> again) { after_reset_.push_back(std::move(again)); }

  // Runs until `stop` returns true (checked between instructions), until
  // `budget` more cycles have run, or until the CPU stops.
  RunEnd run(const std::function<bool()>& stop, uint64_t budget);
  // Runs the serial script to its end (see SerialHost).
  RunEnd run_script(uint64_t budget) { return run([this] { return serial_->finished(); }, budget); }

  const std::map<int, IsrStats>& isr_stats() const { return isr_; }
  unsigned stack_bytes() const;
  // The painted RAM: from the end of .bss to RAMEND. A stack_bytes() this
  // large means the stack reached the static data.
  unsigned free_ram() const;
  // The firmware's count of path starvations (firmware/engine/path.h): the
  // engine ran dry under a block that had more to queue or ended at speed.
  // -1 for an image without a path.
  int starvations() const;

  // Calls `on_change` at every change of a pin, after the harness's own
  // decoders have seen it (an axis's position is already updated).
  void listen_pin(char port, uint8_t bit, std::function<void(bool, uint64_t)> on_change) {
    hook_pin(am::pin_code(port, bit), std::move(on_change));
  }
  // Starts recording every change of a pin (port 'A'..'D', bit 0..7).
  const std::vector<PinEdge>& watch_pin(char port, uint8_t bit);
  // Drives an input pin from outside (a switch, an encoder, a step source).
  void set_input(char port, uint8_t bit, bool level);
  // Holds an input pin at `level` as a switch wired to it does, whatever
  // the firmware does with its pull-up, and through resets (simavr clears
  // the PIN register on a reset but keeps the pin's last level, so a plain
  // set_input() would read 0 afterwards). An endstop's pin is held open
  // from construction (sim/endstops.h drives it from a position).
  void hold_input(char port, uint8_t bit, bool level);
  // The EEPROM: its first `bytes` bytes (all of it with 0; erased cells read
  // 0xFF), and `bytes` written from address 0, as a programmer would (they
  // live through every reset). Empty when simavr has no EEPROM to give.
  std::vector<uint8_t> eeprom(uint32_t bytes = 0);
  void set_eeprom(std::vector<uint8_t> bytes);
  // Puts `mv` millivolts on ADC input `channel` (0..7), as a sensor would.
  // The first call also sets AVCC, VCC and AREF to 5 V if nothing set them
  // (simavr otherwise converts against 3.3 V). simavr samples the input when
  // the firmware reads ADCL/ADCH, not at the start of the conversion.
  void set_adc_millivolts(uint8_t channel, uint32_t mv);

  // Starts logging the duty of timer ('0'..'5') channel 0 (A) or 1 (B); call
  // before running. Only changes are logged (simavr filters repeats), so the
  // duty at a cycle is the last sample at or before it (pwm_duty_at()).
  const std::vector<PwmSample>& watch_pwm(char timer, uint8_t channel);
  static uint16_t pwm_duty_at(const std::vector<PwmSample>& log, uint64_t cycle);


  // simavr's error-level messages about this machine so far (each one is
  // also printed on standard error), and the first of them.
  uint64_t simavr_errors() const { return simavr_errors_; }
  const std::string& first_simavr_error() const { return first_simavr_error_; }

 private:
  // The process-wide simavr logger: counts errors per machine.
  static void on_simavr_log(avr_t* avr, int level, const char* format, va_list args);
  void throw_simavr_fault() const;
  struct PinHook;
  struct PortHook;
  void hook_pin(uint8_t code, std::function<void(bool, uint64_t)> on_change);
  bool pin_hooks_level(uint8_t code) const;
  // Whole-port writes (value = the port's pins after the write).
  void hook_port(char port, std::function<void(uint8_t, uint64_t)> on_write);
  void attach_axes();
  void attach_isr_profiler();
  void paint_stack();
  static void on_pin_irq(avr_irq_t* irq, uint32_t value, void* param);
  static void on_port_irq(avr_irq_t* irq, uint32_t value, void* param);
  static void on_isr_irq(avr_irq_t* irq, uint32_t value, void* param);

  am::BoardDescriptor board_;
  ElfSymbol starvations_;  // firmware/engine/path.cpp's counter
  std::string elf_path_;
  avr_t* avr_ = nullptr;
  std::unique_ptr<SerialHost> serial_;
  std::vector<AxisTrace> axes_;
  std::vector<std::function<void()>> after_reset_;
  std::vector<std::unique_ptr<PinHook>> pin_hooks_;
  std::vector<std::unique_ptr<PortHook>> port_hooks_;
  std::vector<StepDirDecoder> step_dir_;
  std::vector<CoilDecoder> coils_;
  std::unique_ptr<Latch595Model> latch_;
  std::map<int, IsrStats> isr_;
  std::map<int, uint64_t> isr_entry_;
  std::vector<std::unique_ptr<std::pair<Machine*, int>>> isr_hooks_;
  std::map<int, std::vector<PinEdge>> watched_;
  std::map<char, std::pair<uint8_t, uint8_t>> held_;  // port: held pins' mask, levels
  void apply_held(char port);
  void reapply_held();
  struct PwmHook;
  static void on_pwm_irq(avr_irq_t* irq, uint32_t value, void* param);
  std::map<int, std::unique_ptr<PwmHook>> pwm_hooks_;
  uint16_t paint_start_ = 0;
  uint64_t simavr_errors_ = 0;
  std::string first_simavr_error_;
};

}  // namespace sim
