/* Fault M (issue 7): a low level on a disabled INT1 does nothing, and no
 * simulator event is lost while a PWM output sits on that pin.
 * The Motor Shield's D3 PWM at duty 0 in miniature: Timer2 fast PWM on OC2B
 * (PD3, which is also INT1), OCR2B = 0, prescaler 1, so PD3 is low except
 * for a one-clock spike every 256 cycles ("If the OCR2A is set equal to
 * BOTTOM, the output will be a narrow spike for each MAX+1 timer clock
 * cycle"; the same holds for OCR2B). INT1 is in its reset state: ISC11:10 =
 * 00 (low level) and EIMSK.INT1 = 0. A level interrupt triggers as long as
 * the pin is held low only when it is enabled (INT1 in EIMSK, I in SREG);
 * disabled, the low level requests nothing, and INTF1 "is always cleared
 * when INT1 is configured as a level interrupt".
 * simavr 1.6 starts a level poller (a cycle timer that re-arms every cycle
 * until it sees the pin high) on each fall of PD3 regardless. Here every
 * spike falls inside the main loop's JMP, so no poller sees it: they pile
 * up until the 64 cycle-timer slots are gone, and timer events are dropped.
 *
 * Meanwhile Timer0 counts: normal mode, prescaler 8, TOIE0; its ISR toggles
 * PC0. Timer1 (normal mode, prescaler 1, TOIE1) ends the run from its
 * overflow ISR, so the run length is hardware time, not instruction counts.
 *   T2: Timer2 started   T0: Timer0 started (T2 + 3)
 *   T1: Timer1 started, T0 + 1026 (OUT 1, a 128 x 8 - 1 cycle delay loop,
 *   2 NOPs)
 *   end: TOV1 at T1 + 65536 = T0 + 66562 (plus the interrupt latency and at
 *   most one 16-cycle Timer0 ISR)
 *
 * EXPECT t0_overflows: count C0* = 32
 *   TOV0 every 256 * 8 = 2048 cycles, at T0 + 2048 k; k = 1..32 lie before
 *   the end (32 * 2048 = 65536 < 66562 < 67584 = 33 * 2048), ~1000 cycles of
 *   margin either side
 * EXPECT pwm_one_period: OC2Bv#8 -> OC2Bv#9 = 256
 * EXPECT pwm_240_periods: OC2Bv#8 -> OC2Bv#248 = 61440
 *   fast PWM period: (TOP + 1) * N = 256 * 1; 240 * 256 = 61440. The run
 *   holds ~260 periods, so the 248th fall lies well inside it
 * EXPECT intf1_clear: count B0* = 0
 *   INTF1 (read at the end, copied to PB0) stays 0 in level mode
 * BUDGET 200000
 */
#include "calib.h"
// MCUS: atmega328p (OC2B shares PD3 with INT1 on this part only)

	.global main
main:
	sbi IO(DDRD), 3				; PD3: OC2B
	sbi IO(DDRC), 0				; PC0: Timer0 ISR toggles
	sbi IO(DDRB), 0				; PB0: INTF1 at the end

	ldi r16, 0				; INT1 low-level sense, disabled
	sts MEM(EICRA), r16			; (the reset values, written to
	out IO(EIMSK), r16			;  make the point)
	sts MEM(OCR2B), r16			; duty 0: a spike per period
	ldi r16, (1 << COM2B1) | (1 << WGM21) | (1 << WGM20)
	sts MEM(TCCR2A), r16			; fast PWM, TOP 0xFF, OC2B non-inverting
	ldi r16, (1 << TOIE0)
	sts MEM(TIMSK0), r16
	ldi r16, (1 << TOIE1)
	sts MEM(TIMSK1), r16
	ldi r17, (1 << CS01)			; Timer0 N = 8
	ldi r18, (1 << CS10)			; Timer1 N = 1
	ldi r24, 128
	ldi r16, (1 << CS20)
	sts MEM(TCCR2B), r16			; T2: Timer2 N = 1
	sei					; T2 + 2
	out IO(TCCR0B), r17			; T0 = T2 + 3
1:	NOPS 5					; T0 + 1: 128 x 8 - 1 cycles
	dec r24
	brne 1b
	NOPS 2					; T0 + 1024
	sts MEM(TCCR1B), r18			; T1 = T0 + 1026 = T2 + 1029
	NOPS 2
	/* T2 + 1033: the main loop, 4 cycles: NOP at T2 + 1 (mod 4), JMP at
	 * T2 + 2..T2 + 4 (mod 4). Each spike rises on TOV2 at T2 + 256 j (the
	 * JMP's last cycle) and falls one cycle later, at the JMP's end: simavr
	 * runs both at that one instruction boundary, after the pollers (due
	 * earlier) have caught up with PD3 still low, so no poller sees it
	 * high. The ISRs take 16 cycles (12 on stock simavr, fault D), a
	 * multiple of 4, so the loop keeps its phase. */
2:	nop
	jmp 2b

	.global TIMER0_OVF_vect
TIMER0_OVF_vect:				; 4 + 3 (JMP) + 2 + 3 + 4 = 16 cycles
	sbi IO(PINC), 0				; toggle PC0
	nop
	nop
	nop
	reti

	.global TIMER1_OVF_vect
TIMER1_OVF_vect:				; the end: INTF1 to PB0, stop
	sbic IO(EIFR), INTF1
	sbi IO(PORTB), 0
	FINISH
