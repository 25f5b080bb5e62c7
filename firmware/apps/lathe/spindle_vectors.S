/* The spindle encoder's vectors, INT1 (channel A, or the one channel) and
 * INT0 (channel B), for the stepper leadscrew (leadscrew.cpp): the decode
 * (firmware/devices/spindle_encoder.h) and a locked pass's whole count.
 *
 * Each instruction's comment gives its own cycles and, on the timed path,
 * the running total from the interrupt's start: 4 cycles of response and 2
 * of the vector table's RJMP (the linker's relaxation, as on the ATmega16)
 * come first. The timed path is a locked count in the direction of the one
 * before in quadrature (channel A): decode, raise the step the last count
 * precomputed (the direction pin is already right), count, update the
 * lead (spindle_vectors.h: one 32-bit add, its sign the next count's
 * carry), precompute the next count's steps, return. A count that steps
 * then lowers the pulse (held since the rise by that work, more than
 * board::kStepHighCycles), moves the follower's position by the count's
 * steps, counts the carriage's steps and issues the further steps of a
 * burst (each held LV_HIGH_TURNS, the low time being the bookkeeping in
 * between), none beyond the pass's end, then checks the limit switch and
 * the end. A reversal (a locked count against the last one's direction)
 * converts the lead, sets the direction pin (set up by the conversion,
 * more than board::kDirSetupCycles before the rise) and precomputes, then
 * runs as a locked count. A count while neither catching up nor locked
 * goes to the C vector __vector_spindle_unlocked (leadscrew.cpp) with the
 * count's direction in LV_SLOW_DIR and every register as the interrupt
 * found it.
 *
 * While the carriage catches up (the pace vector steps it), a count runs
 * the same path with the T flag set: the lead, the next count's steps and
 * the follower's position, but no step and no direction pin.
 *
 * Registers: r24, r25, SREG, and Z from the count's update on. The data
 * is lathe_vector's and lathe_follower's, by the offsets of
 * spindle_vectors.h.
 */
#include <avr/io.h>

#include "spindle_vectors.h"

#define V(off) (lathe_vector + (off))
#define F(off) (lathe_follower + FOLLOWER_POS + (off))
#define PORTC_IO _SFR_IO_ADDR(PORTC)
#define PIND_IO _SFR_IO_ADDR(PIND)
#define SREG_IO _SFR_IO_ADDR(SREG)

	.section .text.spindle_vectors,"ax",@progbits

/* Out of the vectors' way, within their branches' reach. */
	/* Catching up (T set): the follower's count as a locked one's, no
	 * step, no direction (the pace's). Not locked nor catching: the C
	 * vector, registers as they were. */
not_locked:
	cpi r24, LV_STATE_CATCHING	; 1
	brne unlocked			; 1/2
	set				; 1  catching: the same count, no step
	lds r24, V(LV_AHEAD_DIR)	; 2
	cpse r24, r25			; 1/2
	rjmp reaim			; 2
	push r30			; 2
	push r31			; 2
	rjmp counted			; 2
unlocked:
	sts V(LV_SLOW_DIR), r25		; 2
	pop r25				; 2
	pop r24				; 2
	out SREG_IO, r24		; 1
	pop r24				; 2
	jmp __vector_spindle_unlocked	; 3 (2 relaxed)

/* Channel A (or the one channel). */
	.global INT1_vect
	.type INT1_vect, @function
INT1_vect:
	push r24			; 2   8
	in r24, SREG_IO			; 1   9
	push r24			; 2  11
	push r25			; 2  13
	lds r24, V(LV_MODE)		; 2  15
	ldi r25, LV_FORWARD		; 1  16  one channel: every count forward
	tst r24				; 1  17
	breq common			; 1  18  (2 taken)
	in r24, PIND_IO			; 1  19  the levels now
	lds r25, V(LV_KNOWN)		; 2  21
	eor r24, r25			; 1  22  bit 3: A changed since its last service
	sbrs r24, LV_A_BIT		; 2  24  (1 not skipping)
	rjmp lost			; 2      A as known: a pair of edges missed, no count
	ldi r24, 1 << LV_A_BIT		; 1  25
	eor r25, r24			; 1  26  A's new level
	sts V(LV_KNOWN), r25		; 2  28
	mov r24, r25			; 1  29
	lsr r24				; 1  30  A onto B's bit
	eor r25, r24			; 1  31  bit 2: A != B, forward
	andi r25, LV_FORWARD		; 1  32
	/* r25: the count's direction, LV_FORWARD or 0. */
