// A value-change dump (VCD, IEEE 1364) of a run, for GTKWave:
//   gtkwave build/demo-uno.vcd
//
// Signals
//   pins     a board pin's level (1 bit). The default set is every pin the
//            image's board descriptor names: step, dir and enable of step/dir
//            axes, the Motor Shield's latch, clock, data and output enable,
//            a ULN2003's four inputs. Grouped by axis (scope X, Y, ..., or
//            "shield" for the shared 74HC595 lines).
//   isr      per interrupt vector, 1 from the vector's first instruction to
//            its RETI (the window the report's isr figures count), taken
//            from simavr's per-vector "running" IRQ.
//   pwm      per timer output-compare channel, the duty (OCR value) the
//            firmware set in a PWM mode (8 bits, 16 for timer 1), from
//            simavr's PWM IRQs; a PWM pin's waveform itself is not simulated.
//
// Choosing signals (VcdRecorder's `spec`, avrmotion-sim --vcd-signals):
// a comma-separated list of
//   board        every pin of the board descriptor (the default is board,isr,pwm)
//   X            the pins of axis X (any axis letter of the board)
//   PB3          one pin (port A..D, bit 0..7)
//   isr          every vector that runs at least once
//   isr11        vector 11, even if it never runs
//   pwm          every PWM channel whose duty is ever set
//   pwm2A        timer 2 channel A (0/A or 1/B), even if never set
// Signals named one by one, and board pins, are always in the file; the
// groups `isr` and `pwm` keep only the signals that changed, so the trace
// holds no flat lines for the dozens of vectors an image never uses.
//
// Time
//   $timescale is 1 ps; a change at cycle c is stamped round(c * 1e12 / f_cpu),
//   which is exact for clocks that divide 10^12 (16 MHz: 62500 ps per cycle,
//   8 MHz: 125000) and recovers c exactly by rounding back for any clock up
//   to 1 THz. The header's $comment states the cycle length. Changes are
//   written in cycle order, at most one value per signal per timestamp (the
//   last one in that cycle).
//
// Why not simavr's sim_vcd_file: see docs/simulator-report.md ("Traces").
//
// The recorder hooks its IRQs when constructed and must be finished (or
// destroyed) before the Machine is.
#pragma once
#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "machine.h"

struct avr_irq_t;

namespace sim {

class VcdRecorder {
 public:
  // Throws std::runtime_error for an unknown signal name or an unwritable path.
  VcdRecorder(Machine& m, const std::string& path, const std::string& spec = "board,isr,pwm");
  ~VcdRecorder();
  VcdRecorder(const VcdRecorder&) = delete;
  VcdRecorder& operator=(const VcdRecorder&) = delete;

  // Unhooks, stamps the end of the run and writes the file. Idempotent.
  void finish();
  // Declared signal names ("scope.name"), in declaration order (after finish()).
  const std::vector<std::string>& declared() const { return declared_; }
  uint64_t changes() const { return changes_; }

 private:
  struct Signal;
  static void on_irq(avr_irq_t* irq, uint32_t value, void* param);
  void add(const std::string& scope, const std::string& name, int bits, avr_irq_t* irq, bool always, uint32_t mask);
  void change(Signal& s, uint32_t value);
  void release(uint64_t through);  // stages the held changes up to that cycle
  void stage(Signal& s, uint32_t value, uint64_t cycle);
  void flush_cycle();
  void abandon();  // unhooks and removes the file (a bad signal list)

  Machine& m_;
  std::string path_;
  std::FILE* body_ = nullptr;  // value changes, in order (a temporary file)
  std::vector<std::unique_ptr<Signal>> signals_;
  struct Held {
    uint64_t cycle;
    Signal* signal;
    uint32_t value;
  };
  std::vector<Held> held_;        // changes of the last few cycles, not staged yet (vcd.cpp: kReorder)
  std::vector<Signal*> pending_;  // changed in the current cycle
  uint64_t cycle_ = 0;            // of the pending changes
  uint64_t start_stamp_ = 0;      // when the recording began, ps
  uint64_t last_stamp_ = 0;       // of the last timestamp written
  bool finished_ = false;
  uint64_t changes_ = 0;
  std::vector<std::string> declared_;
};

// The datasheet name of interrupt vector `vector` on `mcu` (simavr's part
// name), e.g. "TIMER1_COMPA" for 11 on the atmega328p; "" when unknown.
const char* vector_name(const std::string& mcu, int vector);

}  // namespace sim
