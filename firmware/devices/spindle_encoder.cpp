#include "spindle_encoder.h"

#include <avr/interrupt.h>

#include "../../hal/avr/ext_int.h"

namespace spindle_encoder {

void init(Mode m, State& s) {
  const uint8_t sreg = SREG;
  cli();
  hal::ext_int::disable_int0();
  hal::ext_int::disable_int1();
  s.mode = m;
  static_assert(board::SpindleEncoder::port == 'D' && board::SpindleEncoder::mask == 1 << 3 &&
                    board::SpindleQuadratureB::port == 'D' && board::SpindleQuadratureB::mask == 1 << 2,
                "known holds A and B in PIND's bits 3 and 2");
  s.known = PIND & uint8_t(board::SpindleEncoder::mask | board::SpindleQuadratureB::mask);
  if (m == Mode::single) {
    hal::ext_int::enable_int1(hal::ext_int::Sense::falling);
  } else {
    hal::ext_int::enable_int1(hal::ext_int::Sense::any_change);
    hal::ext_int::enable_int0(hal::ext_int::Sense::any_change);
  }
  SREG = sreg;
}

}  // namespace spindle_encoder
