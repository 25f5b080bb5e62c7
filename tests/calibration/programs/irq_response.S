/* Fault D: interrupt response time.
 * Timer1 CTC, TOP = OCR1A = 99, prescaler 1, OC1A toggles on match, OCIE1A.
 * The CPU runs only NOPs, so at the match (cycle T) it is at an instruction
 * boundary. Datasheet: 4 cycles response (PC push + vector fetch), then the
 * vector's JMP (3 cycles); the ISR's first instruction starts at T+7.
 *
 * EXPECT response: OC1A*#0 -> B0^#0 = 7
 *   T: response (4) | T+4: JMP (3) | T+7: SBI PORTB,0 -> 7
 * EXPECT period: OC1A*#0 -> OC1A*#1 = 100
 *   CTC period = N * (1 + OCR1A) = 1 * 100
 */
#include "calib.h"

	.global main
main:
	sbi IO(DDRB), 0		; PB0: marker
	sbi IO(OC1A_DDR), OC1A_BIT
	STS16 MEM(OCR1AL), 99
	ldi r16, (1 << COM1A0)	; toggle OC1A on compare match
	sts MEM(TCCR1A), r16
	ldi r16, (1 << OCIE1A)
	sts MEM(TIMSK1), r16
	sei
	ldi r16, (1 << WGM12) | (1 << CS10)	; CTC, clk/1
	sts MEM(TCCR1B), r16
	NOPS 250
	FINISH

	.global TIMER1_COMPA_vect
TIMER1_COMPA_vect:
	sbi IO(PORTB), 0	; marker: first instruction of the ISR
	cbi IO(PORTB), 0
	reti
