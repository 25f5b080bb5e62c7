#include "axis_decoder.h"

#include <algorithm>
#include <cstddef>

#include "../core/motor/shield_wiring.h"

namespace sim {

uint64_t AxisTrace::min_interval() const {
  uint64_t best = 0;
  for (std::size_t i = 1; i < step_cycles.size(); ++i) {
    const uint64_t d = step_cycles[i] - step_cycles[i - 1];
    if (best == 0 || d < best) best = d;
  }
  return best;
}

void StepDirDecoder::on_step(bool level, uint64_t cycle) {
  if (level && !step_level_) trace_->add_step(cycle, forward_ ? 1 : -1);
  step_level_ = level;
}

void CoilDecoder::on_pattern(uint8_t pattern, uint64_t cycle) {
  const int index = am::half_step_index(pattern);
  if (index < 0) return;  // coils off or a transient mix: the rotor stays
  if (index_ < 0) {
    index_ = index;  // first energised state: the reference
    return;
  }
  const int delta = (index - index_ + 8) % 8;
  if (delta == 0) return;
  index_ = index;
  if (delta == 4) {
    ++trace_->decode_errors;
    return;
  }
  trace_->add_step(cycle, delta < 4 ? delta : delta - 8);
}

void Latch595Model::on_clock(bool level, bool data) {
  if (level && !clock_) shift_ = uint8_t((shift_ << 1) | (data ? 1 : 0));
  clock_ = level;
}

bool Latch595Model::on_latch(bool level, uint64_t cycle) {
  const bool rising = level && !latch_;
  latch_ = level;
  if (!rising) return false;
  const bool changed = storage_ != shift_;
  storage_ = shift_;
  history_.push_back({cycle, storage_});
  return changed && output_enabled_;
}

bool Latch595Model::on_enable(bool level) {
  const bool enabled = !level;
  const bool changed = enabled != output_enabled_;
  output_enabled_ = enabled;
  return changed;
}

int64_t position_at(const AxisTrace& axis, uint64_t cycle) {
  const auto it = std::upper_bound(axis.step_cycles.begin(), axis.step_cycles.end(), cycle);
  int64_t p = 0;
  for (auto k = axis.step_cycles.begin(); k != it; ++k) p += axis.step_deltas[size_t(k - axis.step_cycles.begin())];
  return p;
}

bool motion_span(const std::vector<AxisTrace>& axes, uint64_t from, uint64_t to, uint64_t& first, uint64_t& last) {
  first = UINT64_MAX;
  last = 0;
  for (const AxisTrace& a : axes) {
    for (const uint64_t c : a.step_cycles) {
      if (c >= from && c < first) first = c;
      if (c <= to && c > last) last = c;
    }
  }
  return first < last;
}

}  // namespace sim
