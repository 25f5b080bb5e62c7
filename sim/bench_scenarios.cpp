#include <cstring>

#include "bench.h"

namespace bench {

const std::vector<Table>& engine_tables() {
  static const std::vector<Table> tables = {
      {"Uno axis Z, hardware-timed STEP (OC1A), ramp planned on the chip, 300000 steps/s^2\n"
       "(whole move, ramps included: irq cyc/st counts every interrupt from the first step to the\n"
       " last, response and RETI included, per step; spread is the max - min lateness of the steps\n"
       " against the planned schedule; doubled counts intervals > 1.5 x their scheduled interval)",
       "axis Z, hardware-timed STEP on OC1A (D9), 300000 steps/s^2", "uno Z, timer-pulsed STEP",
       {{"uno", 'Z', 50000, 300000, 60000, 'B', 1},
        {"uno", 'Z', 100000, 300000, 80000, 'B', 1},
        {"uno", 'Z', 150000, 300000, 100000, 'B', 1},
        {"uno", 'Z', 160000, 300000, 100000, 'B', 1},
        {"uno", 'Z', 250000, 300000, 100000, 'B', 1}}},
      // The m32's axes on its direct-control image (the printer and the mill
      // have no MOVE).
      {"m32 axis X, software STEP pulse (GPIO in the interrupt), 200000 steps/s^2",
       "axis X, software STEP pulse (GPIO in the interrupt), 200000 steps/s^2", "m32 X, software STEP pulse",
       {{"m32-direct", 'X', 10000, 200000, 20000, 0, 0},
        {"m32-direct", 'X', 40000, 200000, 40000, 0, 0},
        {"m32-direct", 'X', 80000, 200000, 40000, 0, 0}}},
      {"m32 axes X Y Z (and E), one coordinated diagonal block, software STEP pulses, 200000 steps/s^2\n"
       "(figures per step of the dominant axis X; every axis steps at every one of its steps; at 1000\n"
       " and 2000 steps/s the block is smoothed, 8 and 4 interrupts a step: docs/step-engine.md)",
       "axes X Y Z (E), one coordinated diagonal block, software STEP pulses, 200000 steps/s^2",
       "m32 XYZ(E), coordinated",
       {{"m32-direct", 'X', 1000, 200000, 3000, 0, 0, "YZ", 40000},
        {"m32-direct", 'X', 2000, 200000, 6000, 0, 0, "YZ", 40000},
        {"m32-direct", 'X', 10000, 200000, 20000, 0, 0, "YZ", 40000},
        {"m32-direct", 'X', 40000, 200000, 40000, 0, 0, "YZ", 40000},
        {"m32-direct", 'X', 40000, 200000, 40000, 0, 0, "YZE", 40000}}},
      {"Uno axis X, Motor Shield latch (two-phase), 20000 steps/s^2",
       "axis X, Adafruit Motor Shield v1 latch (74HC595, two-phase), 20000 steps/s^2", "uno X, shield latch",
       {{"uno", 'X', 2000, 20000, 4000, 0, 0}, {"uno", 'X', 20000, 20000, 20000, 0, 0}}},
  };
  return tables;
}

const char* const kSizeImages[13] = {"uno",       "uno-grbl",  "m32",       "m32-i3",   "m32-grbl",
                                     "m32-cnc",   "m32-direct", "m32-driver", "m1284",   "m16",
                                     "m16-8mhz",  "m16-lathe", "m16-servo"};

// Flash an image may fill: the Uno's bootloader keeps 512 of the 328P's
// 32768 bytes (firmware/CMakeLists.txt fails the link beyond).
const PartSize kParts[4] = {
    {"atmega328p", 32256, 2048}, {"atmega32", 32768, 2048}, {"atmega1284p", 131072, 16384}, {"atmega16", 16384, 1024}};

const PartSize* part_of(const char* mcu) {
  for (const PartSize& p : kParts) {
    if (!std::strcmp(p.mcu, mcu)) return &p;
  }
  return nullptr;
}

std::string move_line(const Scenario& s) {
  std::string line = std::string("MOVE ") + s.axis + std::to_string(s.steps);
  for (const char* a = s.also; *a; ++a) line += std::string(" ") + *a + std::to_string(s.steps);
  return line + " F" + std::to_string(s.rate) + " A" + std::to_string(s.accel);
}

}  // namespace bench
