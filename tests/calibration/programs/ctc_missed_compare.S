/* Fault H (found by this suite): in CTC mode a counter above TOP misses the
 * match, runs on to MAX (0xFFFF) and wraps before matching the new TOP.
 * Timer1 CTC, OCR1A = 199, prescaler 1, OC1A toggles on match.
 * Phase 1, OCR1A lowered below the count:
 *   T: STS TCCR1B (count 0 at T) | T+2: 146 NOPs | T+148: OUT (MARK high)
 *   T+149: LDI | T+150: STS OCR1AH | T+152: LDI | T+153: STS OCR1AL = 99,
 *   count 153 > 99 -> wrap at T + 65536, match (leaves 99) at T + 65636
 *   loop until T+65356, then 420 NOPs (to T+65776) so the edges at T+65636
 *   and T+65736 are seen exactly
 * Phase 2, TCNT written above TOP:
 *   T+65776: STS TCNT1H = 0 | S2 = T+65778: OUT (MARK low)
 *   S2+1: STS TCNT1L = 150 -> wrap after 65536 - 150 ticks, match 100 later:
 *   S2+1 + 65386 + 100 = S2+65487
 *
 * EXPECT ocr_below_count: MARK^#0 -> OC1A*#0 = 65488
 *   T+65636 - (T+148)
 * EXPECT period_after_wrap: OC1A*#0 -> OC1A*#1 = 100
 * EXPECT tcnt_above_top: MARKv#0 -> OC1A*#2 = 65487
 * BUDGET 200000
 */
#include "calib.h"

/* 8-cycle loop of \n iterations (7 for the last: BRNE not taken),
 * starting 2 cycles after the macro starts */
.macro WAIT8 n
	ldi r24, lo8(\n)
	ldi r25, hi8(\n)
1:	NOPS 4
	sbiw r24, 1
	brne 1b
.endm

	.global main
main:
	sbi IO(MARK_DDR), 0
	sbi IO(OC1A_DDR), OC1A_BIT
	STS16 MEM(OCR1AL), 199
	ldi r16, (1 << COM1A0)
	sts MEM(TCCR1A), r16
	ldi r20, 0x01
	ldi r22, 0x00
	ldi r23, 150
	ldi r21, (1 << WGM12) | (1 << CS10)
	sts MEM(TCCR1B), r21	; T
	NOPS 146		; T+2
	out IO(MARK_PORT), r20	; T+148
	STS16 MEM(OCR1AL), 99	; T+149 .. T+155
	WAIT8 8150		; T+155 + 2 + 8150*8 - 1 = T+65356
	NOPS 420		; T+65356 .. T+65776
	sts MEM(TCNT1H), r22	; T+65776
	out IO(MARK_PORT), r22	; S2 = T+65778
	sts MEM(TCNT1L), r23	; S2+1
	WAIT8 8150		; S2+3 + 2 + 65199 = S2+65204
	NOPS 400		; to S2+65604
	FINISH
