/* Fault C: CTC with TOP = OCR1A = 0 at prescaler 1. The counter matches on
 * every timer tick (every cycle), so OC1A (toggle on match) changes level on
 * every cycle; the CPU runs only NOPs, so each edge is seen at its cycle.
 *
 * EXPECT period: OC1A*#10 -> OC1A*#11 = 1
 *   N * (1 + OCR1A) = 1 * 1
 * EXPECT ten_periods: OC1A*#10 -> OC1A*#20 = 10
 */
#include "calib.h"

	.global main
main:
	sbi IO(OC1A_DDR), OC1A_BIT
	STS16 MEM(OCR1AL), 0
	ldi r16, (1 << COM1A0)
	sts MEM(TCCR1A), r16
	ldi r16, (1 << WGM12) | (1 << CS10)
	sts MEM(TCCR1B), r16
	NOPS 60
	FINISH
