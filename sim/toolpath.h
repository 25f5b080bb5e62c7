// The XY toolpath of a run: where the tool went in the plane, from the
// decoded step events of axes X and Y, and what kind of motion each stretch
// was (travel, feed, extrusion). sim/plot.cpp draws it.
//
// The path
//   X's and Y's step events merged in time order: one point per step event,
//   in mm from the power-up origin (0, 0), the first point being the origin
//   itself. An X and a Y step of one coordinated event (the firmware steps
//   them in one interrupt, at most a few tens of cycles apart) make one
//   diagonal point. Nothing is smoothed or resampled.
//
// Which line moved the tool (attribution)
//   The firmware answers a G0/G1/MOVE line "ok" once the move is queued, so
//   its motion starts after it was sent. But it does not end before the next
//   line is answered: a move of the same axes as the running one is queued
//   behind it as soon as the running one's segments are all in the step
//   queue, and is answered then, while the tool is still on the previous
//   line (examples/uno-plotter.gcode: each diamond edge after the first is
//   answered before the one before it has ended). So answer times do not
//   say where one line's motion ends; the path does. The firmware runs
//   moves in order, each a straight line in steps to its target, so:
//     - the G-code lines answered "ok" are run through the firmware's own
//       interpreter (core/text/gcode_interpreter.h, with the image's axes and
//       scales), which gives each G0/G1 its target;
//     - the motion lines are taken in order, and line k takes the next XY
//       step events as long as each brings the tool strictly closer to line
//       k's target (on a tie: only a step in the line's own direction on
//       that axis). Along a straight line every step brings the tool closer
//       to its end, and the next line's first step takes it away again (the
//       firmware rounds a target to the nearest step, half away from the
//       start, so the end is within half a step of the target);
//     - step events that happened before line k was sent belong to an
//       earlier line: they go to line k-1 (a MOVE has no target here, its
//       motion is what happened before the next motion line was sent), and
//       those after the last motion line to the last one.
//
// Kinds (the classification rule)
//   extrusion  the stretch of a line during which the E axis advanced: the
//              net E steps between the stretch's first and last XY step
//              event are forward (boards with an E axis);
//   feed       a G1 (or MOVE) stretch without extrusion;
//   travel     a G0 stretch without extrusion.
//   A board without an E axis whose Z moved during the run is taken as a pen
//   plotter (the Uno: the pen on Z): there each XY step is feed ("drawing")
//   when Z is at its lowest level of the run at that step (pen down), and
//   travel otherwise (pen up), whatever the line said. Step events no line
//   could account for are feed.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "axis_decoder.h"
#include "serial_host.h"

namespace sim {

enum class MoveKind : uint8_t { travel, feed, extrusion };
const char* move_kind_name(MoveKind k);  // "travel", "feed", "extrusion"

enum class ToolpathRule : uint8_t {
  extrusion,  // the board has an E axis: E decides extrusion, G0/G1 the rest
  pen,        // no E axis, Z moved: Z's lowest level is pen down
  gcode,      // neither: G0 is travel, G1/MOVE feed
};

struct ToolpathPoint {
  double x = 0, y = 0;             // mm
  uint64_t cycle = 0;              // the step event's cycle (0 for the origin)
  MoveKind kind = MoveKind::feed;  // of the stretch from the previous point to this one
  int line = -1;                   // index into the responses of the line that moved the tool here, -1 none
};

struct Toolpath {
  bool present = false;  // the board has X and Y and both stepped in the run
  ToolpathRule rule = ToolpathRule::gcode;
  double pen_down_mm = 0;             // the pen rule's lowest Z level
  std::vector<ToolpathPoint> points;  // the origin, then one point per X and/or Y step event
  double length_mm[3] = {0, 0, 0};    // path length per MoveKind (each line's move taken as straight)
  size_t motion_lines = 0;            // G0/G1/MOVE lines answered ok
};

// `axes` as Machine::axes() (the board's axes in descriptor order),
// `responses` as SerialHost::responses().
Toolpath trace_toolpath(const std::vector<AxisTrace>& axes, const std::vector<Response>& responses);

// Whether the firmware takes a line as G-code (firmware/apps/cnc/gcode.cpp,
// claims()): G, M or N and a number, or a comment.
bool is_gcode_line(const std::string& line);

}  // namespace sim
