/* Fault K: while COM1A is set, OC1A overrides PORTB1; writing other bits of
 * the same port must not touch the pin. Timer1 CTC, prescaler 1, TOP = 40,
 * COM1A = set on match: OC1A rises once at the first match and then stays
 * high. Meanwhile the program toggles a neighbour bit of OC1A's port six
 * times with SBI/CBI (a direction line next to a step line). A simulator that
 * re-drives every output pin on each port write pulls OC1A back to its PORT
 * bit (0) at the first of them.
 *
 * EXPECT rises: count OC1A^ = 1
 *   the one match with COM1A = set
 * EXPECT falls: count OC1Av = 0
 *   nothing clears OC1A: no FOC, no clear-on-match, no PORT write to its bit
 */
#include "calib.h"

#if defined(__AVR_ATmega16__) || defined(__AVR_ATmega32__) || defined(__AVR_ATmega1284P__)
#define NEIGHBOUR_PORT PORTD	/* OC1A = PD5; PD7 is free */
#define NEIGHBOUR_DDR  DDRD
#define NEIGHBOUR_BIT  7
#else
#define NEIGHBOUR_PORT PORTB	/* OC1A = PB1; PB0 is free */
#define NEIGHBOUR_DDR  DDRB
#define NEIGHBOUR_BIT  0
#endif

	.global main
main:
	sbi IO(OC1A_DDR), OC1A_BIT
	sbi IO(NEIGHBOUR_DDR), NEIGHBOUR_BIT
	STS16 MEM(OCR1AL), 40
	ldi r16, (1 << COM1A1) | (1 << COM1A0)	; set OC1A on match
	sts MEM(TCCR1A), r16
	ldi r16, (1 << WGM12) | (1 << CS10)	; CTC, clk/1
	sts MEM(TCCR1B), r16
	NOPS 60					; past the first match (41 cycles)
	.rept 3
	sbi IO(NEIGHBOUR_PORT), NEIGHBOUR_BIT
	NOPS 10
	cbi IO(NEIGHBOUR_PORT), NEIGHBOUR_BIT
	NOPS 10
	.endr
	FINISH
