// The one accepted line that waits for its turn (protocol.cpp): a direct
// command or a G-code line's action, never both at once, so the two share
// their RAM (the command's 41 bytes: the m32-cnc's R arc needs every byte
// of its stack). Only a board with G-code links it.
#pragma once
#include "../../../core/text/command_parser.h"
#include "../../../core/text/gcode_interpreter.h"
#include "../../board.h"

namespace pending {

union Line {
  am::Command command;
  am::GcodeAction<board::Axes::count> action;
};

extern Line line;

}  // namespace pending
