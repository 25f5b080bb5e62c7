// A picture of a run: each axis's position against time, as an SVG file
// (any browser shows it). One polyline per axis, sampled at every step event.
#pragma once
#include <string>

#include "machine.h"

namespace sim {

void write_position_plot(const std::string& path, const Machine& m);

}  // namespace sim
