// ATmega16 / ATmega32 register facts the shared HAL code needs (the two parts
// share their I/O map; datasheets ch. "I/O Ports", "USART", "16-bit
// Timer/Counter1"). Included through hal/avr/family.h only.
#pragma once
#include <avr/io.h>

// The macros are for assembly too (firmware/engine/step_vector.S includes
// this file through hal/avr/family.h); the C++ is not.
#ifndef __ASSEMBLER__
namespace hal {
namespace family {

// I/O address of PINx; DDRx and PORTx follow at +1 and +2.
constexpr uint8_t pin_io_address(char port) {
  return port == 'A' ? 0x19 : port == 'B' ? 0x16 : port == 'C' ? 0x13 : port == 'D' ? 0x10 : 0xFF;
}

}  // namespace family
}  // namespace hal
#endif

#define HAL_UDR UDR
#define HAL_UCSRA UCSRA
#define HAL_UCSRB UCSRB
#define HAL_UCSRC UCSRC
#define HAL_UBRRH UBRRH
#define HAL_UBRRL UBRRL
#define HAL_U2X U2X
#define HAL_RXEN RXEN
#define HAL_TXEN TXEN
#define HAL_RXCIE RXCIE
#define HAL_UDRIE UDRIE
#define HAL_DOR DOR
#define HAL_FE FE
// UCSRC shares its address with UBRRH: URSEL selects UCSRC.
#define HAL_UCSRC_8N1 (_BV(URSEL) | _BV(UCSZ1) | _BV(UCSZ0))
#define HAL_UART_RX_VECT USART_RXC_vect
#define HAL_UART_UDRE_VECT USART_UDRE_vect

// Reset cause flags (WDRF: the watchdog reset the chip).
#define HAL_RESET_FLAGS MCUCSR

#define HAL_TIMER1_MASK TIMSK
#define HAL_TIMER1_FLAGS TIFR

// PC2..PC5 carry JTAG while the JTAGEN fuse is programmed (the factory
// setting); JTD must be written twice within four cycles to free them.
#ifndef __ASSEMBLER__
inline void hal_disable_jtag() {
  MCUCSR = _BV(JTD);
  MCUCSR = _BV(JTD);
}
#endif

// Timer1 output compare A pin and its force-output-compare strobe.
#define HAL_OC1A_PORT 'D'
#define HAL_OC1A_BIT 5
// FOC1A sits in TCCR1A beside the COM bits: the strobe rewrites "clear".
#define HAL_FORCE_OC1A_REG TCCR1A
#define HAL_FORCE_OC1A_VALUE (_BV(COM1A1) | _BV(FOC1A))