common:
	lds r24, V(LV_STATE)		; 2  34
	cpi r24, LV_STATE_LOCKED	; 1  35
	brne not_locked			; 1  36
	clt				; 1  37  locked: T clear
	lds r24, V(LV_AHEAD_DIR)	; 2  39
	cpse r24, r25			; 2  41  (1 not skipping)
	rjmp reaim			; 2      against the last count's direction
	lds r24, V(LV_AHEAD)		; 2  43  this count's steps
	tst r24				; 1  44
	breq 1f				; 1  45  (2 taken: no step)
	sbi PORTC_IO, LV_STEP_BIT	; 2  47  the step rises
1:	push r30			; 2  49
	push r31			; 2  51
counted:
	sbrs r25, LV_FORWARD_BIT	; 2  53  (1 not skipping)
	rjmp back			; 2
	lds r24, V(LV_COUNT)		; 2  55
	subi r24, 0xFF			; 1  56  + 1
	sts V(LV_COUNT), r24		; 2  58
	breq count_up			; 1  59  the low byte wrapped (2)
forward_z:
	ldi r30, lo8(V(LV_DIR1))	; 1  60
	ldi r31, hi8(V(LV_DIR1))	; 1  61
update:
	lds r24, V(LV_LEAD + 3)		; 2  63
	sbrs r24, 7			; 1  64  (2 skipping: the lead < 0, no carry)
	adiw r30, LVD_NEG_T		; 2  66  the lead >= 0: this count carries, add -T
					;        (a skip over ADIW: docs/simulator.md, patch U)
	/* lead += Z[0..3] (rem or -T); then the whole steps at Z. */
	lds r24, V(LV_LEAD)		; 2  68
	ld r25, Z+			; 2  70
	add r24, r25			; 1  71
	sts V(LV_LEAD), r24		; 2  73
	lds r24, V(LV_LEAD + 1)		; 2  75
	ld r25, Z+			; 2  77
	adc r24, r25			; 1  78
	sts V(LV_LEAD + 1), r24		; 2  80
	lds r24, V(LV_LEAD + 2)		; 2  82
	ld r25, Z+			; 2  84
	adc r24, r25			; 1  85
	sts V(LV_LEAD + 2), r24		; 2  87
	lds r24, V(LV_LEAD + 3)		; 2  89
	ld r25, Z+			; 2  91
	adc r24, r25			; 1  92
	sts V(LV_LEAD + 3), r24		; 2  94
	ld r25, Z			; 2  96  the whole steps
	sbrs r24, 7			; 1  97  (2 skipping)
	subi r25, 0xFF			; 1  98  the new lead >= 0: the next count carries, + 1
	lds r24, V(LV_AHEAD)		; 2 100  this count's steps
	sts V(LV_AHEAD), r25		; 2 102  the next one's
	tst r24				; 1 103
	brne steps			; 1 104
done:
	pop r31				; 2 106
	pop r30				; 2 108
leave:
	pop r25				; 2 110
	pop r24				; 2 112
	out SREG_IO, r24		; 1 113
	pop r24				; 2 115
	reti				; 4 119

back:
	lds r24, V(LV_COUNT)		; 2
	subi r24, 1			; 1  - 1
	sts V(LV_COUNT), r24		; 2
	brcs count_down			; 1  the low byte wrapped (2)
back_z:
	ldi r30, lo8(V(LV_DIR0))	; 1
	ldi r31, hi8(V(LV_DIR0))	; 1
	rjmp update			; 2

count_up:				;    bytes 1..3 + 1
	lds r30, V(LV_COUNT + 1)
	lds r31, V(LV_COUNT + 2)
	adiw r30, 1
	sts V(LV_COUNT + 1), r30
	sts V(LV_COUNT + 2), r31
	brne 1f
	lds r24, V(LV_COUNT + 3)
	inc r24
	sts V(LV_COUNT + 3), r24
1:	rjmp forward_z

