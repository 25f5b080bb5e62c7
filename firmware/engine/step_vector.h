/* What the step vector (firmware/engine/step_vector.S) knows of the C++ step
 * engine's data: plain preprocessor definitions, so that both the assembler
 * and step_engine.cpp include them. step_engine.cpp checks every one against
 * the C++ structures and constants (static_assert), so a change there fails
 * the build instead of the vector reading the wrong bytes. The registers come
 * from <avr/io.h> and hal/avr/family.h; the per-board numbers from
 * step_vector_board.h, which the build generates for each image
 * (step_vector_board.cpp).
 */
#pragma once
#include <avr/io.h>

/* am::StepSegment (core/motion/step_queue.h): byte offsets and size. The
 * 16-bit fields are little-endian, low byte first. */
#define STEP_SEGMENT_COUNT 0
#define STEP_SEGMENT_COMPARE 2
#define STEP_SEGMENT_CHAIN 9
#define STEP_SEGMENT_SIZE 11

/* step_queue, an am::StepQueue<engine::kQueueSize>: the slots from offset 0,
 * then the head and tail ring indices. */
#define STEP_QUEUE_SIZE 16
#define STEP_QUEUE_SLOTS_BYTES (STEP_QUEUE_SIZE * STEP_SEGMENT_SIZE)
#define STEP_QUEUE_HEAD 176
#define STEP_QUEUE_TAIL 177

/* TCCR1A's two OC1A modes (hal::step_timer::kOc1aClear, kOc1aSet): "clear on
 * match" and "set on match" (the pulse armed), WGM11:10 = 0 for CTC. */
#define STEP_OC1A_CLEAR _BV(COM1A1)
#define STEP_OC1A_SET (_BV(COM1A1) | _BV(COM1A0))
