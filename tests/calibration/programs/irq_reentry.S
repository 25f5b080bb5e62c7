/* Faults D and E together: a pending interrupt re-entering at once.
 * Timer1 CTC with OCR1A = 3, prescaler 1: OCF1A is set every 4 cycles, so it
 * is pending again whenever the ISR returns. The main line runs NOPs.
 * One loop = response 4 + JMP 3 + OUT 1 + COM 1 + RETI 4 + exactly one
 * main-line instruction after RETI (NOP, 1) = 14 cycles, so PB0 (written by
 * the ISR's first instruction, alternating level) has edges 14 cycles apart.
 *
 * EXPECT isr_period: B0*#4 -> B0*#5 = 14
 * EXPECT isr_period_later: B0*#10 -> B0*#11 = 14
 *   4 (response) + 3 (JMP) + 1 (OUT) + 1 (COM) + 4 (RETI) + 1 (NOP) = 14
 */
#include "calib.h"

	.global main
main:
	ldi r16, 0x01
	out IO(DDRB), r16
	ldi r17, 0x01		; ISR output level, inverted on every entry
	STS16 MEM(OCR1AL), 3
	ldi r16, (1 << OCIE1A)
	sts MEM(TIMSK1), r16
	ldi r16, (1 << WGM12) | (1 << CS10)
	sts MEM(TCCR1B), r16
	sei
	NOPS 400
	FINISH

	.global TIMER1_COMPA_vect
TIMER1_COMPA_vect:
	out IO(PORTB), r17
	com r17
	reti