count_down:				;    bytes 1..3 - 1
	lds r30, V(LV_COUNT + 1)
	lds r31, V(LV_COUNT + 2)
	sbiw r30, 1
	sts V(LV_COUNT + 1), r30
	sts V(LV_COUNT + 2), r31
	brcc 1f
	lds r24, V(LV_COUNT + 3)
	dec r24
	sts V(LV_COUNT + 3), r24
1:	rjmp back_z

	/* The count's steps r24 (not 0): the first pulse is high. */
steps:
	brts 5f				; 1/2  catching: no pulse, the follower only
	cbi PORTC_IO, LV_STEP_BIT	; 2  the pulse ends
5:	mov r25, r24			; 1
	lsl r25				; 1
	sbc r25, r25			; 1  the steps' sign, 0 or 0xff
	lds r30, F(0)			; 2  the follower's position + r24
	add r30, r24			; 1
	sts F(0), r30			; 2
	lds r30, F(1)			; 2
	adc r30, r25			; 1
	sts F(1), r30			; 2
	lds r30, F(2)			; 2
	adc r30, r25			; 1
	sts F(2), r30			; 2
	lds r30, F(3)			; 2
	adc r30, r25			; 1
	sts F(3), r30			; 2
	brtc 6f				; 1/2
	rjmp done			; 2  catching: done
6:	sbrc r24, 7			; 1/2
	neg r24				; 1  steps to count: |n|
stepped:				;    a pulse has ended: the carriage + 1 or - 1
	mov r31, r25			; 1
	ori r31, 1			; 1  +1 or -1
	lds r30, V(LV_POS)		; 2
	add r30, r31			; 1
	sts V(LV_POS), r30		; 2
	lds r30, V(LV_POS + 1)		; 2
	adc r30, r25			; 1
	sts V(LV_POS + 1), r30		; 2
	lds r30, V(LV_POS + 2)		; 2
	adc r30, r25			; 1
	sts V(LV_POS + 2), r30		; 2
	lds r30, V(LV_POS + 3)		; 2
	adc r30, r25			; 1
	sts V(LV_POS + 3), r30		; 2
	dec r24				; 1
	breq checks			; 1/2  the count's last step
	rcall at_end			; 3 + 26
	breq checks			; 1/2  the pass's end: no further step
	sbi PORTC_IO, LV_STEP_BIT	; 2  the next step rises (low 57 cycles or more)
	ldi r30, LV_HIGH_TURNS		; 1
2:	dec r30				; 1
	brne 2b				; 2 / 1
	cbi PORTC_IO, LV_STEP_BIT	; 2  the pulse ends: high 3 x turns + 2
	rjmp stepped			; 2
checks:
	sbis PIND_IO, LV_LIMIT_BIT	; 1/2  the limit switch, low: hit
	rjmp limit			; 2
	rcall at_end
	brne 3f
	ldi r24, LV_STOP_LENGTH		;    the pass ends on this step
	rjmp halt
limit:
	ldi r24, LV_STOP_LIMIT
halt:					;    the pace is off while locked: the state and why
	sts V(LV_STOP), r24
	ldi r24, LV_STATE_IDLE
	sts V(LV_STATE), r24
3:	rjmp done

	/* A locked count against the last one's direction (r25): the lead
	 * converted (lead += flip), the direction pin set and the count's
	 * steps precomputed, then the count as any locked one. */
reaim:
	push r30			; 2
	push r31			; 2
	sts V(LV_AHEAD_DIR), r25	; 2
	brts 2f				; 1/2  catching: the direction is the pace's
	lds r24, V(LV_REVERSED)		; 2
	eor r24, r25			; 1  LV_FORWARD: the steps go up
	lsr r24				; 1
	lsr r24				; 1  1 up, 0 down
	sts V(LV_DIR_UP), r24		; 2
	sbrc r24, 0			; 1/2
	sbi PORTC_IO, LV_DIR_BIT	; 2
	sbrs r24, 0			; 1/2
	cbi PORTC_IO, LV_DIR_BIT	; 2  the direction set: 40 cycles or more before the rise
