#include "path.h"

#include "../../core/motion/amass.h"
#include "../../core/motion/feed_hold.h"
#include "../../core/motion/path_planner.h"
#include "../../core/motion/trapezoid.h"
#include "clock.h"
#include "limits.h"
#include "odometer.h"
#include "step_engine.h"

namespace path {
namespace {

constexpr uint8_t kAxes = board::Axes::count;
using Block = am::PathBlock<kAxes>;
using Plan = am::PathPlanner<kAxes, board::kPathBlocks, board::kPrinterCodes>;

// A G-code block is taken once the engine's queue holds this few segments:
// each is about a millisecond of motion or more except near rest
// (trapezoid.h keeps its runs as long as the curvature allows), time enough
// to plan the next.
constexpr uint8_t kLowWater = 4;
// A coordinated block runs up to 8 events per dominant step at low rates
// (core/motion/amass.h), its events at most at a quarter of the board's
// step-rate limit (grbl's AMASS goes to 16 kHz): the coordinated handler's
// load at that rate (docs/step-engine.md).
constexpr uint32_t kSmoothedEventRate = board::kMaxStepRate / 4;
// With a feed hold, cruise runs of under 2^15 ticks (2 ms at 16 MHz): the
// stop starts after what the engine has queued, at most kQueueSize of them.
constexpr uint8_t kHoldCruiseHalvings = 2;
// Direct moves come from the MOVE command and from homing; a board with
// neither links none.
constexpr bool kDirectMoves = board::kCommands || board::kHoming;

constexpr uint32_t highest_rate(uint8_t i = 0, uint32_t most = board::kMaxStepRate) {
  return i == kAxes ? most
                    : highest_rate(uint8_t(i + 1), board::Axes::max_rate_at(i) > most ? board::Axes::max_rate_at(i) : most);
}

// The planner's axis table, built on the stack for its constructor (a
// static table would sit in RAM for good). Rates are the axis's own limit
// or the coordinated handler's; steps per mm follow the axis's excitation
// mode (set on add(): modes change at rest).
template <typename Set>
struct Planned;
template <typename... A>
struct Planned<AxisSet<A...>> {
  static Plan make() {
    const am::PathAxis axes[kAxes] = {
        am::PathAxis{1.0f, float(OwnMaxRate<A>::value ? OwnMaxRate<A>::value : board::kMaxStepRate),
                     float(board::kDefaultAccel), A::name != 'E'}...};
    return Plan(axes, float(kJunctionDeviationUm) / 1000.0f, float(highest_rate()));
  }
};

// Built on first use: a board without G-code links no ring.
Plan& plan() {
  static Plan instance = Planned<board::Axes>::make();
  return instance;
}

bool ring_empty() { return !board::kGcode || plan().count() == 0; }

// A printer's M204 caps (set_path_accel()), by PathAccel, and which a move
// takes: the extruder's bit with others, alone, or not at all.
float path_accel[3] = {INFINITY, INFINITY, INFINITY};
constexpr uint8_t extruder_bit(uint8_t i = 0) {
  return i == kAxes ? 0 : board::Axes::name_at(i) == 'E' ? uint8_t(1u << i) : extruder_bit(uint8_t(i + 1));
}
PathAccel accel_kind(const planner::Move& move) {
  const uint8_t mask = planner::mask_of(move.steps);
  return !(mask & extruder_bit()) ? PathAccel::travel : mask == extruder_bit() ? PathAccel::retract : PathAccel::print;
}

am::TrapezoidRuns runs;
bool generating;       // the running block has runs left to queue
uint8_t axis_mask, dir_mask, serial;
uint8_t energised;     // axes a G-code block has energised (they stay so until released)
bool direct_waiting;   // a direct move to queue once the ring is empty
am::TrapezoidBlock direct;
planner::Move direct_move;
uint32_t dwell_ms;     // of a dwell still to be queued
bool starting, draining;
uint32_t last_add;     // clock tick of the last G-code block
bool engine_was_busy;  // at the end of the last pump()
bool exit_moving;      // the last block ends at speed: the next must follow at once
uint16_t starvations;  // see path.h; read by the simulator (sim/report.cpp)

// Feed hold (path.h): the generating block's stop (core/motion/feed_hold.h);
// the interval of the last run queued; how much slower than planned a stop
// that runs on into the next block has left it (0: nothing carries over).
Hold holding;
bool resume_asked;
am::FeedHold stop;
uint32_t last_interval;
float carried;

// Every block handed to the engine.
bool idle() { return !generating && !(board::kRealtime && stop.held()) && !direct_waiting && dwell_ms == 0 && ring_empty(); }

// A board with settings (board::kSettings: step/dir axes only) has its
// axes' steps per mm from them (set_axis()); the excitation modes of coil
// axes change them here.
void set_steps_per_mm() {
  if (board::kSettings) return;
  for (uint8_t i = 0; i < kAxes; ++i) {
    const float units_per_mm = float(board::Axes::steps_per_m_at(i)) * board::Axes::units_per_full_step_at(i) / 1000.0f;
    plan().set_steps_per_mm(i, units_per_mm / float(board::Axes::units_for(i, 1, false)));
  }
}

bool take_now() {
  // A block that ends at speed has its successor in the ring, and the engine
  // must never run dry between them (that would stop the axes dead): it is
  // taken as soon as the one before is queued, whatever the parser does next.
  if (plan().full() || draining || exit_moving) return true;
  if (engine::busy()) return engine::queued() <= kLowWater;
  return starting && clock::reached(last_add + clock::ms(kStartDelayMs));
}

// A coordinated block's interpolator, and its profile in the finer events
// of its smoothing level (core/motion/amass.h) where it has minor axes.
engine::Dda* interpolate(am::TrapezoidBlock& b, const planner::Steps& steps) {
  engine::Dda* dda = engine::begin_block(serial);
  const uint8_t level = am::amass::level(b.events, uint32_t(b.cruise), kSmoothedEventRate);
  dda->start(steps, level);
  am::amass::scale(b, level);
  return dda;
}

// Starts block `b` (smoothed in place: the caller's copy is spent).
void begin(am::TrapezoidBlock& b, const planner::Steps& steps) {
  const uint8_t mask = planner::mask_of(steps);
  engine::Dda* dda = (mask & (mask - 1)) ? interpolate(b, steps) : nullptr;
  if (board::kRealtime) {
    runs.shorten_cruise(kHoldCruiseHalvings);
    stop.begin(b);
  }
  runs.start(b, board::kStepTimerHz);
  axis_mask = mask;
  dir_mask = planner::dirs_of(steps);
  if (board::kOdometer) odometer::taken(steps, mask, dir_mask, b.events, dda, serial);
  exit_moving = b.exit > 0;
  generating = true;
}

// Starts the next block's runs; false when none is due or the engine has no
// interpolator slot for it yet (every block waits for one, so none is
// taken that could not start).
bool take() {
  if (!engine::block_available()) return false;
  if (kDirectMoves && direct_waiting) {
    begin(direct, direct_move.steps);
    direct_waiting = false;
    return true;
  }
  if (ring_empty() || !take_now()) return false;
  const Block* b = plan().take();
  // A stop that runs on from the block before enters as much slower.
  const float entry = board::kRealtime && holding == Hold::stopping ? b->entry * carried : b->entry;
  am::TrapezoidBlock block{b->events, entry, b->cruise, b->exit, b->accel};
  begin(block, b->steps);
  plan().done();
  return true;
}

// Whole milliseconds, one timer period each, no axis stepping (the caller
// has made sure the queue has room).
void queue_dwell() {
  const uint16_t ms = dwell_ms > 0xFFFF ? 0xFFFF : uint16_t(dwell_ms);
  engine::push(am::StepSegment::make(F_CPU / 1000, ms, 0, 0));
  dwell_ms -= ms;
}

// From rest again: the held block's events after its stop.
[[gnu::noinline]] void resume_now() {
  holding = Hold::none;
  resume_asked = false;
  if (!stop.held()) return;
  const float slower = stop.resume(runs, board::kStepTimerHz);
  generating = true;
  exit_moving = runs.exit_speed() > 0;
  if (board::kGcode) plan().slow_next_entry(slower);
}

}  // namespace

bool room() { return !direct_waiting && dwell_ms == 0 && !plan().full(); }

Added add(const planner::Move& move, const float (&delta_mm)[kAxes], float feed_mm_per_min, bool rapid) {
  if (!room()) return Added::full;
  const bool at_rest = idle() && !engine::busy();
  if (at_rest) set_steps_per_mm();  // modes change only at rest
  if (board::kPrinterCodes) plan().set_accel_cap(path_accel[uint8_t(accel_kind(move))]);
  switch (plan().add(move.steps, delta_mm, feed_mm_per_min, rapid)) {
    case Plan::Status::bad_feed: return Added::bad_feed;
    case Plan::Status::full: return Added::full;
    default: break;
  }
  last_add = clock::now();
  // Energised before counting: a coil axis's first energising snaps it to
  // its mode's grid, and the count starts from there (planner::count()).
  const uint8_t mask = planner::mask_of(move.steps);
  if (mask & ~energised) {
    board::Axes::energise(uint8_t(mask & ~energised));
    energised |= mask;
  }
  planner::count(move, at_rest);
  return Added::queued;
}

void set_axis(uint8_t axis, uint32_t steps_per_m, uint32_t max_rate, uint32_t max_accel) {
  plan().set_steps_per_mm(axis, float(steps_per_m) / 1000.0f);
  plan().set_limits(axis, float(max_rate), float(max_accel));
}

void set_junction_um(uint32_t um) { plan().set_junction_deviation(float(um) / 1000.0f); }

void set_axis_limit(uint8_t axis, bool accel, float value) {
  const am::PathAxis& a = plan().axis(axis);
  plan().set_limits(axis, accel ? a.max_rate : value, accel ? value : a.max_accel);
}

void set_path_accel(PathAccel which, float mm_per_s2) { path_accel[uint8_t(which)] = mm_per_s2; }
float path_accel_cap(PathAccel which) { return path_accel[uint8_t(which)]; }

float held_feed() { return plan().newest_nominal() * 60; }

bool ready_for(const planner::Move& move) {
  if (!idle()) return false;
  return !engine::busy() || axis_mask == planner::mask_of(move.steps);
}

void add_direct(const planner::Move& move, const planner::Ramp& ramp) {
  direct_move = move;
  direct = am::TrapezoidBlock{planner::dominant_count(move.steps), 0.0f, float(ramp.rate), 0.0f, float(ramp.accel)};
  const bool at_rest = !engine::busy();
  board::Axes::energise(planner::mask_of(move.steps));
  planner::count(move, at_rest);
  direct_waiting = true;
  pump();
}

void dwell(uint32_t ms) { dwell_ms = ms; }

void release() {
  board::Axes::release();
  energised = 0;
}
void start() { starting = true; }

namespace {

// The step interrupt stopped at an endstop: every block and dwell still to
// come is dropped with the engine's queue (limits.h says what that means).
void drop_everything() {
  if (board::kGcode) plan().clear();
  generating = direct_waiting = exit_moving = starting = draining = engine_was_busy = false;
  dwell_ms = 0;
  engine::clear_trip();
  limits::tripped();
}

}  // namespace

void pump() {
  if (board::Endstops::count && engine::stopped_at_endstop()) drop_everything();
  if (engine_was_busy && !engine::busy() && (generating || exit_moving)) ++starvations;
  for (;;) {
    if (engine::queue_full()) break;
    if (board::kRealtime && generating && holding == Hold::stopping && !stop.stopped() && runs.between_runs() &&
        !stop.stop(runs, last_interval, board::kStepTimerHz))
      generating = exit_moving = false;
    if (!generating) {
      if (board::kRealtime && holding != Hold::none && !(holding == Hold::stopping && carried > 0)) break;
      if (dwell_ms) {
        queue_dwell();
        continue;
      }
      if (!take()) break;
    }
    const am::StepRun r = runs.next_run();
    if (r.count == 0) {
      generating = false;
      if (board::kRealtime && stop.stopped()) {
        carried = stop.carried(runs);
        exit_moving = carried > 0;
      }
      continue;
    }
    am::StepSegment s = am::StepSegment::make(r.interval, r.count, axis_mask, dir_mask);
    s.block = serial;
    engine::push(s);
    if (board::kRealtime) last_interval = r.interval;
    if (board::kOdometer) odometer::queued(r.count);
  }
  // From rest the engine starts on a full queue, or on all there is for now.
  if (engine::queue_full() || !generating) engine::start();
  engine_was_busy = engine::busy();
  if (board::kRealtime) {
    if (holding == Hold::stopping && !generating && !(carried > 0) && !engine_was_busy) holding = Hold::held;
    if (holding == Hold::held && resume_asked) resume_now();
  }
  if (idle()) {
    starting = false;
    draining = false;
  }
}

bool handed_over() {
  if (idle()) return true;
  draining = true;
  return false;
}

bool at_rest() { return handed_over() && !engine::busy(); }

bool busy() { return !idle() || engine::busy(); }

void hold() {
  if (holding != Hold::none) return;
  resume_asked = false;
  holding = Hold::stopping;
  // A block that ended at speed with the next not taken yet: the next one
  // slows down from its planned entry.
  carried = !generating && exit_moving ? 1.0f : 0.0f;
  pump();
}

void resume() {
  resume_asked = holding != Hold::none;
  pump();
}

Hold hold_state() { return holding; }

}  // namespace path
