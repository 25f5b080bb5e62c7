/* The step engine's Timer1 compare-A vector (TIMER1_COMPA_vect): the fast
 * path of firmware/engine/step_engine.cpp, whose C handlers it jumps to.
 *
 * Cycle counts are from the match: 4 of interrupt response and 3 of the
 * vector table's JMP come first. Each instruction's comment gives its own
 * cycles and, on the timed paths, the running total from the match.
 * Steady cruise of the timer-pulsed axis is the hot path and is written in
 * assembly: ending the pulse (after the board's pulse width), re-arming it
 * and counting, where a C handler would spend more than that saving and
 * restoring the 17 registers its calls may clobber. At a segment's last step
 * it takes the next segment straight from the ring if that one is marked
 * `chain` (it continues the same axis in the same direction with no long
 * interval): the new compare lands 45 cycles after the match, 60 before the
 * next match at 160 kHz, and only then does the step's pulse end (51 cycles:
 * no padding), so the whole switch takes about 96 cycles. The trapezoid's
 * parts can be one step long (two of them back to back at a run's end), and
 * a switch that took longer than the interval would start the next one late
 * until a compare is missed: a step the pins never make. Every other case
 * ends the pulse, restores the registers it used and jumps to a C handler
 * (__vector_step_slow, __vector_step_coordinated, __vector_step_switch in
 * step_engine.cpp), which then runs exactly as if it were the vector.
 *
 * The vector saves SREG and the registers it uses, nothing else; the C
 * handlers are entered with everything as the interrupt found it. The jumps
 * to them are RJMPs (2 cycles): its section follows step_engine.o's code in
 * the link, and were it ever linked out of an RJMP's reach (+-4 KB) the link
 * would fail, not slow the vector down. The engine's shared
 * state is read by its assembler names (step_queue, step_fast, ...:
 * step_engine.cpp). The layout of the queue and its segments and TCCR1A's
 * OC1A modes are in step_vector.h, checked against the C++ there; the registers are <avr/io.h>'s and hal/avr/family.h's. The two
 * per-board numbers are in step_vector_board.h, generated for each image
 * from the board header (step_vector_board.cpp): STEP_VECTOR_TIMER_AXIS,
 * whether the board has a timer-pulsed axis (without one the fast path's
 * dispatch is left out), and STEP_VECTOR_PAD_TURNS, the turns of the loop
 * that stretches the pulse to the board's kTimerPulseCycles.
 */
#include <avr/io.h>

#include "../../hal/avr/family.h"
#include "step_vector.h"
#include "step_vector_board.h"

#define TCCR1A_MEM _SFR_MEM_ADDR(TCCR1A)
#define FORCE_MEM _SFR_MEM_ADDR(HAL_FORCE_OC1A_REG)

	.section .text.step_vector,"ax",@progbits
	.global TIMER1_COMPA_vect
	.type TIMER1_COMPA_vect, @function
TIMER1_COMPA_vect:
	push r24			; 2   9
	in r24, _SFR_IO_ADDR(SREG)	; 1  10
	push r24			; 2  12
.if STEP_VECTOR_TIMER_AXIS		;    (a board without one has no fast path)
	lds r24, step_fast		; 2  14
	cpi r24, 2			; 1  15
	breq 4f				; 1 / 2 taken (17): the segment's last step
.endif
	/* A match that raised STEP: end the pulse now, whatever comes next. */
	lds r24, step_armed		; 2  18
	tst r24				; 1  19
	breq 3f				; 1  20
	ldi r24, STEP_OC1A_CLEAR	; 1  21
	sts TCCR1A_MEM, r24		; 2  23
.if STEP_VECTOR_PAD_TURNS
	ldi r24, STEP_VECTOR_PAD_TURNS	; 1
9:	dec r24				; 1
	brne 9b				; 2, 1 on the last turn: 3 per turn
.endif
	ldi r24, HAL_FORCE_OC1A_VALUE	; 1
	sts FORCE_MEM, r24		; 2  26 + 3 pad: the pulse ends (38 on the Uno)
3:
	lds r24, step_fast		; 2
	cpi r24, 1			; 1
	breq 2f				; 1 / 2 taken: a step with more to follow
	lds r24, step_coordinated	; 2
	tst r24				; 1
	brne 6f				; 1 / 2
	pop r24				; 2
	out _SFR_IO_ADDR(SREG), r24	; 1
	pop r24				; 2
	rjmp __vector_step_slow		; 2
