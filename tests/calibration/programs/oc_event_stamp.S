/* Fault J: a timer event happens on its own cycle, whatever instruction the
 * CPU is executing. Timer1 CTC, prescaler 1, TOP = 100, OC1A toggles on every
 * compare match, so OC1A edges are exactly 101 cycles apart on the chip.
 * The main loop is RCALL (3) + RET (4) + DEC (1) + BRNE taken (2) = 10
 * cycles, mostly multi-cycle instructions; 101 = 10 * 10 + 1, so successive
 * matches fall on different cycles inside those instructions. A simulator that runs timer events only
 * between instructions sees the edges 0..3 cycles late, differently each
 * time, and the intervals below come out as 101 +- 3.
 *
 * EXPECT p1: OC1A*#2 -> OC1A*#3 = 101
 * EXPECT p2: OC1A*#3 -> OC1A*#4 = 101
 * EXPECT p3: OC1A*#4 -> OC1A*#5 = 101
 * EXPECT p4: OC1A*#5 -> OC1A*#6 = 101
 * EXPECT p5: OC1A*#6 -> OC1A*#7 = 101
 * EXPECT p6: OC1A*#7 -> OC1A*#8 = 101
 * EXPECT p7: OC1A*#8 -> OC1A*#9 = 101
 * EXPECT p8: OC1A*#9 -> OC1A*#10 = 101
 *   each: 1 * (1 + 100) = 101
 */
#include "calib.h"

	.global main
main:
	sbi IO(OC1A_DDR), OC1A_BIT
	STS16 MEM(OCR1AL), 100
	ldi r16, (1 << COM1A0)			; toggle OC1A on match
	sts MEM(TCCR1A), r16
	ldi r16, (1 << WGM12) | (1 << CS10)	; CTC, clk/1
	sts MEM(TCCR1B), r16
	ldi r18, 120				; 120 * 10 cycles > 11 periods
loop:
	rcall sub
	dec r18
	brne loop
	FINISH
sub:
	ret
