// ATmega328P register facts the shared HAL code needs (datasheet 2015, ch. 14,
// 16, 20). Included through hal/avr/family.h only.
#pragma once
#include <avr/io.h>

// The macros are for assembly too (firmware/engine/step_vector.S includes
// this file through hal/avr/family.h); the C++ is not.
#ifndef __ASSEMBLER__
namespace hal {
namespace family {

// I/O address of PINx; DDRx and PORTx follow at +1 and +2 on every AVR we use.
constexpr uint8_t pin_io_address(char port) {
  return port == 'B' ? 0x03 : port == 'C' ? 0x06 : port == 'D' ? 0x09 : 0xFF;
}

}  // namespace family
}  // namespace hal
#endif

#include "../avr/usart0_names.h"
#define HAL_UART_RX_VECT USART_RX_vect
#define HAL_UART_UDRE_VECT USART_UDRE_vect

// Reset cause flags (WDRF: the watchdog reset the chip).
#define HAL_RESET_FLAGS MCUSR

#define HAL_TIMER1_MASK TIMSK1
#define HAL_TIMER1_FLAGS TIFR1

#ifndef __ASSEMBLER__
inline void hal_disable_jtag() {}
#endif

// Timer1 output compare A pin and its force-output-compare strobe.
#define HAL_OC1A_PORT 'B'
#define HAL_OC1A_BIT 1
// TCCR1C holds nothing but the force bits.
#define HAL_FORCE_OC1A_REG TCCR1C
#define HAL_FORCE_OC1A_VALUE _BV(FOC1A)
