// The register and bit names of a USART0 with the n-suffixed spelling (the
// ATmega328P's and the ATmega1284P's; datasheets "USART0"), as the HAL's
// names. Included by those parts' register maps (hal/avr/family.h); each
// names its own vectors.
#pragma once

#define HAL_UDR UDR0
#define HAL_UCSRA UCSR0A
#define HAL_UCSRB UCSR0B
#define HAL_UCSRC UCSR0C
#define HAL_UBRRH UBRR0H
#define HAL_UBRRL UBRR0L
#define HAL_U2X U2X0
#define HAL_RXEN RXEN0
#define HAL_TXEN TXEN0
#define HAL_RXCIE RXCIE0
#define HAL_UDRIE UDRIE0
#define HAL_DOR DOR0
#define HAL_FE FE0
#define HAL_UCSRC_8N1 (_BV(UCSZ01) | _BV(UCSZ00))
