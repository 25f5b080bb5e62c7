/* Timer compare period in CTC mode, prescalers 256 / 1024 / 1 (see
 * ctc_periods_a.S for the method: 8-cycle main loop, periods multiple of 8).
 *
 * EXPECT t0_n256_top1: OC0A*#2 -> OC0A*#3 = 512
 *   256 * (1 + 1) = 512
 * EXPECT t1_n1024_top2: OC1A*#1 -> OC1A*#2 = 3072
 *   1024 * (1 + 2) = 3072
 * EXPECT t2_n1_top127: OC2A*#2 -> OC2A*#3 = 128
 *   1 * (1 + 127) = 128
 */
#include "calib.h"
// MCUS: atmega328p atmega1284p (uses the A/B compare units of timers 0 and 2)
// BUDGET 200000

	.global main
main:
	ldi r16, 0xff				; every pin of B and D an output:
	out IO(DDRD), r16			; the OC pins are there on both parts
	out IO(DDRB), r16

	ldi r16, 1
	out IO(OCR0A), r16
	ldi r16, (1 << COM0A0) | (1 << WGM01)
	out IO(TCCR0A), r16

	STS16 MEM(OCR1AL), 2
	ldi r16, (1 << COM1A0)
	sts MEM(TCCR1A), r16

	ldi r16, 127
	sts MEM(OCR2A), r16
	ldi r16, (1 << COM2A0) | (1 << WGM21)
	sts MEM(TCCR2A), r16

	ldi r16, (1 << CS02)			; clk/256
	out IO(TCCR0B), r16
	ldi r16, (1 << WGM12) | (1 << CS12) | (1 << CS10)	; CTC, clk/1024
	sts MEM(TCCR1B), r16
	ldi r16, (1 << CS20)			; clk/1
	sts MEM(TCCR2B), r16

	ldi r24, lo8(2000)
	ldi r25, hi8(2000)
1:	NOPS 4
	sbiw r24, 1
	brne 1b
	FINISH
