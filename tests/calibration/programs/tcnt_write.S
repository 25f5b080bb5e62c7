/* Fault B: a TCNT write moves the count by whole ticks (prescaler cycles),
 * and TCNT == TOP is a legal value.
 * Timer1 CTC, OCR1A = 9 (TOP), prescaler 8, OC1A toggles on match.
 * A TCNT write restarts the prescaler phase at the write (simavr models the
 * prescaler as starting with the count; see docs/simulator.md).
 *   S: OUT (MARK high) | S+1: STS TCNT1L = 5 -> ticks at S+9 (6), S+17 (7),
 *   S+25 (8), S+33 (9), S+41 (leaves TOP: match)
 *   S+3: 50 NOPs | S+53: OUT (MARK low) | S+54: STS TCNT1L = 9 (TOP)
 *   -> next tick leaves TOP: match at S+62
 *
 * EXPECT tcnt_mid: MARK^#0 -> OC1A*#0 = 41
 *   1 + (9 - 5 + 1) * 8 = 41
 * EXPECT tcnt_top: MARKv#0 -> OC1A*#1 = 9
 *   1 + 1 * 8 = 9
 * EXPECT period_after: OC1A*#1 -> OC1A*#2 = 80
 *   8 * (1 + 9) = 80
 */
#include "calib.h"

	.global main
main:
	sbi IO(MARK_DDR), 0	; marker pin (MARK)
	sbi IO(OC1A_DDR), OC1A_BIT
	STS16 MEM(OCR1AL), 9
	ldi r16, (1 << COM1A0)
	sts MEM(TCCR1A), r16
	ldi r20, 0x01
	ldi r22, 0x00
	ldi r24, 5
	ldi r25, 9
	ldi r16, (1 << WGM12) | (1 << CS11)	; CTC, clk/8
	sts MEM(TCCR1B), r16
	sts MEM(TCNT1H), r22	; high byte first (TEMP register)
	out IO(MARK_PORT), r20	; S
	sts MEM(TCNT1L), r24	; S+1
	NOPS 50
	out IO(MARK_PORT), r22	; S+53
	sts MEM(TCNT1L), r25	; S+54
	NOPS 120
	FINISH
