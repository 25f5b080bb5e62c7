/* Fault R: a write to TIFR clears only the flags written one.
 * On the ATmega16/32 one TIFR holds the flags of Timer0, Timer1 and Timer2;
 * each flag "is cleared by writing a logic one to the flag" (datasheet,
 * TIFR), so writing 1 << OCF1A, as the step engine does when it stops
 * Timer1, leaves a pending TOV0 alone. Stock simavr 1.6 clears every set
 * flag of every timer on any write to the register: the overflow is lost.
 *
 * Timer0 runs in normal mode, prescaler 1, TOIE0 set, interrupts off (main
 * is called with them off): TOV0 is set 256 cycles after the start. The
 * program waits 300 cycles, writes TIFR = 1 << OCF1A, then enables
 * interrupts: the pending overflow enters its vector, which toggles PC0.
 *
 * EXPECT tov0_kept: count C0* = 1
 *   one overflow vector entry (the next overflow, 256 cycles after the
 *   first, comes after FINISH)
 * BUDGET 10000
 */
#include "calib.h"
// MCUS: atmega32

	.global main
main:
	sbi IO(DDRC), 0				; PC0: Timer0 ISR toggles
	ldi r16, (1 << TOIE0)
	out IO(TIMSK), r16
	ldi r16, (1 << CS00)
	out IO(TCCR0), r16			; Timer0 N = 1
	ldi r24, 100
1:	dec r24					; 100 x 3 cycles: TOV0 set meanwhile
	brne 1b
	ldi r16, (1 << OCF1A)
	out IO(TIFR), r16			; clear Timer1's compare-A flag only
	sei
	NOPS 20					; the overflow vector runs here
	FINISH

	.global TIMER0_OVF_vect
TIMER0_OVF_vect:
	sbi IO(PORTC), 0			; PC0 high: the vector ran
	reti
