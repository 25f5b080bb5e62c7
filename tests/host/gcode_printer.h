// The printer the G-code interpreter tests run lines on
// (test_gcode_interpreter.cpp, test_gcode_interpreter_functions.cpp), and
// running a line that must be accepted.
#pragma once
#include <gtest/gtest.h>

#include "core/text/gcode_interpreter.h"

namespace gcodetest {

using am::GcodeError;

// A printer: 80 steps/mm on X and Y, 400 on Z, 93 on E.
const am::GcodeAxis kPrinter[] = {{'X', 0, 80000}, {'Y', 0, 80000}, {'Z', 0, 400000}, {'E', 0, 93000}};
using Printer = am::GcodeInterpreter<4>;
using Action = am::GcodeAction<4>;

inline GcodeError run(Printer& g, const char* line, Action& a) { return g.run(line, a); }
inline Action ok(Printer& g, const char* line) {
  Action a;
  const GcodeError e = g.run(line, a);
  EXPECT_EQ(e, GcodeError::none) << line << ": " << am::gcode_error_message(e);
  return a;
}

}  // namespace gcodetest
