// Endstop switches for the simulated board: one per axis whose descriptor
// names an endstop pin, closed while the axis is at or beyond the switch's
// position, with contact bounce.
//
// Model
//   position   in the axis's steps as the harness decodes them from the
//              step/dir pins (AxisTrace::position, 0 at reset); a switch at
//              the axis's minimum end (the descriptor's kEndstopAtMax clear)
//              is closed while position <= at, one at the maximum end while
//              position >= at. Default: every switch at 0 (a printer's
//              world: the axes start on their min switches).
//   bounce     when the contact changes (closing or opening), the pin
//              toggles `bounce_toggles` more times at pseudo-random moments
//              (a fixed seed) within `bounce_us` microseconds and then rests
//              at the new level; a change during a burst starts a new one.
//              0 us: a clean edge.
//   level      closed is the descriptor's polarity (kEndstopClosedHigh:
//              high, else low: a switch to ground against the pull-up);
//              `normally_closed` switches read the other way (a contact
//              that opens when the axis reaches it: the pin low while the
//              axis is away, high at the switch; grbl's $5 for them). The
//              pin is held through Machine::hold_input().
// Log: every level the pin takes, with its cycle (edges()), and the cycle
// of each contact change (contact_changes()), per axis.
#pragma once
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "machine.h"

namespace sim {

struct EndstopParams {
  double bounce_us = 0;
  unsigned bounce_toggles = 6;  // even: the burst ends on the new level
  bool normally_closed = false;
};

class Endstops {
 public:
  // Every endstop of the image's descriptor, each at 0 until set_position().
  explicit Endstops(Machine& m, const EndstopParams& p = EndstopParams());
  Endstops(const Endstops&) = delete;
  Endstops& operator=(const Endstops&) = delete;

  // The switch of axis `name` (throws if it has none) at `steps`: takes
  // effect at once (the contact follows the axis's position from then on).
  void set_position(char name, int64_t steps);
  bool has(char name) const;
  bool closed(char name) const;  // the contact (not the bouncing pin)
  const std::vector<PinEdge>& edges(char name) const;
  const std::vector<uint64_t>& contact_changes(char name) const;

 private:
  struct Switch {
    Endstops* owner;
    char name;
    char port;
    uint8_t bit;
    bool at_max, closed_high;
    int64_t at = 0;
    bool contact = false;   // closed
    const AxisTrace* axis;
    std::vector<uint64_t> pending;  // toggle cycles of the burst, latest last
    std::vector<PinEdge> edges;
    std::vector<uint64_t> changes;
    bool level = false;             // the pin now
  };
  Switch& find(char name);
  const Switch& find(char name) const;
  void follow(Switch& s, uint64_t cycle);
  void drive(Switch& s, bool level, uint64_t cycle);
  static uint64_t on_toggle(avr_t* avr, uint64_t when, void* param);

  Machine& m_;
  EndstopParams p_;
  std::vector<Switch> switches_;
  std::mt19937 rng_{20261202};
};

// "X=1200" -> axis and position (steps); false if malformed.
bool parse_endstop_position(const std::string& text, char& axis, int64_t& steps);

}  // namespace sim
