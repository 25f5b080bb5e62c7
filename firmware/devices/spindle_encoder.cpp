#include "spindle_encoder.h"

#include <avr/interrupt.h>

#include "../../hal/avr/ext_int.h"

namespace spindle_encoder {

Mode mode;
volatile int32_t count;
volatile uint16_t lost;
uint8_t known_a, known_b;

void init(Mode m) {
  const uint8_t sreg = SREG;
  cli();
  hal::ext_int::disable_int0();
  hal::ext_int::disable_int1();
  mode = m;
  known_a = board::SpindleEncoder::read() ? 1 : 0;
  known_b = board::SpindleQuadratureB::read() ? 1 : 0;
  if (m == Mode::single) {
    hal::ext_int::enable_int1(hal::ext_int::Sense::falling);
  } else {
    hal::ext_int::enable_int1(hal::ext_int::Sense::any_change);
    hal::ext_int::enable_int0(hal::ext_int::Sense::any_change);
  }
  SREG = sreg;
}

}  // namespace spindle_encoder
