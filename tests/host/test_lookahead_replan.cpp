// Lookahead (core/motion/lookahead.h) replanning. Random polylines (turns of
// every size, straight runs, reversals, lengths from 0.01 to 50 mm, feeds
// from 10 mm/min to rapids) are added one block at a time, and after every
// add the plan must equal
//   - the planner's own replan() from scratch (planning all at once), and
//   - a plain reverse-then-forward pass written here over the blocks' limits
//     (junction limit, 2 a L), which by construction is the largest feasible
//     plan: entry <= limit, entry <= next entry + 2aL, entry <= previous
//     entry + 2aL, the newest block stops.
// A step generator takes blocks at random moments (begin, refresh, lock,
// finish): a busy block's entry never changes, its exit only rises until it
// is locked and never changes after, the next block starts at exactly the
// locked exit, and a profile marked final never changes again.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <random>
#include <vector>

#include "core/motion/lookahead.h"

namespace {

const am::LookaheadAxis kAxes[3] = {{80000, 24000, 160000}, {100000, 20000, 50000}, {400000, 4000, 40000}};

struct Segment {
  int32_t steps[3];
  int32_t len[3];
  int32_t feed;
  bool rapid;
};

class Polyline {
 public:
  explicit Polyline(uint32_t seed) : rng_(seed) {}

  Segment next() {
    std::uniform_real_distribution<double> u(0, 1);
    const double r = u(rng_);
    if (r < 0.15) {
      // keep the direction
    } else if (r < 0.22) {
      for (double& d : dir_) d = -d;  // reversal
    } else if (r < 0.6) {
      // a small turn
      for (double& d : dir_) d += 0.15 * (u(rng_) - 0.5);
    } else {
      for (double& d : dir_) d = u(rng_) - 0.5;
      dir_[2] *= 0.3;
    }
    double n = std::sqrt(dir_[0] * dir_[0] + dir_[1] * dir_[1] + dir_[2] * dir_[2]);
    if (n < 1e-6) {
      dir_[0] = 1;
      n = 1;
    }
    for (double& d : dir_) d /= n;
    const double mm = std::exp(std::log(0.01) + u(rng_) * (std::log(50.0) - std::log(0.01)));
    Segment s;
    for (int i = 0; i < 3; ++i) {
      const int32_t c = coord_[i] + int32_t(std::lround(dir_[i] * mm * 10000));
      const int32_t st = int32_t(std::lround(c * double(kAxes[i].steps_per_m) / 1e7));
      s.len[i] = c - coord_[i];
      s.steps[i] = st - steps_[i];
      coord_[i] = c;
      steps_[i] = st;
    }
    const double f = u(rng_);
    s.rapid = f < 0.1;
    s.feed = s.rapid ? 0 : int32_t(std::exp(std::log(1e5) + u(rng_) * (std::log(2e8) - std::log(1e5))));
    return s;
  }

 private:
  std::mt19937 rng_;
  double dir_[3] = {1, 0, 0};
  int32_t coord_[3] = {0, 0, 0};
  int32_t steps_[3] = {0, 0, 0};
};

// The plain two-pass plan over the planner's block limits; entries before
// `first` are fixed as they are.
template <uint8_t Size>
std::vector<uint64_t> reference_plan(const am::Lookahead<3, Size>& p, uint8_t first) {
  const uint8_t n = p.size();
  std::vector<uint64_t> e(n);
  for (uint8_t i = 0; i < n; ++i) e[i] = p.block(i).entry_sqr.value();
  uint64_t next = 0;
  for (int k = n - 1; k >= first; --k) {
    e[k] = std::min(p.block(uint8_t(k)).max_entry_sqr.value(), next + p.block(uint8_t(k)).delta_sqr.value());
    next = e[k];
  }
  for (int k = std::max<int>(first, 1); k < n; ++k)
    e[k] = std::min(e[k], e[k - 1] + p.block(uint8_t(k - 1)).delta_sqr.value());
  return e;
}

template <uint8_t Size>
void expect_plan(const am::Lookahead<3, Size>& p, const char* what, int step) {
  // Against replan() from scratch.
  am::Lookahead<3, Size> again = p;
  again.replan();
  for (uint8_t i = 0; i < p.size(); ++i)
    ASSERT_EQ(p.block(i).entry_sqr.value(), again.block(i).entry_sqr.value()) << what << " step " << step << " block "
                                                                              << int(i);
  // Against the plain two passes.
  const uint8_t first = p.locked() ? 2 : 1;
  const std::vector<uint64_t> ref = reference_plan(p, first);
  for (uint8_t i = 0; i < p.size(); ++i)
    ASSERT_EQ(p.block(i).entry_sqr.value(), ref[i]) << what << " step " << step << " block " << int(i);
  // The largest feasible plan: every entry meets one of its bounds.
  for (uint8_t i = first; i < p.size(); ++i) {
    const auto& b = p.block(i);
    const uint64_t e = b.entry_sqr.value(), next = p.exit_sqr(i);
    const uint64_t prev = p.block(uint8_t(i - 1)).entry_sqr.value() + p.block(uint8_t(i - 1)).delta_sqr.value();
    EXPECT_LE(e, b.max_entry_sqr.value());
    EXPECT_LE(e, next + b.delta_sqr.value());
    EXPECT_LE(e, prev);
    EXPECT_TRUE(e == b.max_entry_sqr.value() || e == next + b.delta_sqr.value() || e == prev) << "not maximal";
  }
  EXPECT_EQ(p.exit_sqr(uint8_t(p.size() - 1)), 0u) << "the queue's end must stop";
  am::LookaheadMove<3> last;
  p.move(uint8_t(p.size() - 1), last);
  EXPECT_EQ(last.exit, 0u);
}

}  // namespace

