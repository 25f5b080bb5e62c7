// The path: everything that moves goes through here into the step engine.
// G-code's straight blocks pass the look-ahead planner
// (core/motion/path_planner.h), so a polyline runs through its vertices;
// a direct move (the MOVE command) is one block from rest to rest with its
// own rate and acceleration; a dwell is an idle stretch in the queue. Every
// block is timed by the exact trapezoid generator (core/motion/trapezoid.h):
// each step within a fifth of a step of constant-acceleration kinematics.
//
// Contract
//   add() queues one G-code block: the steps of every axis (planner::Move,
//   checked with planner::check() first), the program coordinates' change in
//   mm (the path's length and direction), the feed in mm/min, rapid for G0.
//   It answers full (nothing changed: call again) while the ring is full or
//   a direct move or dwell waits to be queued; room() says so beforehand
//   (an arc computes a chord only when it can queue it). held_feed() then says how
//   fast the block will really run.
//   ready_for(move) says whether a direct move may be queued now: the path
//   is idle, and the engine is at rest or runs the same axes (energising
//   other axes under a running move could hold the step interrupt off).
//   add_direct() then queues it (planner::check_ramp() and clamp() first);
//   dwell(ms) queues an idle stretch when the path is idle: after everything
//   queued so far, timed by the step timer to the tick.
//   Positions are counted when a block is queued (planner::count()).
//   pump() runs from the main loop. It takes the oldest planned G-code block
//   as late as it can: when the engine's queue runs low, when the ring is
//   full, or, with the engine at rest, once start() has said no more input
//   is on its way for now and kStartDelayMs have passed since the last block
//   arrived (so the first block of a program is planned with those after
//   it). A taken block's speeds are final; its segments go to the engine as
//   the queue takes them. handed_over() is true when every block has been
//   handed to the engine; asking it is waiting for that, so while it is false
//   pump() takes every block at once. at_rest() is handed_over() and the
//   engine stopped: what a command that needs the motion ended waits for.
//   When the step interrupt has stopped at an endstop (a hard limit or a
//   homing move's switch), pump() drops every block, direct move and dwell
//   not yet run and tells limits::tripped().
//   `starvations` (in path.cpp; the simulator's report reads it) counts the
//   times the engine ran dry while a block still had segments to queue or
//   ended at speed: the path fell behind the motion.
//
// Why
//   A taken block is fixed (its exit speed is the next block's entry), so
//   taking it late gives the planner the most blocks to look ahead over.
//   Directions change between chained blocks at speed: the engine sets them
//   when it loads a segment, one whole step interval before that segment's
//   first step edge, which is the drivers' set-up time with room to spare.
#pragma once
#include <stdint.h>

#include "../board.h"
#include "planner.h"

namespace path {

constexpr uint16_t kStartDelayMs = 50;
// grbl's junction deviation, the default of the $11 setting: 0.01 mm.
constexpr uint32_t kJunctionDeviationUm = 10;

enum class Added : uint8_t { queued, full, bad_feed };
Added add(const planner::Move& move, const float (&delta_mm)[board::Axes::count], float feed_mm_per_min, bool rapid);
// The settings (firmware/services/settings.h), at rest: a G-code block's
// axis limits in steps (its steps/mm as steps per metre, the top rate in
// steps/s, the acceleration in steps/s^2) and the junction deviation in um.
void set_axis(uint8_t axis, uint32_t steps_per_m, uint32_t max_rate, uint32_t max_accel);
void set_junction_um(uint32_t um);
// A printer's machine limits (firmware/services/printer_codes.h), at any
// time: the blocks queued so far keep theirs. An axis's top rate in steps/s
// (M203) or, `accel`, its acceleration in steps/s^2 (M201); the acceleration along the
// path in mm/s^2 of the blocks that extrude while they move (M204 P), that
// do not extrude (T) and that only move the extruder (R).
enum class PathAccel : uint8_t { print, travel, retract };
void set_axis_limit(uint8_t axis, bool accel, float value);
void set_path_accel(PathAccel which, float mm_per_s2);
float path_accel_cap(PathAccel which);  // infinite: none set
// Whether add() would queue a block now (not full).
bool room();
// The feed the last queued block runs at, mm/min: its F as the axes' limits
// hold it (lower than asked: the caller says so).
float held_feed();
bool ready_for(const planner::Move& move);
void add_direct(const planner::Move& move, const planner::Ramp& ramp);
void dwell(uint32_t ms);
// Switches every coil and driver off (at rest); the next block energises
// its axes again.
void release();
void start();
void pump();
bool handed_over();
bool at_rest();
// Blocks or steps remain (asking changes nothing, unlike handed_over()).
bool busy();

// Feed hold, on a board with kRealtime. hold() slows the motion down to rest
// at each block's own acceleration, from the speed it has reached at the
// end of what the engine has queued (at most kQueueSize segments of under
// 2^15 ticks in a cruise, core/motion/trapezoid.h; a ramp's runs in a ramp): through as many blocks as that
// takes, a stop within a block keeping the rest of it. hold_state() says
// stopping, then held once the axes are at rest; nothing new starts while
// held (blocks still arrive and are planned). resume() (also while still
// stopping: it waits) runs the rest of the held block from rest to its
// planned exit, lowering the next block's entry as much as that exit is
// missed. Every step is kept: the positions end exactly where they would
// have without the hold.
enum class Hold : uint8_t { none, stopping, held };
void hold();
void resume();
Hold hold_state();

}  // namespace path
