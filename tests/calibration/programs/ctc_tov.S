/* Fault I (found by this suite): in CTC mode TOV1 is set only when the
 * counter wraps from MAX to 0, not at every compare-match clear at TOP.
 * Timer1 CTC, OCR1A = 99, prescaler 1, TOIE1 enabled; the overflow ISR
 * inverts PORTC, so every overflow makes an edge on PC0.
 *   T: start, 500 NOPs (five CTC periods: no overflow expected)
 *   S: OUT (MARK high) | S+1: STS TCNT1L = 150 (above TOP: runs to MAX,
 *   fault H) -> wrap at S+1 + 65536 - 150 = S+65387: TOV1
 *   ISR's first instruction: S+65387 + 4 (response) + 3 (JMP) = S+65394,
 *   IN (1) + COM (1), so the OUT to PORTC starts at S+65396
 *   S+3: loop to S+65300 (8162 x 8 cycles), then 200 NOPs
 *
 * EXPECT tov_at_wrap: MARK^#0 -> C0*#0 = 65396
 * EXPECT tov_only_at_wrap: count C0* = 1
 * BUDGET 200000
 */
#include "calib.h"

	.global main
main:
	sbi IO(MARK_DDR), 0
	ldi r16, 0x01
	out IO(DDRC), r16
	STS16 MEM(OCR1AL), 99
	ldi r16, (1 << TOIE1)
	sts MEM(TIMSK1), r16
	ldi r20, 0x01
	ldi r22, 0x00
	ldi r23, 150
	ldi r16, (1 << WGM12) | (1 << CS10)
	sts MEM(TCCR1B), r16	; T
	sei
	NOPS 500
	sts MEM(TCNT1H), r22
	out IO(MARK_PORT), r20	; S
	sts MEM(TCNT1L), r23	; S+1
	ldi r24, lo8(8162)	; S+3
	ldi r25, hi8(8162)
1:	NOPS 4			; S+5: 8162 x 8 - 1 cycles -> S+65300
	sbiw r24, 1
	brne 1b
	NOPS 200
	FINISH

	.global TIMER1_OVF_vect
TIMER1_OVF_vect:
	in r18, IO(PORTC)
	com r18
	out IO(PORTC), r18
	reti