TEST(LookaheadReplan, OneBlockAtATimeEqualsPlanningAllAtOnce) {
  for (uint32_t seed : {1u, 2u, 3u}) {
    Polyline line(seed);
    am::Lookahead<3, 64> p(kAxes);
    int added = 0;
    while (p.size() < 64) {
      const Segment s = line.next();
      const am::LookaheadStatus st = p.add(s.steps, s.len, s.feed, s.rapid);
      if (st == am::LookaheadStatus::empty) continue;
      ASSERT_EQ(st, am::LookaheadStatus::queued);
      ++added;
      expect_plan(p, "growing", added);
      if (::testing::Test::HasFatalFailure()) return;
    }
    EXPECT_EQ(p.add(line.next().steps, line.next().len, 10000000, false), am::LookaheadStatus::full);
  }
}

TEST(LookaheadReplan, TheFinalPrefixNeverChanges) {
  // Blocks up to planned() are final: later adds leave their entries alone,
  // and move() says so.
  Polyline line(7);
  am::Lookahead<3, 64> p(kAxes);
  std::vector<uint64_t> seen;
  while (p.size() < 64) {
    const Segment s = line.next();
    if (p.add(s.steps, s.len, s.feed, s.rapid) != am::LookaheadStatus::queued) continue;
    for (uint8_t i = 0; i <= p.planned() && i < seen.size(); ++i)
      ASSERT_EQ(p.block(i).entry_sqr.value(), seen[i]) << "block " << int(i) << " was final";
    seen.assign(p.size(), 0);
    for (uint8_t i = 0; i < p.size(); ++i) seen[i] = p.block(i).entry_sqr.value();
    seen.resize(p.planned() + 1u);
    for (uint8_t i = 0; i < p.size(); ++i) {
      am::LookaheadMove<3> m;
      p.move(i, m);
      EXPECT_EQ(m.final, i + 1 <= p.planned());
    }
  }
  EXPECT_GT(p.planned(), 10);
}

TEST(LookaheadReplan, AStepGeneratorTakingBlocksAtRandomMoments) {
  for (uint32_t seed : {11u, 12u, 13u, 14u}) {
    Polyline line(seed);
    std::mt19937 rng(seed * 77);
    std::uniform_int_distribution<int> act(0, 9);
    am::Lookahead<3, 8> p(kAxes);
    am::LookaheadMove<3> m{};
    uint64_t busy_entry = 0, busy_exit = 0, locked_exit = 0;
    int finished = 0;
    // id -> (entry, exit) of every block seen final.
    std::map<int, std::pair<uint64_t, uint64_t>> final_values;
    bool have_locked = false;
    for (int step = 0; step < 1500; ++step) {
      const int a = act(rng);
      if (a < 5 && !p.full()) {
        const Segment s = line.next();
        const am::LookaheadStatus st = p.add(s.steps, s.len, s.feed, s.rapid);
        ASSERT_TRUE(st == am::LookaheadStatus::queued || st == am::LookaheadStatus::empty);
      } else if (a < 6 && !p.busy() && !p.empty()) {
        ASSERT_TRUE(p.begin(m));
        busy_entry = p.block(0).entry_sqr.value();
        busy_exit = p.exit_sqr(0);
        if (have_locked) {
          EXPECT_EQ(busy_entry, locked_exit) << "the next block starts at the locked exit";
        }
      } else if (a < 8 && p.busy()) {
        const uint64_t now = p.exit_sqr(0);
        am::LookaheadMove<3> before = m;
        const bool changed = p.refresh(m);
        EXPECT_EQ(changed, now != busy_exit) << step;
        if (!changed) {
          EXPECT_EQ(m.exit, before.exit);
        }
        busy_exit = now;
      } else if (a < 9 && p.busy() && !p.locked()) {
        ASSERT_TRUE(p.lock(m));
        EXPECT_TRUE(m.final);
        locked_exit = busy_exit = p.exit_sqr(0);
        am::LookaheadMove<3> fresh;
        p.move(0, fresh);
        EXPECT_EQ(m.exit, fresh.exit) << "lock refills a changed exit";
      } else if (p.busy()) {
        if (!p.locked()) {
          ASSERT_TRUE(p.lock(m));
          locked_exit = p.exit_sqr(0);
        }
        ASSERT_TRUE(p.finish());
        have_locked = true;
        ++finished;
        if (!p.empty()) {
          EXPECT_EQ(p.block(0).entry_sqr.value(), locked_exit);
        }
      }
      if (p.empty()) {
        have_locked = false;  // at rest: the next block starts from 0
        continue;
      }
      if (p.busy()) {
        EXPECT_EQ(p.block(0).entry_sqr.value(), busy_entry) << "a busy block's entry never changes";
        if (p.locked()) {
          EXPECT_EQ(p.exit_sqr(0), locked_exit) << "a locked exit never changes";
        } else {
          EXPECT_GE(p.exit_sqr(0), busy_exit) << "an unlocked busy exit only rises";
        }
      }
      expect_plan(p, "streaming", step);
      if (::testing::Test::HasFatalFailure()) return;
      for (uint8_t i = 0; i < p.size(); ++i) {
        am::LookaheadMove<3> f;
        p.move(i, f);
        const int id = finished + i;
        const std::pair<uint64_t, uint64_t> v{p.block(i).entry_sqr.value(), p.exit_sqr(i)};
        auto it = final_values.find(id);
        if (it != final_values.end()) {
          EXPECT_EQ(it->second, v) << "block " << id << " changed after it was final";
        } else if (f.final) {
          final_values[id] = v;
        }
      }
    }
    EXPECT_GT(finished, 100);
    EXPECT_GT(final_values.size(), 100u);
  }
}

