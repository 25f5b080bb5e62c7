/* The contract between the spindle vectors in assembly (spindle_vectors.S)
 * and the C++ leadscrew (leadscrew.cpp): the data both touch, by offset.
 *
 * One object, lathe_vector (struct LatheVector below), holds what a
 * spindle count reads and writes; the follower (am::Follower) is
 * lathe_follower, whose position the vector moves by the count's steps
 * (FOLLOWER_POS: its offset, checked against core/lathe/follower.h). The
 * offsets are numbers here because the assembler reads this file too; the
 * C++ part checks every one of them against the struct (static_assert), so
 * a field moved in one place and not the other does not compile.
 *
 * The lead. While a pass catches up or is locked, the vector does not keep the follower's
 * residual R (0 <= R < den) but lead = R - T, T = den - rem for the
 * direction of the last count (rem: that direction's fraction, T: what R
 * must reach for the next count in that direction to carry). lead >= 0 is
 * then exactly "the next count carries", one sign bit, and a count's update
 * is one 32-bit add: lead += rem without a carry, lead += -T with one
 * (R + rem - den - T = lead - T), so the next count's steps are known from
 * the sum's top byte. A reversal converts: lead += flip, flip = -T_new +
 * T_old. The entries (LatheVectorDir, one per direction) are filled by
 * engage() from the follower's steps, lead and ahead at the index (the
 * count that starts the catch-up, leadscrew.cpp). From then on the
 * follower's residual is stale (no C code reads it: a pass that ends is
 * reset before the next) and its position exact.
 */
#pragma once

/* Offsets in lathe_vector. */
#define LV_MODE 0       /* spindle_encoder::Mode: 0 single, 1 quadrature */
#define LV_KNOWN 1      /* the levels last served, in PIND's bits (A 3, B 2) */
#define LV_LOST 2       /* uint16: doubtful edges */
#define LV_COUNT 4      /* int32: net spindle counts */
#define LV_STATE 8      /* leadscrew::State */
#define LV_AHEAD 9      /* int8: the steps of the next count in direction ahead_dir */
#define LV_AHEAD_DIR 10 /* LV_FORWARD or 0: the last locked count's direction */
#define LV_HAS_END 11   /* bool: the pass has an end */
#define LV_REVERSED 12  /* LV_FORWARD if the pass is reversed, else 0 */
#define LV_DIR_UP 13    /* bool: the direction pin's level (high = +Z) */
#define LV_STOP 14      /* leadscrew::Stop */
#define LV_SLOW_DIR 15  /* the count handed to the C vector: LV_FORWARD or 0 */
#define LV_POS 16       /* int32: the carriage, steps */
#define LV_END 20       /* int32: the pass ends there */
#define LV_LEAD 24      /* int32: R - T (above) */
#define LV_DIR0 28      /* LatheVectorDir for a backward count */
#define LV_DIR1 43      /* ... and a forward one */
#define LV_SIZE 58

/* Offsets in a LatheVectorDir: three 32-bit addends, each followed by the
 * direction's whole steps (the low byte: |whole| <= kMaxStepsPerCount), so
 * that after a chain through Z+ the whole is at Z. */
#define LVD_REM 0    /* rem: lead += rem, a count that does not carry */
#define LVD_NEG_T 5  /* -T: a count that carries */
#define LVD_FLIP 10  /* the lead's conversion into this direction */
#define LVD_SIZE 15

#define FOLLOWER_POS 0 /* am::Follower's position, int32 */

/* Direction codes (LV_AHEAD_DIR, LV_SLOW_DIR, LV_REVERSED). */
#define LV_FORWARD 4
#define LV_FORWARD_BIT 2

/* Values of leadscrew::State and ::Stop the vector writes or compares. */
#define LV_STATE_IDLE 0
#define LV_STATE_CATCHING 3
#define LV_STATE_LOCKED 4
#define LV_STOP_LENGTH 2
#define LV_STOP_LIMIT 3

/* Pins (firmware/boards/common/m16_wiring.h): step PC0, direction PC1,
 * spindle A PD3 (INT1), B PD2 (INT0), limit switch PD7 (low = hit). */
#define LV_STEP_BIT 0
#define LV_DIR_BIT 1
#define LV_A_BIT 3
#define LV_B_BIT 2
#define LV_LIMIT_BIT 7
/* A burst's further pulses: LDI, then 3 cycles a turn but the last, then
 * CBI: 3 x turns + 2 cycles high (32 at 16 MHz, board::kStepHighCycles). */
#define LV_HIGH_TURNS 10

#ifndef __ASSEMBLER__
#include <stddef.h>
#include <stdint.h>

#include "../../../core/lathe/follower.h"
#include "../../devices/spindle_encoder.h"
#include "leadscrew.h"

