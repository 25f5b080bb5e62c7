// The interpreter's printer codes (core/text/gcode_printer_codes.h): each
// code's words into its slots, every refusal with the state untouched, the
// codes absent from an interpreter without them, and M221's flow against an
// integer model of its rule over a sweep of flows and extruder moves.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "core/text/gcode_interpreter.h"

using am::GcodeError;

namespace {

// A printer's axes, steps per metre: X Y at 80 steps/mm, Z at 400, E at 93
// (an i3's), and a fourth at the seed's 1000 would do as well.
const am::GcodeAxis kPrinter[] = {{'X', 0, 80000}, {'Y', 0, 80000}, {'Z', 0, 400000}, {'E', 0, 93000}};
using Printer = am::GcodeInterpreter<4, false, true, true, false>;  // the m32 Marlin image's
using NoPrinter = am::GcodeInterpreter<4, false, true, true, false, false>;  // the m32-grbl image's
using Action = am::GcodeAction<4>;

struct Ran {
  GcodeError error;
  Action action;
};

template <typename I>
Ran run(I& g, const std::string& line) {
  Ran r;
  r.error = g.run(line.c_str(), r.action);
  return r;
}

TEST(GcodePrinterCodes, EachCodeFillsItsSlots) {
  Printer g(kPrinter);
  Ran r = run(g, "M201 X3000 Y2500.5 E10000");
  ASSERT_EQ(r.error, GcodeError::none);
  EXPECT_EQ(r.action.kind, am::GcodeActionKind::printer);
  EXPECT_EQ(r.action.printer.code, am::GcodeCode::m201);
  EXPECT_EQ(r.action.printer.given, 0x0B);  // X Y E
  EXPECT_EQ(r.action.printer.value[0], 30000000);
  EXPECT_EQ(r.action.printer.value[1], 25005000);
  EXPECT_EQ(r.action.printer.value[3], 100000000);

  r = run(g, "M203 Z12");
  ASSERT_EQ(r.error, GcodeError::none);
  EXPECT_EQ(r.action.printer.code, am::GcodeCode::m203);
  EXPECT_EQ(r.action.printer.given, 0x04);
  EXPECT_EQ(r.action.printer.value[2], 120000);

  r = run(g, "M204 P1500 R1000 T3000 S800");
  ASSERT_EQ(r.error, GcodeError::none);
  EXPECT_EQ(r.action.printer.given, 0x0F);
  EXPECT_EQ(r.action.printer.value[0], 15000000);
  EXPECT_EQ(r.action.printer.value[1], 30000000);
  EXPECT_EQ(r.action.printer.value[2], 10000000);
  EXPECT_EQ(r.action.printer.value[3], 8000000);

  r = run(g, "M205 X10 Y10 Z0.4 E4.5 S0 T0 B20000 J0.02");  // PrusaSlicer's words, one line
  ASSERT_EQ(r.error, GcodeError::none);
  EXPECT_EQ(r.action.printer.given, 0x01);
  EXPECT_EQ(r.action.printer.value[0], 200);
  r = run(g, "M205 X8 Y8");
  ASSERT_EQ(r.error, GcodeError::none);
  EXPECT_EQ(r.action.printer.given, 0x00);

  r = run(g, "M73 P42 R17");
  ASSERT_EQ(r.error, GcodeError::none);
  EXPECT_EQ(r.action.printer.given, 0x03);
  EXPECT_EQ(r.action.printer.value[0], 42);
  EXPECT_EQ(r.action.printer.value[1], 17);
  r = run(g, "M73 Q42 S17");
  ASSERT_EQ(r.error, GcodeError::none);
  EXPECT_EQ(r.action.printer.given, 0x00);

  for (const char* line : {"M220 S10", "M221 S500"}) {
    r = run(g, line);
    ASSERT_EQ(r.error, GcodeError::none) << line;
    EXPECT_EQ(r.action.printer.given, 0x01);
    EXPECT_EQ(r.action.printer.value[0], std::atoi(line + 6)) << line;
  }
  r = run(g, "N7 M220");
  ASSERT_EQ(r.error, GcodeError::none);
  EXPECT_EQ(r.action.printer.given, 0x00);
}

// Every refusal, and nothing changes (the positions a line holds are kept).
TEST(GcodePrinterCodes, RefusalsChangeNothing) {
  Printer g(kPrinter);
  ASSERT_EQ(run(g, "G1 X10 E2 F600").error, GcodeError::none);
  const am::GcodeState<4> before = g.state();
  const struct {
    const char* line;
    GcodeError e;
  } rows[] = {
      {"M201 X0", GcodeError::bad_limit},       {"M201 E-1", GcodeError::bad_limit},
      {"M203 Y0", GcodeError::bad_limit},       {"M204 S0", GcodeError::bad_limit},
      {"M204 P1000 T-5", GcodeError::bad_limit}, {"M205 J0.0009", GcodeError::bad_limit},
      {"M205 J10.0001", GcodeError::bad_limit}, {"M73 P101", GcodeError::bad_percent},
      {"M73 P-1", GcodeError::bad_percent},     {"M73 P50.5", GcodeError::bad_percent},
      {"M73 R2.5", GcodeError::bad_percent},    {"M73 R-1", GcodeError::bad_percent},
      {"M220 S9", GcodeError::bad_percent},     {"M220 S501", GcodeError::bad_percent},
      {"M221 S99.5", GcodeError::bad_percent},  {"M221 S0", GcodeError::bad_percent},
      {"M201 P100", GcodeError::unused_word},   {"M203 J1", GcodeError::unused_word},
      {"M204 X100", GcodeError::unused_word},   {"M205 P1", GcodeError::unused_word},
      {"M73 X1", GcodeError::unused_word},      {"M220 T0", GcodeError::unused_word},
      {"M221 E1", GcodeError::unused_word},     {"G1 X1 M220 S100", GcodeError::heater_code_alone},
      {"G90 M204 S100", GcodeError::heater_code_alone}, {"M220 M221", GcodeError::modal_group_conflict},
  };
  for (const auto& row : rows) {
    EXPECT_EQ(run(g, row.line).error, row.e) << row.line;
    const am::GcodeState<4>& after = g.state();
    for (uint8_t i = 0; i < 4; ++i) {
      EXPECT_EQ(after.axis[i].coord, before.axis[i].coord) << row.line;
      EXPECT_EQ(after.axis[i].steps, before.axis[i].steps) << row.line;
      EXPECT_EQ(after.axis[i].offset, before.axis[i].offset) << row.line;
    }
    EXPECT_EQ(g.flow(), 100);
  }
  // Accepted, the codes do not move anything either.
  for (const char* line : {"M201 X100", "M203 X1", "M204 S1", "M205 J1", "M73 P1", "M220 S100", "M221 S100"}) {
    const Ran r = run(g, line);
    ASSERT_EQ(r.error, GcodeError::none) << line;
    EXPECT_EQ(r.action.axes, 0) << line;
    for (uint8_t i = 0; i < 4; ++i) {
      EXPECT_EQ(r.action.target[i], before.axis[i].steps) << line;
      EXPECT_EQ(r.action.coord[i], before.axis[i].coord) << line;
    }
  }
}

// The seed's M3 S<C> / M5: the hot end on at S, as M104; off, as M104 S0.
TEST(GcodePrinterCodes, TheSeedsM3AndM5AreTheHotEndOnAndOff) {
  Printer g(kPrinter);
  Ran r = run(g, "M3 S215.5");
  ASSERT_EQ(r.error, GcodeError::none);
  EXPECT_EQ(r.action.kind, am::GcodeActionKind::heater);
  EXPECT_EQ(r.action.heater.code, am::GcodeCode::m104);
  EXPECT_EQ(r.action.heater.target, 21550);
  r = run(g, "M5");
  ASSERT_EQ(r.error, GcodeError::none);
  EXPECT_EQ(r.action.heater.code, am::GcodeCode::m104);
  EXPECT_EQ(r.action.heater.target, 0);
  EXPECT_EQ(run(g, "M3").error, GcodeError::missing_temperature);
  EXPECT_EQ(run(g, "M3 S261").error, GcodeError::bad_temperature);
  EXPECT_EQ(run(g, "M5 S100").error, GcodeError::unused_word);
  EXPECT_EQ(run(g, "G1 X1 M3 S100").error, GcodeError::heater_code_alone);
  NoPrinter without(kPrinter);
  EXPECT_EQ(run(without, "M3 S200").error, GcodeError::unsupported_code);
  EXPECT_EQ(run(without, "M5").error, GcodeError::unsupported_code);
}

TEST(GcodePrinterCodes, AnInterpreterWithoutThemRefusesThem) {
  NoPrinter g(kPrinter);
  for (const char* line : {"M73 P1", "M201 X100", "M203 X1", "M204 S1", "M205 J1", "M220 S100", "M221 S100"})
    EXPECT_EQ(run(g, line).error, GcodeError::unsupported_code) << line;
  EXPECT_EQ(run(g, "M104 S200").error, GcodeError::none);  // the heater's stay
  am::GcodeInterpreter<4, false, false> no_heater(kPrinter);
  EXPECT_EQ(run(no_heater, "M221 S95").error, GcodeError::unsupported_code);
}

int64_t round_half_away(int64_t v, int64_t d) { return v >= 0 ? (v + d / 2) / d : -((-v + d / 2) / d); }

// M221: each move's E steps are its unflowed distance in steps times flow /
// 100, half away from zero; the program position is the program's. The
// model keeps the unflowed target from the coordinates alone.
TEST(GcodePrinterCodes, FlowScalesEveryExtruderMoveAndKeepsTheProgramPosition) {
  const uint32_t spm = kPrinter[3].steps_per_m;
  long moves = 0;
  for (uint16_t flow : {10, 33, 95, 99, 100, 101, 107, 150, 333, 500}) {
    Printer g(kPrinter);
    ASSERT_EQ(run(g, "G1 F1800").error, GcodeError::none);
    ASSERT_EQ(run(g, "M221 S" + std::to_string(flow)).error, GcodeError::none);
    g.set_flow(flow);  // the machine's part (firmware/services/printer_codes.cpp)
    int64_t coord = 0, base = 0, machine = 0;  // 1/10000 mm; unflowed steps of coord; machine steps
    uint32_t seed = flow * 2654435761u;
    for (int k = 0; k < 400; ++k) {
      seed = seed * 1103515245u + 12345u;
      const bool relative = (seed >> 8) % 3 == 0, reset = (seed >> 12) % 17 == 0;
      const int64_t step = int64_t((seed >> 16) % 40001) - 8000;  // -0.8 .. 3.2 mm, fifth-decimal noise
      std::string line;
      if (reset) {
        line = "G92 E0";
        coord = 0;
        base = 0;  // steps = length_to_steps(0) + offset: the offset takes the machine position
      } else {
        const int64_t to = relative ? step : coord + step;
        ASSERT_EQ(run(g, relative ? "M83" : "M82").error, GcodeError::none);
        char buf[40];
        std::snprintf(buf, sizeof buf, "G1 E%s%lld.%04lld", to < 0 ? "-" : "", (long long)(std::llabs(to) / 10000),
                      (long long)(std::llabs(to) % 10000));
        line = buf;
        const int64_t new_coord = relative ? coord + step : to;
        const int64_t new_base = round_half_away(new_coord * spm, 10000000);
        machine += round_half_away((new_base - base) * flow, 100);
        coord = new_coord;
        base = new_base;
        ++moves;
      }
      const Ran r = run(g, line);
      ASSERT_EQ(r.error, GcodeError::none) << line;
      EXPECT_EQ(g.state().axis[3].coord, coord) << line << " flow " << flow;
      EXPECT_EQ(g.state().axis[3].steps, machine) << line << " flow " << flow;
      if (!reset) {
        EXPECT_EQ(r.action.target[3], machine) << line;
      }
    }
  }
  EXPECT_GE(moves, 3500);
}

// Flow touches E alone: X Y Z of the same moves are the unflowed steps.
TEST(GcodePrinterCodes, FlowLeavesTheOtherAxesAlone) {
  Printer g(kPrinter);
  g.set_flow(250);
  ASSERT_EQ(run(g, "G1 X10.0125 Y-3.3333 Z0.2 E1 F600").error, GcodeError::none);
  EXPECT_EQ(g.state().axis[0].steps, 801);
  EXPECT_EQ(g.state().axis[1].steps, -267);
  EXPECT_EQ(g.state().axis[2].steps, 80);
  EXPECT_EQ(g.state().axis[3].steps, 233);  // 93 steps/mm x 2.5, 232.5 half away
}

}  // namespace
