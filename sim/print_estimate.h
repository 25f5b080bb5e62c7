// A slicer's print-time estimate: every straight move a trapezoid (entry,
// cruise, exit speed, one acceleration), the junction speeds between moves
// from grbl's junction deviation, planned over the whole file at once (a
// slicer looks ahead over everything; the firmware over its ring), with the
// machine limits of the printer it writes for (MachineLimits).
//
// Contract
//   move(delta_mm, feed, rapid): one block, the program coordinates' change
//   per axis (the limits' order), feed in mm/min (a rapid: the axes' top
//   rates). A move of no axis is ignored. rest() says the machine comes to
//   rest there (G28, M109, M400: the firmware drains its queue): the move
//   before ends at 0 and the next starts at 0. seconds() is the time of
//   every move so far, in seconds; moves() counts them.
//   The same rules as the firmware's planner (docs/planner.md), computed
//   in double: a block's length is the norm over the path axes (over the
//   others when no path axis moves: an extruder-only retract); its cruise
//   the feed held to each moving axis's top rate (its share of the length)
//   and to the dominant axis at max_event_rate steps/s; its acceleration
//   the lowest each moving axis allows, capped (M204) by print_accel when
//   it moves E with a path axis, travel_accel when it does not move E,
//   retract_accel when it moves E alone (0: no cap); a block that moves no path axis
//   starts and ends at rest; a junction's speed is
//   v^2 = a d h / (1 - h), h = sin(theta / 2), a = min_i a_i / |j_i| over
//   the unit vector j = (w - u) / |w - u| of the two directions, capped by
//   both blocks' cruises. Then a reverse pass from rest at the end and a
//   forward pass, as a slicer's estimator does, and each block's trapezoid
//   (or triangle) time. mark() names the point before the next move;
//   at(mark) is the time of the moves before it (for M73 lines: call it
//   once every move is given, it plans what is pending).
#pragma once
#include <string>
#include <vector>

#include "board_info.h"

namespace sim {

struct AxisLimit {
  char name = 0;
  double steps_per_mm = 0;
  double max_rate_mm_s = 0;
  double accel_mm_s2 = 0;
  bool in_path = true;  // E is not: its moves share the XYZ path's time
};

struct MachineLimits {
  std::vector<AxisLimit> axes;
  double junction_mm = 0.01;
  double print_accel = 0, travel_accel = 0, retract_accel = 0;  // M204 P T R, mm/s^2 (0: none)
  double max_event_rate = 0;  // steps/s of a block's dominant axis at most (0: none)
  int index(char name) const;  // -1 if the machine has no such axis
  // "X 1000 steps/mm 40 mm/s 500 mm/s^2, ..., junction 0.01 mm": for a
  // file's header and a report.
  std::string describe() const;
};

class TimeEstimator {
 public:
  explicit TimeEstimator(const MachineLimits& limits) : l_(limits) {}
  void move(const std::vector<double>& delta_mm, double feed_mm_per_min, bool rapid = false);
  void rest();
  double seconds();
  size_t moves() const { return moves_; }
  size_t mark();
  double at(size_t mark);

 private:
  struct Block {
    double length, cruise2, accel, max_entry2;
    bool path;  // moves a path axis
  };
  void plan();  // the pending blocks, from rest to rest: their time added

  MachineLimits l_;
  std::vector<Block> pending_;
  std::vector<double> last_unit_;  // the last path block's direction (path axes), empty after a rest
  double seconds_ = 0;
  size_t moves_ = 0, planned_ = 0;           // blocks given, blocks timed
  std::vector<size_t> mark_block_;           // each mark's next block
  std::vector<double> mark_s_;               // its time (-1 until planned)
};

}  // namespace sim
