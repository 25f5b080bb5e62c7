// The operator's 4x4 keypad on the simulated board: keys pressed and
// released at scripted times, each contact bouncing, read through the
// firmware's own column scan.
//
// Wiring (firmware/devices/keypad.h, the seed's): column c (0 = "1 4 7 *")
// on PB(7 - c), row r (0 = "1 2 3 A") on PB(3 - r); layout
// 1 2 3 A / 4 5 6 B / 7 8 9 C / * 0 # D.
//
// Model: a row pin reads low while a closed key joins it to a column the
// firmware drives low (DDR 1, PORT 0), else it is left to the firmware's
// pull-up. It is re-evaluated on every write to port B's PORT or DDR
// (simavr's whole-port IRQ, raised within the writing instruction, so the
// firmware's next read of PINB sees it) and at every contact change.
// press(key, at_s, hold_s) closes the key at at_s and opens it hold_s later;
// each of the two transitions bounces: `bounces` extra open/close flips at
// random times within bounce_s after it (a fixed seed: every run is the
// same), ending in the new state. press() may be called before or during a
// run; times are seconds of simulated time from reset.
// type(keys, at_s, every_s) presses each character of `keys` in turn,
// every_s apart, each held for half of that.
// The model must not be destroyed before the machine stops running (the
// machine's reset hook refers to it); its destructor drops its IRQ hook and
// its pending contact event.
#pragma once
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "machine.h"

namespace sim {

struct KeypadTiming {
  double hold_s = 0.08;
  double bounce_s = 0.004;
  int bounces = 6;
};

class KeypadModel {
 public:
  explicit KeypadModel(Machine& m, const KeypadTiming& t = KeypadTiming());
  ~KeypadModel();
  KeypadModel(const KeypadModel&) = delete;
  KeypadModel& operator=(const KeypadModel&) = delete;

  void press(char key, double at_s, double hold_s = -1);
  // Returns the time after the last key.
  double type(const std::string& keys, double at_s, double every_s = 0.25);
  // Contact flips scheduled so far (bounces included), and those applied.
  size_t scheduled() const { return events_.size(); }
  size_t applied() const { return next_; }

 private:
  struct Event {
    uint64_t cycle;
    uint8_t key;  // r * 4 + c
    bool closed;
  };
  static uint64_t on_timer(struct avr_t* avr, uint64_t when, void* param);
  static void on_port(struct avr_irq_t* irq, uint32_t value, void* param);
  void transition(uint8_t key, uint64_t at, bool closed);
  void arm();
  void update_rows();

  Machine& m_;
  KeypadTiming timing_;
  std::vector<Event> events_;  // sorted by cycle from next_ on
  size_t next_ = 0;
  bool closed_[16] = {};
  std::mt19937 rng_{20261202};
};

}  // namespace sim
