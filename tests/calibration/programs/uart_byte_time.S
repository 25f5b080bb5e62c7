/* Fault L: the UART's byte time follows U2X and the frame format whatever
 * the order of the writes. UBRR = 3 is written first, then U2X, then 8N1,
 * then the transmitter is enabled with the data-register-empty interrupt.
 * The handler toggles MARK and refills UDR: while the transmitter runs
 * without a gap, UDR empties once per frame, so the toggles are one frame
 * apart: 10 bits (start, 8 data, stop; no parity) of 8 * (UBRR + 1) = 32
 * cycles each with U2X.
 *
 * EXPECT frame_1: MARK*#2 -> MARK*#3 = 320
 * EXPECT frame_2: MARK*#3 -> MARK*#4 = 320
 *   10 * 8 * (3 + 1) = 320
 */
#include "calib.h"

#ifdef UCSR0A
#define UCSRA_ UCSR0A
#define UCSRB_ UCSR0B
#define UCSRC_ UCSR0C
#define UBRRL_ UBRR0L
#define UBRRH_ UBRR0H
#define UDR_   UDR0
#define U2X_   U2X0
#define TXEN_  TXEN0
#define UDRIE_ UDRIE0
#define FRAME_8N1 ((1 << UCSZ01) | (1 << UCSZ00))
#ifdef USART0_UDRE_vect_num
#define UDRE_VECTOR __vector_21	/* ATmega1284P: USART0 */
#else
#define UDRE_VECTOR __vector_19
#endif
#else
#define UCSRA_ UCSRA
#define UCSRB_ UCSRB
#define UCSRC_ UCSRC
#define UBRRL_ UBRRL
#define UBRRH_ UBRRH
#define UDR_   UDR
#define U2X_   U2X
#define TXEN_  TXEN
#define UDRIE_ UDRIE
#define FRAME_8N1 ((1 << URSEL) | (1 << UCSZ1) | (1 << UCSZ0))
#define UDRE_VECTOR __vector_14
#endif

	.global main
main:
	sbi IO(MARK_DDR), 0
	ldi r16, 0
	sts MEM(UBRRH_), r16
	ldi r16, 3
	sts MEM(UBRRL_), r16		; divisor first...
	ldi r16, (1 << U2X_)
	sts MEM(UCSRA_), r16		; ...then double speed
	ldi r16, FRAME_8N1
	sts MEM(UCSRC_), r16		; ...then 8N1
	ldi r16, (1 << TXEN_) | (1 << UDRIE_)
	ldi r20, 0			; MARK level
	ldi r21, 6			; toggles before stopping
	sts MEM(UCSRB_), r16
	sei
	NOPS 3000
	FINISH

	.global UDRE_VECTOR
UDRE_VECTOR:
	com r20
	out IO(MARK_PORT), r20
	ldi r16, 0x55
	sts MEM(UDR_), r16
	dec r21
	brne 1f
	ldi r16, (1 << TXEN_)		; enough: stop refilling
	sts MEM(UCSRB_), r16
1:	reti
