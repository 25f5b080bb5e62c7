#include "odometer.h"

namespace odometer {
namespace {

constexpr uint8_t kAxes = board::Axes::count;

uint32_t handed[kAxes];  // steps of every block taken
// The newest block taken: its axes and directions (a one-axis block's), its
// interpolator and serial (a coordinated block's), its events and those queued.
uint8_t newest_axes, newest_dirs, newest_serial;
const engine::Dda* newest_dda;
uint32_t newest_events, newest_queued;

// Takes the steps of events (from, to] of a stretch off `steps`: of block
// `d` (every axis, closed form), or of the one axis in `axes`.
void take_off(uint32_t (&steps)[kAxes], const engine::Dda* d, uint8_t axes, uint8_t dirs, uint32_t from, uint32_t to) {
  if (d) dirs = d->dirs();
  for (uint8_t i = 0, bit = 1; i < kAxes; ++i, bit = uint8_t(bit << 1)) {
    uint32_t n = to - from;
    if (d) n = d->steps_after(i, to) - d->steps_after(i, from);
    else if (!(axes & bit)) continue;
    steps[i] -= (dirs & bit) ? n : 0u - n;
  }
}

}  // namespace

void taken(const int32_t (&steps)[kAxes], uint8_t axes, uint8_t dirs, uint32_t events, const engine::Dda* dda,
           uint8_t serial) {
  for (uint8_t i = 0; i < kAxes; ++i) handed[i] += uint32_t(steps[i]);
  newest_axes = axes;
  newest_dirs = dirs;
  newest_dda = dda;
  newest_serial = serial;
  newest_events = events;
  newest_queued = 0;
}

void queued(uint16_t events) { newest_queued += events; }

void now(uint32_t (&steps)[kAxes]) {
  const engine::Progress p = engine::progress();
  for (uint8_t i = 0; i < kAxes; ++i) steps[i] = handed[i];
  take_off(steps, newest_dda, newest_axes, newest_dirs, newest_queued, newest_events);
  // The queue, newest segment first: a coordinated block's stretch runs
  // from `high` (its events queued) down to `low`.
  const engine::Dda* d = nullptr;
  uint32_t high = 0, low = 0;
  for (uint8_t index = engine::head(); index != p.tail;) {
    index = uint8_t(index - 1);
    const am::StepSegment& s = engine::segment(index);
    const uint16_t left = index == p.tail ? uint16_t(s.count - p.made) : s.count;
    if (!(s.axes & (s.axes - 1))) {
      take_off(steps, nullptr, s.axes, s.dirs, 0, left);  // one axis, or a dwell (none)
      continue;
    }
    const engine::Dda* b = &engine::block(s.block);
    if (b != d) {
      if (d) take_off(steps, d, 0, 0, low, high);
      d = b;
      high = low = newest_dda == b && s.block == newest_serial ? newest_queued : b->events();
    }
    low -= left;  // the running segment's made events stay below its stretch
  }
  if (d) take_off(steps, d, 0, 0, low, high);
}

}  // namespace odometer