6:
	pop r24				; 2
	out _SFR_IO_ADDR(SREG), r24	; 1
	pop r24				; 2
	rjmp __vector_step_coordinated	; 2
	/* Another step of this segment follows: re-arm and count. */
2:
	ldi r24, STEP_OC1A_SET		; 1
	sts TCCR1A_MEM, r24		; 2
	lds r24, step_remaining		; 2
	subi r24, 1			; 1
	sts step_remaining, r24		; 2
	lds r24, step_remaining+1	; 2
	sbci r24, 0			; 1  Z: the 16-bit result is 0
	sts step_remaining+1, r24	; 2
	brne 5f				; 1 / 2
	ldi r24, 2			; 1  the next match is the last step
	sts step_fast, r24		; 2
5:
	pop r24				; 2
	out _SFR_IO_ADDR(SREG), r24	; 1
	pop r24				; 2
	reti				; 4
	/* The segment's last step; its pulse is high. */
4:
	push r25			; 2  19
	push r30			; 2  21
	push r31			; 2  23
	lds r24, step_next_index	; 2  25
	lds r25, step_queue+STEP_QUEUE_HEAD	; 2  27
	cp r24, r25			; 1  28
	breq 7f				; 1  29  nothing queued (2, 30)
	lds r30, step_next		; 2  31
	lds r31, step_next+1		; 2  33
	ldd r25, Z+STEP_SEGMENT_CHAIN	; 2  35  chain
	tst r25				; 1  36
	breq 7f				; 1  37  (2, 38)
	ldd r25, Z+STEP_SEGMENT_COMPARE+1	; 2  39
	sts _SFR_MEM_ADDR(OCR1AH), r25	; 2  41
	ldd r25, Z+STEP_SEGMENT_COMPARE	; 2  43
	sts _SFR_MEM_ADDR(OCR1AL), r25	; 2  45  the new period is set
	ldi r25, STEP_OC1A_CLEAR	; 1  46
	sts TCCR1A_MEM, r25		; 2  48
	ldi r25, HAL_FORCE_OC1A_VALUE	; 1  49
	sts FORCE_MEM, r25		; 2  51  the pulse ends
	ldi r25, STEP_OC1A_SET		; 1
	sts TCCR1A_MEM, r25		; 2  the next one is armed
	sts step_queue+STEP_QUEUE_TAIL, r24	; 2  pop the finished segment
	subi r24, 0xFF			; 1
	sts step_next_index, r24	; 2
	ldd r24, Z+STEP_SEGMENT_COUNT	; 2
	ldd r25, Z+STEP_SEGMENT_COUNT+1	; 2
	sbiw r24, 1			; 2  count - 1, Z: a one-step segment
	sts step_remaining, r24		; 2
	sts step_remaining+1, r25	; 2
	ldi r24, 1			; 1
	brne 6f				; 1 / 2
	ldi r24, 2			; 1
6:
	sts step_fast, r24		; 2
	adiw r30, STEP_SEGMENT_SIZE	; 2  the slot after the new segment
	cpi r30, lo8(step_queue+STEP_QUEUE_SLOTS_BYTES)	; 1
	ldi r25, hi8(step_queue+STEP_QUEUE_SLOTS_BYTES)	; 1
	cpc r31, r25			; 1
	brne 1f				; 1 / 2
	ldi r30, lo8(step_queue)	; 1
	ldi r31, hi8(step_queue)	; 1
1:
	sts step_next, r30		; 2
	sts step_next+1, r31		; 2
	pop r31				; 2
	pop r30				; 2
	pop r25				; 2
	rjmp 5b				; 2  about 96 to the end of RETI
	/* Nothing to chain: end the pulse (36 cycles at the earliest), then
	 * the C handler takes the queue. */
7:
	ldi r25, STEP_OC1A_CLEAR	; 1  31
	sts TCCR1A_MEM, r25		; 2  33
	ldi r25, HAL_FORCE_OC1A_VALUE	; 1  34
	sts FORCE_MEM, r25		; 2  36  the pulse ends
	pop r31				; 2
	pop r30				; 2
	pop r25				; 2
	pop r24				; 2
	out _SFR_IO_ADDR(SREG), r24	; 1
	pop r24				; 2
	rjmp __vector_step_switch	; 2
	.size TIMER1_COMPA_vect, . - TIMER1_COMPA_vect
