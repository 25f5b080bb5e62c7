#include "lathe_check.h"

#include <algorithm>

namespace sim {

namespace {

using i128 = __int128;

i128 floor_div(i128 a, i128 b) {
  i128 q = a / b;
  if ((a % b != 0) && ((a < 0) != (b < 0))) --q;
  return q;
}

}  // namespace

int64_t target_steps(const ThreadSpec& t, int64_t s) {
  // lead (s - kC/n) S / (C L) = pitch n (n s - k C) / n x S / (C L)
  //                           = pitch_num (n s - k C) S screw_den / (pitch_den C screw_num)
  const i128 num = i128(t.pitch_num) * (i128(t.starts) * s - i128(t.start) * t.counts_per_turn) * t.steps_per_turn *
                   t.screw_den;
  const i128 den = i128(t.pitch_den) * t.counts_per_turn * t.screw_num;
  return int64_t(floor_div(t.right_hand ? -num : num, den));
}

namespace {

// position_at() for many cycles: the running sums once.
struct Positions {
  explicit Positions(const AxisTrace& a) : axis(a), sum(a.step_deltas.size() + 1, 0) {
    for (size_t k = 0; k < a.step_deltas.size(); ++k) sum[k + 1] = sum[k] + a.step_deltas[k];
  }
  int64_t at(uint64_t cycle) const {
    return sum[size_t(std::upper_bound(axis.step_cycles.begin(), axis.step_cycles.end(), cycle) -
                      axis.step_cycles.begin())];
  }
  const AxisTrace& axis;
  std::vector<int64_t> sum;
};

}  // namespace

PulseTiming pulse_timing(const std::vector<PinEdge>& step, const std::vector<PinEdge>& dir) {
  PulseTiming t;
  auto lower = [](uint64_t& min, uint64_t v) {
    if (min == 0 || v < min) min = v;
  };
  uint64_t rise = 0, fall = 0, dir_change = 0;
  bool high = false, dir_pending = false;
  size_t d = 0;
  for (const PinEdge& e : step) {
    for (; d < dir.size() && dir[d].cycle <= e.cycle; ++d) {
      if (high) t.dir_changed_in_pulse = true;
      dir_change = dir[d].cycle;
      dir_pending = true;
      ++t.dir_changes;
    }
    if (e.level) {
      if (fall) lower(t.min_low, e.cycle - fall);
      if (dir_pending) lower(t.min_dir_setup, e.cycle - dir_change);
      dir_pending = false;
      rise = e.cycle;
      high = true;
      ++t.pulses;
    } else if (high) {
      lower(t.min_high, e.cycle - rise);
      fall = e.cycle;
      high = false;
    }
  }
  return t;
}

PassResult check_pass(const SpindleEncoder& spindle, const AxisTrace& axis, const std::vector<PinEdge>& step_pin,
                      const ThreadSpec& t, int64_t base, uint64_t armed, uint64_t until, const int64_t* end) {
  PassResult r;
  const std::vector<SpindleTransition>& log = spindle.log();
  size_t i = 0;
  while (i < log.size() && (log[i].cycle < armed || !log[i].count)) ++i;
  // The firmware arms with the index taken as high: a count reading it low
  // first, then the one reading it high.
  bool seen_low = false;
  for (; i < log.size() && log[i].cycle < until; ++i) {
    if (!log[i].count) continue;
    if (!log[i].index) seen_low = true;
    else if (seen_low) break;
  }
  if (i >= log.size() || log[i].cycle >= until) return r;
  r.index_found = true;
  r.index_cycle = log[i].cycle;
  const bool quadrature = spindle.phases_per_turn() % 4 == 0 && t.counts_per_turn == spindle.phases_per_turn();

  // Counts after the index: cycle and net count.
  std::vector<std::pair<uint64_t, int64_t>> counts;
  int64_t s = 0, last_phase = log[i].phase;
  for (size_t k = i + 1; k < log.size() && log[k].cycle < until; ++k) {
    if (!log[k].count) continue;
    s += quadrature ? (log[k].phase > last_phase ? 1 : -1) : 1;
    last_phase = log[k].phase;
    counts.push_back({log[k].cycle, s});
  }
  // The pass's end: the first cycle the position reaches *end.
  uint64_t end_cycle = until;
  if (end) {
    int64_t p = 0;
    for (size_t k = 0; k < axis.step_cycles.size(); ++k) {
      p += axis.step_deltas[k];
      if (axis.step_cycles[k] >= r.index_cycle && p == *end) {
        end_cycle = axis.step_cycles[k];
        break;
      }
    }
  }
  const Positions pos(axis);
  // Position just before each next count (or at the end).
  std::vector<bool> match;
  std::vector<int64_t> expect;
  for (size_t k = 0; k < counts.size(); ++k) {
    if (counts[k].first > end_cycle) break;
    const uint64_t next = k + 1 < counts.size() ? std::min(counts[k + 1].first, end_cycle + 1) : until;
    int64_t want = base + target_steps(t, counts[k].second);
    if (end && (*end < base ? want < *end : want > *end)) want = *end;  // the pass stops there
    expect.push_back(want);
    match.push_back(pos.at(next - 1) == want);
  }
  r.counts = match.size();
  size_t lock = match.size();
  while (lock > 0 && match[lock - 1]) --lock;
  r.locked = lock < match.size();
  r.locked_after = lock;
  if (r.locked) r.lock_cycles = counts[lock].first - r.index_cycle;
  for (size_t k = lock; k < match.size(); ++k) r.mismatches += match[k] ? 0 : 1;
  r.s_end = counts.empty() ? 0 : counts[r.counts ? r.counts - 1 : 0].second;
  r.position = pos.at(end_cycle);
  r.expected = base + target_steps(t, r.s_end);
  if (end) {
    const int64_t e = *end;
    const bool up = e > base;
    if (up ? r.expected > e : r.expected < e) r.expected = e;
  }
  // Latency: a locked count whose target moved, to the first step rise after it.
  size_t rise = 0;
  for (size_t k = lock + 1; k < r.counts; ++k) {
    if (expect[k] == expect[k - 1]) continue;
    while (rise < step_pin.size() && (!step_pin[rise].level || step_pin[rise].cycle < counts[k].first)) ++rise;
    if (rise == step_pin.size()) break;
    r.max_latency = std::max(r.max_latency, step_pin[rise].cycle - counts[k].first);
    ++r.latency_samples;
  }
  return r;
}

}  // namespace sim
