/* Timer compare period in CTC mode, three timers at once, prescalers
 * 8 / 64 / 32. Each OCnx toggles on compare match, so consecutive pin edges
 * are one CTC period apart: N * (1 + OCRnA) cycles (datasheet CTC formula
 * f_OCnA = f_clk / (2 N (1 + OCRnA)), i.e. half a pin period per match).
 * The main loop is 8 cycles long and every period below is a multiple of 8,
 * so each edge is observed at the same loop phase: a one-cycle error in the
 * simulated period shows up as a one-cycle error here.
 *
 * EXPECT t0_n8_top24: OC0A*#2 -> OC0A*#3 = 200
 *   8 * (1 + 24) = 200
 * EXPECT t1_n64_top11: OC1A*#2 -> OC1A*#3 = 768
 *   64 * (1 + 11) = 768
 * EXPECT t1_ocr1b_phase: OC1B*#2 -> OC1A*#2 = 384
 *   OCR1B = 5 matches 64 * (5 + 1) = 384 cycles into the period,
 *   OCR1A (TOP) at 768: 768 - 384 = 384
 * EXPECT t2_n32_top6: OC2A*#2 -> OC2A*#3 = 224
 *   32 * (1 + 6) = 224
 */
#include "calib.h"
// MCUS: atmega328p atmega1284p (uses the A/B compare units of timers 0 and 2)

	.global main
main:
	ldi r16, 0xff				; every pin of B and D an output:
	out IO(DDRD), r16			; the OC pins are there on both parts
	out IO(DDRB), r16

	ldi r16, 24
	out IO(OCR0A), r16
	ldi r16, (1 << COM0A0) | (1 << WGM01)	; toggle, CTC
	out IO(TCCR0A), r16

	STS16 MEM(OCR1AL), 11
	STS16 MEM(OCR1BL), 5
	ldi r16, (1 << COM1A0) | (1 << COM1B0)
	sts MEM(TCCR1A), r16

	ldi r16, 6
	sts MEM(OCR2A), r16
	ldi r16, (1 << COM2A0) | (1 << WGM21)
	sts MEM(TCCR2A), r16

	ldi r16, (1 << CS01)			; clk/8
	out IO(TCCR0B), r16
	ldi r16, (1 << WGM12) | (1 << CS11) | (1 << CS10)	; CTC, clk/64
	sts MEM(TCCR1B), r16
	ldi r16, (1 << CS21) | (1 << CS20)	; clk/32
	sts MEM(TCCR2B), r16

	ldi r24, lo8(1200)
	ldi r25, hi8(1200)
1:	NOPS 4					; 4 + SBIW 2 + BRNE 2 = 8 cycles
	sbiw r24, 1
	brne 1b
	FINISH
