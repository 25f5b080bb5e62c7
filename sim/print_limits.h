// The machine limits a slicer's estimate needs (print_estimate.h), for a
// G-code image: the steps/mm from its board descriptor; each axis's top
// rate and acceleration measured from the image itself, since the
// descriptor does not carry them (core/board/descriptor.h); the junction
// deviation, which neither says, given.
//
// Contract of probe_limits()
//   Runs the image on a machine of its own (endstops open, no homing: the
//   soft limits are off) with `G91`, then for each axis of the descriptor
//   `G1 <axis>40 F60000` and `M400`: one block from rest to rest, asked
//   faster than any axis goes. From that axis's step edges: its top rate is
//   the mean rate over the cruise (the intervals within 1 % of the
//   shortest), its acceleration the cruise rate squared over twice the
//   steps before the first cruise interval (v^2 = 2 a s from rest), both
//   in mm. An axis that did not move all its steps, or has no cruise,
//   throws std::runtime_error. The extruder ('E') is not a path axis.
//   junction_mm is the argument (grbl's default 0.01 mm: what the m32's
//   firmware uses, docs/gcode.md; a slicer takes it from its profile).
//
// Contract of board_limits()
//   The descriptor's axes and steps/mm alone (rates and accelerations 0),
//   read without running the image: for a file whose machine-limits block
//   sets every one of them (slicer_file.h, file_sets_all()).
#pragma once
#include <string>

#include "print_estimate.h"

namespace sim {

MachineLimits probe_limits(const std::string& elf_path, double junction_mm = 0.01);
MachineLimits board_limits(const std::string& elf_path, double junction_mm = 0.01);

}  // namespace sim