TEST(LookaheadReplan, ABlockAfterALockedStopStartsFromRest) {
  // The generator locks the only block (its exit is 0: it will stop). A
  // block added then must start at 0, whatever the junction would allow.
  am::Lookahead<3, 4> p(kAxes);
  const int32_t steps[3] = {800, 0, 0}, len[3] = {100000, 0, 0};
  ASSERT_EQ(p.add(steps, len, 30000000, false), am::LookaheadStatus::queued);
  am::LookaheadMove<3> m;
  ASSERT_TRUE(p.begin(m));
  ASSERT_TRUE(p.lock(m));
  EXPECT_EQ(m.exit, 0u);
  ASSERT_EQ(p.add(steps, len, 30000000, false), am::LookaheadStatus::queued);
  EXPECT_EQ(p.block(1).entry_sqr.value(), 0u);
  EXPECT_EQ(p.block(1).max_entry_sqr.value(), 0u);
  // Unlocked, the same straight continuation raises the busy block's exit.
  am::Lookahead<3, 4> q(kAxes);
  ASSERT_EQ(q.add(steps, len, 30000000, false), am::LookaheadStatus::queued);
  ASSERT_TRUE(q.begin(m));
  EXPECT_FALSE(q.refresh(m));
  ASSERT_EQ(q.add(steps, len, 30000000, false), am::LookaheadStatus::queued);
  EXPECT_TRUE(q.refresh(m));
  EXPECT_EQ(m.exit, m.nominal);  // 10 mm is room to stop from 50 mm/s
  EXPECT_FALSE(q.refresh(m));
}

TEST(LookaheadReplan, ALockedExitStaysPutWhenLaterBlocksWouldRaiseIt) {
  // 20 mm then 0.5 mm at 6000 mm/min: the second block's entry is what it
  // can stop from in 0.5 mm (45 mm/s at 2000 mm/s^2), backward-limited.
  // Locked now, that exit is final; more blocks would otherwise raise it.
  const int32_t steps[3] = {40, 0, 0}, len[3] = {5000, 0, 0};
  const int32_t first_steps[3] = {1600, 0, 0}, first_len[3] = {200000, 0, 0};
  am::Lookahead<3, 8> p(kAxes);
  ASSERT_EQ(p.add(first_steps, first_len, 60000000, false), am::LookaheadStatus::queued);
  ASSERT_EQ(p.add(steps, len, 60000000, false), am::LookaheadStatus::queued);
  am::LookaheadMove<3> m;
  ASSERT_TRUE(p.begin(m));
  const uint64_t exit = p.exit_sqr(0);
  ASSERT_LT(exit, p.block(1).max_entry_sqr.value());  // room to rise
  ASSERT_TRUE(p.lock(m));
  for (int k = 0; k < 5; ++k) ASSERT_EQ(p.add(steps, len, 60000000, false), am::LookaheadStatus::queued);
  EXPECT_EQ(p.exit_sqr(0), exit);
  am::Lookahead<3, 8> again = p;
  again.replan();
  EXPECT_EQ(again.exit_sqr(0), exit);
  // Without the lock the same adds raise it.
  am::Lookahead<3, 8> q(kAxes);
  ASSERT_EQ(q.add(first_steps, first_len, 60000000, false), am::LookaheadStatus::queued);
  ASSERT_EQ(q.add(steps, len, 60000000, false), am::LookaheadStatus::queued);
  ASSERT_TRUE(q.begin(m));
  for (int k = 0; k < 5; ++k) ASSERT_EQ(q.add(steps, len, 60000000, false), am::LookaheadStatus::queued);
  EXPECT_GT(q.exit_sqr(0), exit);
  EXPECT_TRUE(q.refresh(m));
}
