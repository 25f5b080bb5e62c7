// Decoders that turn a board's output pins back into motor positions.
//
//   StepDirDecoder   counts rising step edges, signed by the direction line.
//   CoilDecoder      follows a coil pattern (from the shield's latch or from
//                    four unipolar driver inputs) around the 8-state half-step
//                    cycle of core/motor/phase_sequencer.h.
//   Latch595Model    a 74HC595: shifts on clock rising edges, copies to its
//                    outputs on latch rising edges, tri-states them while
//                    output-enable is high; it feeds the shield's decoders.
//
// A coil-driven motor's position is counted in half steps from the first
// pattern that energises it (a motor at rest with its coils off has no defined
// state, so the first energised state is taken as where the rotor is). A jump
// of four half steps cannot be told apart from its reverse: it is counted as
// a decode error, not as motion.
#pragma once
#include <cstdint>
#include <vector>

namespace sim {

struct AxisTrace {
  char name = '?';
  int kind = 0;                        // am::AxisKind
  double steps_per_mm = 0;             // full steps
  int64_t position = 0;                // steps (step/dir) or half steps (coils)
  int units_per_step = 1;              // 2 for coil-driven axes (half steps)
  std::vector<uint64_t> step_cycles;   // cycle of every step event
  std::vector<int8_t> step_deltas;     // its signed size, in position units
  uint64_t decode_errors = 0;

  double steps() const { return double(position) / units_per_step; }
  uint64_t min_interval() const;       // 0 with fewer than two steps
  void add_step(uint64_t cycle, int delta) {
    position += delta;
    step_cycles.push_back(cycle);
    step_deltas.push_back(int8_t(delta));
  }
};

// The axis's position at a cycle: the sum of its steps at or before it.
int64_t position_at(const AxisTrace& axis, uint64_t cycle);
// The first and the last step of any of `axes` within [from, to] (cycles);
// false when none stepped there.
bool motion_span(const std::vector<AxisTrace>& axes, uint64_t from, uint64_t to, uint64_t& first, uint64_t& last);

class StepDirDecoder {
 public:
  explicit StepDirDecoder(AxisTrace* trace) : trace_(trace) {}
  void on_step(bool level, uint64_t cycle);
  void on_dir(bool level) { forward_ = level; }

 private:
  AxisTrace* trace_;
  bool step_level_ = false;
  bool forward_ = false;
};

class CoilDecoder {
 public:
  explicit CoilDecoder(AxisTrace* trace) : trace_(trace) {}
  void on_pattern(uint8_t pattern, uint64_t cycle);

 private:
  AxisTrace* trace_;
  int index_ = -1;  // last energised half-step state, -1 before the first
};

struct LatchEvent {
  uint64_t cycle;
  uint8_t value;
};

class Latch595Model {
 public:
  void on_clock(bool level, bool data);
  // Returns true when the outputs changed.
  bool on_latch(bool level, uint64_t cycle);
  bool on_enable(bool level);  // active low; returns true when outputs changed
  uint8_t outputs() const { return output_enabled_ ? storage_ : 0; }
  const std::vector<LatchEvent>& history() const { return history_; }

 private:
  uint8_t shift_ = 0;
  uint8_t storage_ = 0;
  bool clock_ = false;
  bool latch_ = false;
  bool output_enabled_ = false;  // EN is pulled high (disabled) at power-up
  std::vector<LatchEvent> history_;
};

}  // namespace sim