2:	ldi r30, lo8(V(LV_DIR0 + LVD_FLIP))	; 1
	ldi r31, hi8(V(LV_DIR0 + LVD_FLIP))	; 1
	/* SBRS and RJMP round the ADIW, written before the simulator's
	 * patch U: stock simavr 1.6 skips an ADIW r30, 15 (0x963f) as a
	 * two-word CALL. An SBRC over it would save a cycle and a word. */
	sbrs r25, LV_FORWARD_BIT	; 1/2
	rjmp 1f				; 2
	adiw r30, LVD_SIZE		; 2
1:
	lds r24, V(LV_LEAD)		; 2  lead += flip
	ld r25, Z+			; 2
	add r24, r25			; 1
	sts V(LV_LEAD), r24		; 2
	lds r24, V(LV_LEAD + 1)		; 2
	ld r25, Z+			; 2
	adc r24, r25			; 1
	sts V(LV_LEAD + 1), r24		; 2
	lds r24, V(LV_LEAD + 2)		; 2
	ld r25, Z+			; 2
	adc r24, r25			; 1
	sts V(LV_LEAD + 2), r24		; 2
	lds r24, V(LV_LEAD + 3)		; 2
	ld r25, Z+			; 2
	adc r24, r25			; 1
	sts V(LV_LEAD + 3), r24		; 2
	ld r25, Z			; 2  the whole steps
	sbrs r24, 7			; 1/2
	subi r25, 0xFF			; 1  the lead >= 0: this count carries
	sts V(LV_AHEAD), r25		; 2
	mov r24, r25			; 1
	lds r25, V(LV_AHEAD_DIR)	; 2
	tst r24				; 1
	breq 1f				; 1/2
	brts 1f				; 1/2  catching: no step
	sbi PORTC_IO, LV_STEP_BIT	; 2  the step rises
1:	rjmp counted			; 2

	/* Z flag: the pass has an end and the carriage is on it (r30, r31). */
at_end:
	lds r30, V(LV_HAS_END)		; 2
	cpi r30, 1			; 1
	brne 4f				; 1
	lds r30, V(LV_POS)		; 2
	lds r31, V(LV_END)		; 2
	cp r30, r31			; 1
	lds r30, V(LV_POS + 1)		; 2
	lds r31, V(LV_END + 1)		; 2
	cpc r30, r31			; 1
	lds r30, V(LV_POS + 2)		; 2
	lds r31, V(LV_END + 2)		; 2
	cpc r30, r31			; 1
	lds r30, V(LV_POS + 3)		; 2
	lds r31, V(LV_END + 3)		; 2
	cpc r30, r31			; 1
4:	ret				; 4
	/* An edge with no count: lost + 1. */
lost:
	rcall lost_one
	rjmp leave

	/* lost + 1 (r24). */
lost_one:
	lds r24, V(LV_LOST)
	subi r24, 0xFF
	sts V(LV_LOST), r24
	brne 1f
	lds r24, V(LV_LOST + 1)
	inc r24
	sts V(LV_LOST + 1), r24
1:	ret

	.size INT1_vect, . - INT1_vect

/* Channel B. Both channels' levels are read at once. */
	.global INT0_vect
	.type INT0_vect, @function
INT0_vect:
	push r24			; 2   8
	in r24, SREG_IO			; 1   9
	push r24			; 2  11
	push r25			; 2  13
	in r24, PIND_IO			; 1  14  the levels now
	lds r25, V(LV_KNOWN)		; 2  16
	eor r24, r25			; 1  17  bits 3, 2: A, B changed
	sbrs r24, LV_B_BIT		; 2  19  (1 not skipping)
	rjmp lost			; 2      B as known: a pair missed, no count
	sbrc r24, LV_A_BIT		; 2  21  (1 not skipping)
	rcall lost_one			; 3      A changed too: the order is unknown, doubtful
	ldi r24, 1 << LV_B_BIT		; 1  22
	eor r25, r24			; 1  23  B's new level
	sts V(LV_KNOWN), r25		; 2  25
	mov r24, r25			; 1  26
	lsr r24				; 1  27  A onto B's bit
	eor r25, r24			; 1  28  bit 2: A != B, backward
	andi r25, LV_FORWARD		; 1  29
	ldi r24, LV_FORWARD		; 1  30
	eor r25, r24			; 1  31  forward: A = B
	rjmp common			; 2  33  (then as INT1's, one cycle later)
	.size INT0_vect, . - INT0_vect
