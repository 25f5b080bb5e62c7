/* Fault E: after SEI exactly one instruction runs before a pending interrupt.
 * Timer1 CTC OCR1A = 9, prescaler 1, OCIE1A, with I = 0 until OCF1A is
 * pending. Then SEI at cycle S:
 *   S: SEI (1) | S+1: OUT PORTB <- PB0 high (1) | S+2: response (4)
 *   S+6: JMP (3) | S+9: ISR's SBI PORTC,0 (2) | S+11: RETI (4)
 *   S+15: OUT PORTB <- PB1 high (the instruction after RETI)
 *
 * EXPECT after_sei: B0^#0 -> C0^#0 = 8
 *   (S+9) - (S+1) = 8
 * EXPECT after_reti: C0^#0 -> B1^#0 = 6
 *   SBI (2) + RETI (4) = 6: the second OUT only runs after the ISR
 */
#include "calib.h"

	.global main
main:
	ldi r16, 0x03
	out IO(DDRB), r16
	ldi r16, 0x01
	out IO(DDRC), r16
	STS16 MEM(OCR1AL), 9
	ldi r16, (1 << OCIE1A)
	sts MEM(TIMSK1), r16
	ldi r16, (1 << WGM12) | (1 << CS10)
	sts MEM(TCCR1B), r16
	NOPS 20			; the first match (10 cycles in) is now pending
	ldi r18, 0x01
	ldi r19, 0x03
	sei			; S
	out IO(PORTB), r18	; S+1
	out IO(PORTB), r19
	NOPS 40
	FINISH

	.global TIMER1_COMPA_vect
TIMER1_COMPA_vect:
	sbi IO(PORTC), 0
	reti
