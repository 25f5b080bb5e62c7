// ATmega1284P register facts the shared HAL code needs (datasheet 8059D,
// ch. "I/O-Ports", "USART", "16-bit Timer/Counter1"). The part has the
// ATmega32's 40 pins (ports A..D, OC1A on PD5, OC2A on PD7, INT0/INT1 on
// PD2/PD3, the ADC on port A) with the ATmega328P's register layout (UART0,
// TCCRnA/B, TIMSKn/TIFRn, MCUSR). Included through hal/avr/family.h only.
#pragma once
#include <avr/io.h>

// The macros are for assembly too (firmware/engine/step_vector.S includes
// this file through hal/avr/family.h); the C++ is not.
#ifndef __ASSEMBLER__
namespace hal {
namespace family {

// I/O address of PINx; DDRx and PORTx follow at +1 and +2.
constexpr uint8_t pin_io_address(char port) {
  return port == 'A' ? 0x00 : port == 'B' ? 0x03 : port == 'C' ? 0x06 : port == 'D' ? 0x09 : 0xFF;
}

}  // namespace family
}  // namespace hal
#endif

#include "../avr/usart0_names.h"
#define HAL_UART_RX_VECT USART0_RX_vect
#define HAL_UART_UDRE_VECT USART0_UDRE_vect

// Reset cause flags (WDRF: the watchdog reset the chip).
#define HAL_RESET_FLAGS MCUSR

#define HAL_TIMER1_MASK TIMSK1
#define HAL_TIMER1_FLAGS TIFR1

// PC2..PC5 carry JTAG while the JTAGEN fuse is programmed (the factory
// setting); JTD (in MCUCR here) must be written twice within four cycles.
#ifndef __ASSEMBLER__
inline void hal_disable_jtag() {
  MCUCR = _BV(JTD);
  MCUCR = _BV(JTD);
}
#endif

// Timer1 output compare A pin and its force-output-compare strobe.
#define HAL_OC1A_PORT 'D'
#define HAL_OC1A_BIT 5
// TCCR1C holds nothing but the force bits.
#define HAL_FORCE_OC1A_REG TCCR1C
#define HAL_FORCE_OC1A_VALUE _BV(FOC1A)
