// The slicer-style time estimate (print_estimate.h).
#include "print_estimate.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace sim {

int MachineLimits::index(char name) const {
  for (size_t i = 0; i < axes.size(); ++i)
    if (axes[i].name == name) return int(i);
  return -1;
}

std::string MachineLimits::describe() const {
  std::string out;
  char buf[128];
  for (const AxisLimit& a : axes) {
    std::snprintf(buf, sizeof buf, "%s%c %g steps/mm %g mm/s %g mm/s^2", out.empty() ? "" : ", ", a.name,
                  a.steps_per_mm, a.max_rate_mm_s, a.accel_mm_s2);
    out += buf;
  }
  if (print_accel > 0 || travel_accel > 0 || retract_accel > 0) {
    std::snprintf(buf, sizeof buf, ", path acceleration P %g T %g R %g mm/s^2", print_accel, travel_accel, retract_accel);
    out += buf;
  }
  std::snprintf(buf, sizeof buf, ", junction deviation %g mm", junction_mm);
  return out + buf;
}

void TimeEstimator::move(const std::vector<double>& d, double feed, bool rapid) {
  const size_t n = l_.axes.size();
  double path2 = 0, other2 = 0, dominant_steps = 0;
  for (size_t i = 0; i < n; ++i) {
    (l_.axes[i].in_path ? path2 : other2) += d[i] * d[i];
    dominant_steps = std::max(dominant_steps, std::fabs(d[i]) * l_.axes[i].steps_per_mm);
  }
  if (path2 == 0 && other2 == 0) return;
  ++moves_;
  Block b;
  b.path = path2 > 0;
  b.length = std::sqrt(b.path ? path2 : other2);
  double cruise = rapid ? std::numeric_limits<double>::infinity() : feed / 60;
  b.accel = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < n; ++i) {
    const double share = std::fabs(d[i]) / b.length;  // the axis's mm per mm of the block
    if (share == 0) continue;
    cruise = std::min(cruise, l_.axes[i].max_rate_mm_s / share);
    b.accel = std::min(b.accel, l_.axes[i].accel_mm_s2 / share);
  }
  double e = 0;
  for (size_t i = 0; i < n; ++i)
    if (l_.axes[i].name == 'E') e = d[i];
  const double cap = !b.path ? l_.retract_accel : e != 0 ? l_.print_accel : l_.travel_accel;
  if (cap > 0) b.accel = std::min(b.accel, cap);
  if (l_.max_event_rate > 0) cruise = std::min(cruise, l_.max_event_rate * b.length / dominant_steps);
  b.cruise2 = cruise * cruise;
  b.max_entry2 = 0;
  std::vector<double> unit;
  if (b.path) {
    for (size_t i = 0; i < n; ++i) unit.push_back(l_.axes[i].in_path ? d[i] / b.length : 0);
    if (!last_unit_.empty() && !pending_.empty() && pending_.back().path) {
      // D = |w - u|^2, S = |w + u|^2: h = sqrt(S) / 2, h / (1 - h) = (2 sqrt(S) + S) / D.
      double D = 0, S = 0;
      for (size_t i = 0; i < n; ++i) {
        D += (unit[i] - last_unit_[i]) * (unit[i] - last_unit_[i]);
        S += (unit[i] + last_unit_[i]) * (unit[i] + last_unit_[i]);
      }
      double v2 = std::min(b.cruise2, pending_.back().cruise2);
      if (D > 0) {
        double a = std::numeric_limits<double>::infinity();
        for (size_t i = 0; i < n; ++i) {
          const double j = std::fabs(unit[i] - last_unit_[i]) / std::sqrt(D);
          if (j > 0) a = std::min(a, l_.axes[i].accel_mm_s2 / j);
        }
        v2 = std::min(v2, a * l_.junction_mm * (2 * std::sqrt(S) + S) / D);
      }
      b.max_entry2 = v2;
    }
    last_unit_ = unit;
  } else {
    last_unit_.clear();  // an extruder-only block: the next starts at rest
  }
  pending_.push_back(b);
}

void TimeEstimator::rest() {
  plan();
  last_unit_.clear();
}

double TimeEstimator::seconds() {
  plan();
  return seconds_;
}

void TimeEstimator::plan() {
  const size_t n = pending_.size();
  if (n == 0) return;
  // entry2[i]: block i's entry speed squared; entry2[n]: the end, at rest.
  std::vector<double> entry2(n + 1, 0);
  for (size_t i = n; i-- > 0;)
    entry2[i] = std::min(pending_[i].max_entry2, entry2[i + 1] + 2 * pending_[i].accel * pending_[i].length);
  for (size_t i = 0; i < n; ++i) {
    const Block& b = pending_[i];
    if (!b.path) entry2[i + 1] = 0;  // it ends at rest, whatever follows
    entry2[i + 1] = std::min(entry2[i + 1], entry2[i] + 2 * b.accel * b.length);
  }
  for (size_t i = 0; i < n; ++i) {
    for (size_t k = 0; k < mark_block_.size(); ++k)
      if (mark_block_[k] == planned_ + i) mark_s_[k] = seconds_;
    const Block& b = pending_[i];
    const double v0 = std::sqrt(entry2[i]), v1 = std::sqrt(entry2[i + 1]);
    const double up = (b.cruise2 - entry2[i]) / (2 * b.accel), down = (b.cruise2 - entry2[i + 1]) / (2 * b.accel);
    if (up + down <= b.length) {
      const double vc = std::sqrt(b.cruise2);
      seconds_ += (vc - v0) / b.accel + (vc - v1) / b.accel + (b.length - up - down) / vc;
    } else {  // a triangle: the ramps meet below the cruise
      const double vp = std::sqrt((2 * b.accel * b.length + entry2[i] + entry2[i + 1]) / 2);
      seconds_ += (vp - v0) / b.accel + (vp - v1) / b.accel;
    }
  }
  planned_ += n;
  pending_.clear();
}

size_t TimeEstimator::mark() {
  mark_block_.push_back(moves_);
  mark_s_.push_back(-1);
  return mark_block_.size() - 1;
}

double TimeEstimator::at(size_t mark) {
  plan();
  return mark_block_[mark] >= planned_ ? seconds_ : mark_s_[mark];
}

}  // namespace sim
