// A lathe spindle for the simulated board: its encoder's channels and index
// driven from an rpm profile, onto the pins the image's descriptor names
// (spindle_pins: A, B, index).
//
// Model (SpindleParams)
//   rpm profile: points (t_s, rpm), linear between them, the first rpm
//   before the first point and the last one after the last; a negative rpm
//   turns the spindle backward, so a ramp through 0 is a reversal. The
//   spindle's angle is integrated exactly (piecewise quadratic), and every
//   encoder transition is scheduled at the cycle its angle is crossed
//   (rounded to the nearest cycle), plus an optional uniform jitter of up to
//   +-jitter_us (never before the transition before it).
//   Encoder: `lines` lines per turn; single channel (the seed's slotted
//   disc): A low for the first half of each line, high for the second, so
//   the falling edge (the firmware's count) comes at every whole line;
//   quadrature: A and B a quarter line apart, A leading forward (AB = 00,
//   10, 11, 01), a transition every quarter line, each one a count x4.
//   Index: high for the phase that ends at turn 0 of each turn's first count
//   and low again at the next transition (quadrature: the one quarter line
//   [0, 1/4); single: the half line before and the half line after the
//   count at the whole turn), set before the channel's transition of the
//   same cycle, so the firmware reads it high at exactly that count.
// Log: every transition (cycle, phase after it, and whether it is a count
// for the firmware); counts(): forward minus backward counts (single
// channel: every falling edge, which has no direction, counts +1).
#pragma once
#include <cstdint>
#include <random>
#include <vector>

#include "machine.h"

namespace sim {

struct RpmPoint {
  double t_s;
  double rpm;
};

struct SpindleParams {
  uint16_t lines = 40;
  bool quadrature = false;
  std::vector<RpmPoint> profile = {{0, 600}};
  double jitter_us = 0;
  uint32_t seed = 20261202;
};

struct SpindleTransition {
  uint64_t cycle;
  int64_t phase;  // transitions of the encoder since the start, signed
  bool count;     // a count for the firmware (single: a falling edge)
  bool index;     // the index's level after it
};

class SpindleEncoder {
 public:
  // Throws when the image's descriptor names no spindle encoder, or
  // quadrature is asked for on a board without a B channel.
  SpindleEncoder(Machine& m, const SpindleParams& p);
  SpindleEncoder(const SpindleEncoder&) = delete;
  SpindleEncoder& operator=(const SpindleEncoder&) = delete;

  const std::vector<SpindleTransition>& log() const { return log_; }
  int64_t counts() const { return counts_; }
  uint32_t phases_per_turn() const { return phases_per_turn_; }
  double rpm_at(double t_s) const;
  // Transitions per second at an rpm (2 per line single, 4 quadrature).
  double transitions_per_s(double rpm) const { return rpm / 60 * phases_per_turn_; }

 private:
  static uint64_t on_transition(avr_t* avr, uint64_t when, void* param);
  // The time of the next phase boundary after now_s_ and the direction it
  // is crossed in; false if the spindle never gets to one (at rest for good).
  bool next_crossing(double& t_s, int& direction) const;
  // The cycle of the next transition (0: none), with its jitter.
  uint64_t schedule();
  void set_pins(uint64_t cycle, bool logged, bool count);
  void drive(uint8_t pin, bool level);
  double omega(double t_s) const;  // phases per second

  Machine& m_;
  SpindleParams p_;
  uint8_t pin_a_, pin_b_, pin_index_;
  uint32_t phases_per_turn_;
  double now_s_ = 0;
  int64_t phase_ = 0;     // the phase the pins show
  double angle_ = 0.5;    // in phases; starts mid-phase 0
  double next_s_ = 0;     // the scheduled transition's exact time ...
  int next_direction_ = 0;  // ... and direction
  uint64_t last_cycle_ = 0;
  int64_t counts_ = 0;
  std::vector<SpindleTransition> log_;
  std::mt19937 rng_;
};

}  // namespace sim
