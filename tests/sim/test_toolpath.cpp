// The XY toolpath avrmotion-sim draws (--plot), as numbers: each step given
// to the line that made it (the one whose target it approaches, not the last
// one answered), travel / feed / extrusion told apart, the pen deciding on a
// plotter. Its panel in real runs: test_pictures_toolpath.cpp.
#include <string>
#include <vector>

#include "picture_check.h"
#include "toolpath.h"

namespace {

using picturetest::stretches;
using picturetest::Stretch;

// --- the XY toolpath: which line moved the tool, and what kind of move -----

sim::AxisTrace step_axis(char name, double steps_per_mm) {
  sim::AxisTrace a;
  a.name = name;
  a.kind = 1;  // am::AxisKind::step_dir
  a.steps_per_mm = steps_per_mm;
  return a;
}

sim::Response ok_line(const std::string& line, uint64_t sent) { return {line, "ok", "", sent, sent + 50}; }

using sim::MoveKind;

TEST(Toolpath, AStepBelongsToTheLineWhoseTargetItApproachesNotToTheLastLineAnswered) {
  // 10 steps per mm. The G1 is sent (and answered) while the G0 before it is
  // still running, as the firmware does with moves of the same axes; so is
  // the last G0. Their steps still go to their own lines.
  sim::AxisTrace x = step_axis('X', 10), y = step_axis('Y', 10);
  uint64_t c = 1000;
  for (int k = 0; k < 10; ++k, c += 1000) {  // G0 X1 Y1: diagonal events
    x.add_step(c, 1);
    y.add_step(c + 5, 1);
  }
  c += 20000;
  for (int k = 0; k < 10; ++k, c += 1000) {  // G1 X2 Y1.5: Y on every other event
    x.add_step(c, 1);
    if (k % 2) y.add_step(c + 5, 1);
  }
  c += 20000;
  for (int k = 0; k < 20; ++k, c += 1000) {  // G0 X0 Y0: Y on 15 of 20 events
    x.add_step(c, -1);
    if ((k + 1) * 15 / 20 > k * 15 / 20) y.add_step(c + 5, -1);
  }
  const std::vector<sim::Response> r = {ok_line("G21 G90", 0), ok_line("G0 X1 Y1", 100),
                                        ok_line("G1 X2 Y1.5 F600", 500), ok_line("G0 X0 Y0", 25000)};
  const sim::Toolpath tp = sim::trace_toolpath({x, y}, r);
  ASSERT_TRUE(tp.present);
  EXPECT_EQ(tp.rule, sim::ToolpathRule::gcode);
  EXPECT_EQ(tp.motion_lines, 3u);
  ASSERT_EQ(tp.points.size(), 41u);  // the origin and one point per event
  EXPECT_EQ(stretches(tp),
            (std::vector<Stretch>{{1, MoveKind::travel, 10}, {2, MoveKind::feed, 10}, {3, MoveKind::travel, 20}}));
  EXPECT_NEAR(tp.points[10].x, 1, 1e-12);
  EXPECT_NEAR(tp.points[10].y, 1, 1e-12);
  EXPECT_NEAR(tp.points[20].x, 2, 1e-12);
  EXPECT_NEAR(tp.points[20].y, 1.5, 1e-12);
  EXPECT_NEAR(tp.points.back().x, 0, 1e-12);
  EXPECT_NEAR(tp.points.back().y, 0, 1e-12);
  EXPECT_NEAR(tp.length_mm[int(MoveKind::travel)], std::sqrt(2.0) + std::sqrt(4 + 2.25), 1e-9);
  EXPECT_NEAR(tp.length_mm[int(MoveKind::feed)], std::sqrt(1 + 0.25), 1e-9);
  EXPECT_EQ(tp.length_mm[int(MoveKind::extrusion)], 0);
}

TEST(Toolpath, ATargetHalfAStepAwayEndsWhereTheFirmwareRoundedIt) {
  // Motor Shield axes at 10 full steps per mm in a full-step mode: the
  // interpreter keeps X0.05 as half a step (32 of the 64 units of a full
  // step), the firmware rounds the move to whole steps, away from the start:
  // one step (two half steps as decoded) to 0.1. Both that step and the next
  // line's first step leave the tool 0.05 from the target: the step in the
  // line's own direction is the line's. All lines are sent before anything
  // moves.
  const auto coil_axis = [](char name) {
    sim::AxisTrace a = step_axis(name, 10);
    a.kind = 2;  // am::AxisKind::shield_latch
    a.units_per_step = 2;
    return a;
  };
  for (const bool back : {false, true}) {
    sim::AxisTrace x = coil_axis('X'), y = coil_axis('Y');
    x.add_step(1000, 2);
    x.add_step(5000, back ? -2 : 2);
    if (!back) x.add_step(6000, 2);
    for (int k = 0; k < 3; ++k) y.add_step(9000 + 1000 * uint64_t(k), 2);
    const std::vector<sim::Response> r = {ok_line("G1 X0.05 F600", 100), ok_line(back ? "G0 X0" : "G0 X0.3", 200),
                                          ok_line("G1 Y0.3", 300)};
    const sim::Toolpath tp = sim::trace_toolpath({x, y}, r);
    EXPECT_EQ(
        stretches(tp),
        (std::vector<Stretch>{{0, MoveKind::feed, 1}, {1, MoveKind::travel, back ? 1u : 2u}, {2, MoveKind::feed, 3}}))
        << (back ? "back" : "on");
    ASSERT_EQ(tp.points.size(), back ? 6u : 7u);
    EXPECT_NEAR(tp.points[1].x, 0.1, 1e-12);
  }
}

TEST(Toolpath, ExtrusionIsWhereEAdvancedDuringTheMove) {
  // 100 steps per mm; E steps 13 cycles after X or Y in the same event.
  sim::AxisTrace x = step_axis('X', 100), y = step_axis('Y', 100), e = step_axis('E', 100);
  std::vector<sim::Response> r = {ok_line("M83", 0)};
  uint64_t c = 1000;
  const auto line = [&](const std::string& text) { r.push_back(ok_line(text, c - 500)); };
  line("G0 X1 Y0");
  for (int k = 0; k < 100; ++k, c += 500) x.add_step(c, 1);
  c += 10000;
  line("G1 E0.5 F1800");  // prime: E alone
  for (int k = 0; k < 50; ++k, c += 500) e.add_step(c, 1);
  c += 10000;
  line("G1 X1 Y1 E0.2 F600");
  for (int k = 0; k < 100; ++k, c += 500) {
    y.add_step(c, 1);
    if (k % 5 == 4) e.add_step(c + 13, 1);
  }
  c += 10000;
  line("G1 E-0.5 F1800");  // retract
  for (int k = 0; k < 50; ++k, c += 500) e.add_step(c, -1);
  c += 10000;
  line("G0 X0 Y0");
  for (int k = 0; k < 100; ++k, c += 500) {
    x.add_step(c, -1);
    y.add_step(c + 5, -1);
  }
  c += 10000;
  line("G1 E0.5 F1800");  // a prime just before a move without E: not that move's extrusion
  for (int k = 0; k < 50; ++k, c += 500) e.add_step(c, 1);
  c += 10000;
  line("G1 X0 Y-1 F600");
  for (int k = 0; k < 100; ++k, c += 500) y.add_step(c, -1);
  c += 10000;
  line("G0 X1 Y-1 E0.1");  // E advancing on a G0 is extrusion all the same
  for (int k = 0; k < 100; ++k, c += 500) {
    x.add_step(c, 1);
    if (k % 10 == 9) e.add_step(c + 13, 1);
  }
  const sim::Toolpath tp = sim::trace_toolpath({x, y, step_axis('Z', 100), e}, r);
  EXPECT_EQ(tp.rule, sim::ToolpathRule::extrusion);
  EXPECT_EQ(stretches(tp), (std::vector<Stretch>{{1, MoveKind::travel, 100},
                                                 {3, MoveKind::extrusion, 100},
                                                 {5, MoveKind::travel, 100},
                                                 {7, MoveKind::feed, 100},
                                                 {8, MoveKind::extrusion, 100}}));
  EXPECT_NEAR(tp.length_mm[int(MoveKind::extrusion)], 2, 1e-9);
  EXPECT_NEAR(tp.length_mm[int(MoveKind::travel)], 1 + std::sqrt(2.0), 1e-9);
  EXPECT_NEAR(tp.length_mm[int(MoveKind::feed)], 1, 1e-9);
}

TEST(Toolpath, OnAPlotterThePenDecidesWhateverTheLineSaid) {
  // No E axis, Z moves: Z at its lowest level (0 here) is the pen down.
  sim::AxisTrace x = step_axis('X', 10), y = step_axis('Y', 10), z = step_axis('Z', 10);
  std::vector<sim::Response> r;
  uint64_t c = 1000;
  r.push_back(ok_line("G1 Z2 F600", c - 500));
  for (int k = 0; k < 20; ++k, c += 500) z.add_step(c, 1);
  r.push_back(ok_line("G1 X1 Y1", c));  // pen up: travel, though G1
  c += 1000;
  for (int k = 0; k < 10; ++k, c += 500) {
    x.add_step(c, 1);
    y.add_step(c, 1);
  }
  r.push_back(ok_line("G1 Z0", c));
  c += 1000;
  for (int k = 0; k < 20; ++k, c += 500) z.add_step(c, -1);
  r.push_back(ok_line("G0 X2", c));  // pen down: drawing, though G0
  c += 1000;
  for (int k = 0; k < 10; ++k, c += 500) x.add_step(c, 1);
  const sim::Toolpath tp = sim::trace_toolpath({x, y, z}, r);
  EXPECT_EQ(tp.rule, sim::ToolpathRule::pen);
  EXPECT_EQ(tp.pen_down_mm, 0);
  EXPECT_EQ(stretches(tp), (std::vector<Stretch>{{1, MoveKind::travel, 10}, {3, MoveKind::feed, 10}}));
  // Without the pen's Z moving, the lines decide.
  const sim::Toolpath flat = sim::trace_toolpath({x, y, step_axis('Z', 10)}, r);
  EXPECT_EQ(flat.rule, sim::ToolpathRule::gcode);
  EXPECT_EQ(stretches(flat), (std::vector<Stretch>{{1, MoveKind::feed, 10}, {3, MoveKind::travel, 10}}));
}

TEST(Toolpath, AMoveLineTakesWhatHappenedBeforeTheNextMotionLine) {
  sim::AxisTrace x = step_axis('X', 10), y = step_axis('Y', 10);
  for (int k = 0; k < 10; ++k) {
    x.add_step(1000 + 500 * uint64_t(k), 1);
    y.add_step(1000 + 500 * uint64_t(k), 1);
  }
  for (int k = 0; k < 10; ++k) x.add_step(20000 + 500 * uint64_t(k), -1);
  const std::vector<sim::Response> r = {ok_line("MOVE X10 Y10 F100", 100), ok_line("POS", 9000),
                                        ok_line("G0 X0 Y1", 15000)};
  const sim::Toolpath tp = sim::trace_toolpath({x, y}, r);
  EXPECT_EQ(tp.motion_lines, 2u);
  EXPECT_EQ(stretches(tp), (std::vector<Stretch>{{0, MoveKind::feed, 10}, {2, MoveKind::travel, 10}}));
}

TEST(Toolpath, OnlyWhenXAndYBothMoved) {
  sim::AxisTrace x = step_axis('X', 10), y = step_axis('Y', 10);
  x.add_step(1000, 1);
  EXPECT_FALSE(sim::trace_toolpath({x, y}, {}).present);
  EXPECT_FALSE(sim::trace_toolpath({x, step_axis('Z', 10)}, {}).present);
  y.add_step(2000, 1);
  EXPECT_TRUE(sim::trace_toolpath({x, y}, {}).present);
  EXPECT_TRUE(sim::is_gcode_line("G1 X1"));
  EXPECT_TRUE(sim::is_gcode_line(" m 114"));
  EXPECT_TRUE(sim::is_gcode_line("; a comment"));
  EXPECT_FALSE(sim::is_gcode_line("MOVE X1"));
  EXPECT_FALSE(sim::is_gcode_line("NOP"));
}


}  // namespace
