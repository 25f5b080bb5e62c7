// One step event of an interpolator: which axes step now, and which way.
//
// Contract
//   Bit i of `axes` set = axis i takes one step at this event; bit i of
//   `dirs` set = axis i moves forward (towards +). `dirs` is valid for every
//   axis in `axes` (bits of axes that do not step carry no meaning). The
//   layout matches StepSegment's axes/dirs bytes (core/motion/step_queue.h), so an
//   event can drive the same outputs. Two bytes: returned in registers on the
//   AVR (r24:r25), which matters because the step interrupt calls next() once
//   per event.
#pragma once
#include <stdint.h>

namespace am {

struct StepEvent {
  uint8_t axes;
  uint8_t dirs;
};

}  // namespace am
