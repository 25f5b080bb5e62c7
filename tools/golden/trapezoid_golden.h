// The trapezoid generator's golden schedules (core/motion/trapezoid.h): the
// hashes of every StepRun of 16 fixed blocks and of 3000 pseudo-random
// blocks chained through exit_speed(), as the chip computes them.
//
// The host test (tests/host/test_trapezoid_parts.cpp, TrapezoidBitIdentity) must
// reproduce them bit for bit: any float expression rounded differently (an
// a * b + c fused on a host with FMA, x87 evaluation, -ffast-math, a double
// literal) changes them. A change of the generator changes them too: then
// they are recomputed on the chip, never copied from the host:
// tools/golden/run.sh builds tools/golden/chip.cpp with avr-gcc 5.4 -Os for
// an ATmega328P (avr-libc's float routines), runs it in simavr and prints
// the values to paste below.
#pragma once
#include <stdint.h>
#include <string.h>

#include "../../core/motion/trapezoid.h"

namespace am {
namespace golden {

struct Block {
  TrapezoidBlock b;
  uint32_t tick_hz, hash;
};

const Block kBlocks[] = {
    {{65000, 0, 160000, 0, 400000}, 16000000, 0xf15b94b2},
    {{2500, 0, 40000, 0, 800000}, 16000000, 0x9d7c9837},
    {{5000, 0, 20000, 300, 40000}, 16000000, 0x882f2545},
    {{100, 1000, 1000, 0, 1000}, 16000000, 0xf866edaf},
    {{100, 0, 5000, 5000, 1000}, 20000000, 0x148aa01b},
    {{1000, 7000, 7000, 9000, 50000}, 16000000, 0x3d7846a1},
    {{50, 0, 250000, 0, 10}, 16000000, 0xdde3e305},
    {{3, 12345.6f, 12345.6f, 12345.6f, 1000}, 8000000, 0x78fa049f},
    {{40000, 0, 250000, 0, 2e6f}, 16000000, 0x9439b1d7},
    {{19, 0.37f * 77.7f, 77.7f, 0.81f * 77.7f, 517}, 20000000, 0xbea51111},
    {{4000, 0.9f * 99999, 99999, 0.05f * 99999, 33333}, 8000000, 0xa7fb73ba},
    {{250, 0, 12345.6f, 12345.6f, 1.5e8f}, 16000000, 0xcd872dfc},
    {{60000, 3000, 250000, 2000, 10}, 16000000, 0x01582291},
    {{7, 0, 10, 0, 10}, 16000000, 0xb3ccabd3},
    {{120000, 240000, 250000, 0, 31000}, 20000000, 0xc52854de},
    {{15000, 5, 250000, 77, 99.9f}, 8000000, 0xdfb64185},
};
constexpr uint32_t kChainStepRuns = 454658u;
constexpr uint32_t kChainHash = 0x4adb28e7u;

inline uint32_t mix(uint32_t h, uint32_t v) { return (h ^ v) * 16777619u; }
inline uint32_t float_bits(float x) {
  uint32_t u;
  memcpy(&u, &x, sizeof u);
  return u;
}

// FNV-1a style over (interval, count) of every run, then the exit speed.
inline uint32_t hash_block(const TrapezoidBlock& b, uint32_t tick_hz) {
  TrapezoidRuns runs;
  if (!runs.start(b, tick_hz)) return 0;
  uint32_t h = 2166136261u;
  for (StepRun r = runs.next_run(); r.count; r = runs.next_run()) h = mix(mix(h, r.interval), r.count);
  return mix(h, float_bits(runs.exit_speed()));
}

// The chain's blocks, from integer operations and float multiplications
// only (the same on both).
struct ChainGen {
  uint32_t s = 2463534242u;
  uint32_t next() {
    s ^= s << 13;
    s ^= s >> 17;
    s ^= s << 5;
    return s;
  }
  float between(uint32_t lo, uint32_t hi) {  // a random significand, biased exponent in [lo, hi]
    const uint32_t e = lo + next() % (hi - lo + 1), u = (e << 23) | (next() & 0x7FFFFF);
    float x;
    memcpy(&x, &u, sizeof x);
    return x;
  }
};

struct ChainHash {
  uint32_t step_runs, hash;
};

inline ChainHash hash_chain() {
  const uint32_t kHz[] = {16000000, 8000000, 20000000};
  ChainGen gen;
  TrapezoidRuns runs;
  float entry = 0;
  ChainHash out{0, 2166136261u};
  const int kBlocks = 3000;
  for (int i = 0; i < kBlocks; ++i) {
    const float cruise = gen.between(130, 144);  // 8 .. 65536 events/s
    const float accel = gen.between(131, 150);   // 16 .. 2^24 events/s^2
    const uint32_t n = 1 + gen.next() % (1u << (gen.next() % 13));
    const float exit = i + 1 == kBlocks ? 0 : cruise * gen.between(120, 126);
    const uint32_t tick_hz = kHz[gen.next() % 3];
    if (!runs.start({n, entry, cruise, exit, accel}, tick_hz)) {
      out.hash = mix(out.hash, 0xDEAD);
      continue;
    }
    for (StepRun r = runs.next_run(); r.count; r = runs.next_run(), ++out.step_runs)
      out.hash = mix(mix(out.hash, r.interval), r.count);
    entry = runs.exit_speed();
    out.hash = mix(out.hash, float_bits(entry));
  }
  return out;
}

}  // namespace golden
}  // namespace am