struct LatheVectorDir {
  uint32_t rem;
  int8_t whole_a;
  uint32_t neg_t;
  int8_t whole_b;
  uint32_t flip;
  int8_t whole_c;
};

struct LatheVector {
  spindle_encoder::State encoder;
  volatile leadscrew::State state;
  int8_t ahead;
  uint8_t ahead_dir;
  bool has_end;
  uint8_t reversed;
  bool dir_up;
  volatile leadscrew::Stop stop;
  uint8_t slow_dir;
  int32_t pos;
  int32_t end;
  int32_t lead;
  LatheVectorDir dir[2];  // [0] backward, [1] forward
};

extern "C" LatheVector lathe_vector;

static_assert(offsetof(LatheVector, encoder) + offsetof(spindle_encoder::State, mode) == LV_MODE, "layout");
static_assert(offsetof(LatheVector, encoder) + offsetof(spindle_encoder::State, known) == LV_KNOWN, "layout");
static_assert(offsetof(LatheVector, encoder) + offsetof(spindle_encoder::State, lost) == LV_LOST, "layout");
static_assert(offsetof(LatheVector, encoder) + offsetof(spindle_encoder::State, count) == LV_COUNT, "layout");
static_assert(sizeof(spindle_encoder::Mode) == 1 && uint8_t(spindle_encoder::Mode::single) == 0, "mode");
static_assert(offsetof(LatheVector, state) == LV_STATE, "layout");
static_assert(offsetof(LatheVector, ahead) == LV_AHEAD, "layout");
static_assert(offsetof(LatheVector, ahead_dir) == LV_AHEAD_DIR, "layout");
static_assert(offsetof(LatheVector, has_end) == LV_HAS_END, "layout");
static_assert(offsetof(LatheVector, reversed) == LV_REVERSED, "layout");
static_assert(offsetof(LatheVector, dir_up) == LV_DIR_UP, "layout");
static_assert(offsetof(LatheVector, stop) == LV_STOP, "layout");
static_assert(offsetof(LatheVector, slow_dir) == LV_SLOW_DIR, "layout");
static_assert(offsetof(LatheVector, pos) == LV_POS, "layout");
static_assert(offsetof(LatheVector, end) == LV_END, "layout");
static_assert(offsetof(LatheVector, lead) == LV_LEAD, "layout");
static_assert(offsetof(LatheVector, dir) == LV_DIR0, "layout");
static_assert(offsetof(LatheVector, dir) + sizeof(LatheVectorDir) == LV_DIR1, "layout");
static_assert(sizeof(LatheVector) == LV_SIZE, "layout");
static_assert(offsetof(LatheVectorDir, rem) == LVD_REM && offsetof(LatheVectorDir, whole_a) == LVD_REM + 4, "layout");
static_assert(offsetof(LatheVectorDir, neg_t) == LVD_NEG_T && offsetof(LatheVectorDir, whole_b) == LVD_NEG_T + 4,
              "layout");
static_assert(offsetof(LatheVectorDir, flip) == LVD_FLIP && offsetof(LatheVectorDir, whole_c) == LVD_FLIP + 4,
              "layout");
static_assert(sizeof(LatheVectorDir) == LVD_SIZE, "layout");
static_assert(sizeof(bool) == 1 && sizeof(leadscrew::State) == 1 && sizeof(leadscrew::Stop) == 1, "layout");
static_assert(uint8_t(leadscrew::State::idle) == LV_STATE_IDLE && uint8_t(leadscrew::State::locked) == LV_STATE_LOCKED &&
                  uint8_t(leadscrew::State::catching) == LV_STATE_CATCHING,
              "states");
static_assert(uint8_t(leadscrew::Stop::length) == LV_STOP_LENGTH && uint8_t(leadscrew::Stop::limit) == LV_STOP_LIMIT,
              "stops");
static_assert(LV_FORWARD == 1 << LV_FORWARD_BIT && LV_FORWARD == 1 << LV_B_BIT && 1 << LV_A_BIT == LV_FORWARD << 1,
              "the decode shifts A's level onto B's bit");

namespace am {
// The follower's internals the vector and its set-up use (a friend of
// am::Follower).
struct FollowerVectorAccess {
  static_assert(offsetof(Follower, pos_) == FOLLOWER_POS && sizeof(Follower::pos_) == 4, "layout");
  static uint32_t whole(const Follower& f, uint8_t i) { return f.step_[i].whole; }
  static uint32_t rem(const Follower& f, uint8_t i) { return f.step_[i].rem; }
  static uint32_t den(const Follower& f) { return f.den_; }
  static uint32_t residual(const Follower& f) { return f.residual_; }
};
}  // namespace am
#endif
