// PathPlanner (core/motion/path_planner.h) replanning and the step
// generator's side. Random sequences (turns of every size, straight runs,
// reversals, extruder-only and extruder-with-XY blocks, blocks given only as
// steps, lengths from 0.01 to 50 mm, feeds from 30 mm/min to rapids) are
// added one block at a time while a step generator takes and drops blocks at
// random moments. After every add:
//   - the plan, read by draining a copy of the planner through take(), equals
//     a plain reverse-then-forward pass written here in double over limits
//     computed here (grbl's junction formula, nominal speeds, 2 a L with
//     kPlanAccel), from the fixed entry of the first block not taken;
//   - the last block ends at exactly 0.
// Every block take() gives (from the planner and from the copies) is exactly
// feasible in float as the contract writes it, within its cruise, and the next
// block enters at exactly the previous exit converted (x * (k_next / k)) and
// at the same path speed. A taken block never changes until done(). Single
// steps between long blocks at 1 .. 2 m/s make the rounding walks act (and
// are compared with the reference too); rings of 16, 3 and 32 blocks wrap
// around thousands of times; a sweep of extreme inputs (single steps at the
// event cap, kilometre blocks) stays feasible.
// The reference and the sequences: path_replan_model.h.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <deque>
#include <random>
#include <vector>

#include "core/motion/path_planner.h"

#include "path_replan_model.h"

namespace {

using namespace replantest;

struct Worst {
  double speed = 0;  // |v^2 - v_ref^2| / (v_ref^2 + 1 (mm/s)^2)
  int compared = 0;
  int blocks = 0;    // blocks taken and checked
  int raised = 0;    // of these, with the cruise raised to the entry
};

// The cruise is the block's nominal speed (what the planner gives the block
// alone, bit for bit), except where an exit raised by rounding made the
// entry a hair faster: then it is that entry.
void expect_cruise(const am::PathBlock<4>& b, float nominal, Worst& worst) {
  ++worst.blocks;
  if (b.cruise == nominal) return;
  ++worst.raised;
  ASSERT_EQ(b.cruise, b.entry);
  ASSERT_LE(b.cruise, nominal * (1 + 5e-7f));
}

// Drains a copy of the planner: its plan, compared with the reference; every
// block feasible, hand-overs exact, the last block ending at 0.
template <uint8_t Size>
void check_plan(const am::PathPlanner<4, Size>& planner, const Reference& ref, Worst& worst) {
  am::PathPlanner<4, Size> copy = planner;
  const std::vector<double> plan = ref.plan();
  const size_t first = ref.first_open();
  const am::PathBlock<4>* prev = nullptr;
  for (size_t j = first; j < ref.size(); ++j) {
    const am::PathBlock<4>* b = copy.take();
    ASSERT_NE(b, nullptr);
    const Ref& r = ref.at(j);
    ASSERT_EQ(b->events, r.events);
    expect_feasible(*b);
    expect_cruise(*b, r.cruise, worst);
    if (prev) expect_hand_over(*prev, ref.at(j - 1).in, *b, r.in, ref.at(j - 1), r);
    const double entry = b->entry / r.k, exit = b->exit / r.k;
    const double want_entry = plan[j - first], want_exit = plan[j - first + 1];
    const double err = std::max(std::abs(entry * entry - want_entry) / (want_entry + 1),
                                std::abs(exit * exit - want_exit) / (want_exit + 1));
    ASSERT_LT(err, 4e-5) << "block " << j - first << " of " << ref.size() - first << ": entry^2 " << entry * entry
                         << " / " << want_entry << ", exit^2 " << exit * exit << " / " << want_exit;
    worst.speed = std::max(worst.speed, err);
    ++worst.compared;
    prev = b;
  }
  ASSERT_EQ(copy.take(), nullptr);
  if (prev) {
    ASSERT_EQ(prev->exit, 0.0f);
  }
}

// A taken block and what it held when taken.
struct Held {
  const am::PathBlock<4>* at;
  am::PathBlock<4> copy;
};

template <uint8_t Size>
void run_sequence(uint32_t seed, int blocks, bool compare, Worst& worst, bool spiky = false) {
  using Planner = am::PathPlanner<4, Size>;
  Planner planner(kAxes, kDeviation, kEventCap);
  Reference ref;
  Sequence seq(seed, spiky);
  std::deque<Held> held;
  am::PathBlock<4> last_block{};
  Input last_in{};
  Ref last_ref{};
  auto take = [&]() {
    const am::PathBlock<4>* b = planner.take();
    ASSERT_NE(b, nullptr);
    const size_t i = ref.first_open();
    ASSERT_EQ(b->events, ref.at(i).events);
    for (int a = 0; a < 4; ++a) ASSERT_EQ(b->steps[a], ref.at(i).in.steps[a]);
    expect_feasible(*b);
    expect_cruise(*b, ref.at(i).cruise, worst);
    if (ref.at(i).by_take) {  // the previous take fixed its entry: it is the last taken block
      expect_hand_over(last_block, last_in, *b, ref.at(i).in, last_ref, ref.at(i));
    } else {
      ASSERT_EQ(b->entry, 0.0f);  // from rest
    }
    held.push_back({b, *b});
    last_block = *b;
    last_in = ref.at(i).in;
    last_ref = ref.at(i);
    ref.take(b->exit);
  };
  auto drop = [&]() {
    planner.done();
    ref.done();
    held.pop_front();
  };
  auto unchanged = [&]() {
    for (const Held& h : held) ASSERT_EQ(std::memcmp(h.at, &h.copy, sizeof h.copy), 0);
  };
  for (int added = 0; added < blocks;) {
    const Input in = seq.next();
    if (!moves(in)) continue;
    while (planner.full()) {
      if (ref.first_open() < ref.size()) take();
      drop();
    }
    ASSERT_EQ(planner.add(in.steps, in.mm, in.feed, in.rapid), Planner::Status::queued);
    ref.add(in);
    ++added;
    ASSERT_EQ(planner.count(), ref.size());
    unchanged();
    if (compare) check_plan(planner, ref, worst);
    if (::testing::Test::HasFatalFailure()) return;
    if (seq.u(0, 1) < 0.35 && ref.first_open() < ref.size()) take();
    if (seq.u(0, 1) < 0.3 && !held.empty()) drop();
    unchanged();
    if (::testing::Test::HasFatalFailure()) return;
  }
  while (!planner.empty()) {
    if (ref.first_open() < ref.size()) take();
    drop();
  }
  EXPECT_EQ(planner.take(), nullptr);
}

TEST(PathReplan, EqualsTwoPassReferenceAfterEveryAdd) {
  Worst worst;
  for (uint32_t seed = 1; seed <= 6; ++seed) {
    run_sequence<16>(seed, 3000, true, worst);
    if (HasFatalFailure()) return;
  }
  EXPECT_GT(worst.compared, 50000);
  EXPECT_EQ(worst.raised, 0);
  std::printf("replan: %d plans compared, worst |v^2 - v_ref^2| / (v_ref^2 + 1 (mm/s)^2) = %.2e\n", worst.compared,
              worst.speed);
}

// Where float rounding would make a taken block infeasible: single steps at
// speed between long blocks. Some exits must rise there, and some cruises
// with them (by a unit in the last place).
TEST(PathReplan, SingleStepsBetweenLongRapids) {
  Worst worst;
  run_sequence<16>(41, 20000, true, worst, true);
  EXPECT_GT(worst.compared, 80000);
  EXPECT_GT(worst.raised, 0);  // the rounding cases do occur here
  EXPECT_LT(worst.raised, worst.blocks / 50);
  std::printf("single steps: %d blocks, %d with the cruise raised to the entry\n", worst.blocks, worst.raised);
}

TEST(PathReplan, SmallRingWrapsAroundThousandsOfTimes) {
  Worst worst;
  run_sequence<3>(21, 12000, true, worst);
  EXPECT_GT(worst.compared, 10000);
  EXPECT_EQ(worst.raised, 0);
}

TEST(PathReplan, LongRingStreamsFeasibly) {
  Worst worst;
  run_sequence<32>(33, 20000, false, worst);
  EXPECT_EQ(worst.blocks, 20000);
  EXPECT_EQ(worst.raised, 0);
}

// The last block of the queue always plans to stop; the first starts from
// rest; a block added after the only block was taken starts from rest too.
TEST(PathReplan, QueueEndsAtRest) {
  Ring16 p(kAxes, kDeviation, kEventCap);
  Sequence seq(7);
  for (int k = 0; k < 200; ++k) {
    const Input in = seq.next();
    if (!moves(in)) continue;
    if (p.full()) {
      p.take();
      p.done();
    }
    ASSERT_EQ(p.add(in.steps, in.mm, in.feed, in.rapid), Ring16::Status::queued);
    Ring16 copy = p;
    const am::PathBlock<4>* b = nullptr;
    while (const am::PathBlock<4>* t = copy.take()) b = t;
    ASSERT_EQ(b->exit, 0.0f);
  }
  // Straight on, long blocks: the only block is taken (exit 0); the next
  // one then starts from rest although the junction would allow the feed.
  Ring16 q(kAxes, kDeviation, kEventCap);
  const int32_t steps[4] = {8000, 0, 0, 0};
  const float mm[4] = {100, 0, 0, 0};
  ASSERT_EQ(q.add(steps, mm, 3000, false), Ring16::Status::queued);
  EXPECT_EQ(q.take()->exit, 0.0f);
  ASSERT_EQ(q.add(steps, mm, 3000, false), Ring16::Status::queued);
  ASSERT_EQ(q.add(steps, mm, 3000, false), Ring16::Status::queued);
  const am::PathBlock<4>* b = q.take();
  EXPECT_EQ(b->entry, 0.0f);
  EXPECT_NEAR(b->exit, 50.0f * 80, 1e-3f);
}

// Extremes: single steps at the event cap, kilometre blocks, tiny and huge
// scales, rates, accelerations and deviations; every block given feasible,
// hand-overs exact (a block added after the newest was taken enters at that
// block's exit, 0), every queue ending at 0.
TEST(PathReplan, ExtremeInputsStayFeasible) {
  std::mt19937 rng(99);
  auto u = [&](double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); };
  auto logu = [&](double lo, double hi) { return std::exp(u(std::log(lo), std::log(hi))); };
  int taken = 0;
  for (int round = 0; round < 40; ++round) {
    am::PathAxis axes[4];
    for (int i = 0; i < 4; ++i) axes[i] = {float(logu(0.5, 5000)), float(logu(10, 1e6)), float(logu(10, 1e8)), i < 3};
    using P = am::PathPlanner<4, 8>;
    P p(axes, float(logu(1e-4, 1.0)), float(logu(100, 1e6)));
    // The planner's float events per mm of an input, with these axes.
    auto per_mm = [&](const Input& in, uint32_t events) { return per_mm_float(in, events, axes); };
    std::deque<Input> queued;
    am::PathBlock<4> prev{};
    float prev_per_mm = 0;
    for (int k = 0; k < 400; ++k) {
      Input in{};
      const double scale = logu(1e-3, 1e6);
      for (int i = 0; i < 4; ++i) {
        in.mm[i] = u(0, 1) < 0.3 ? 0.0f : float(u(-1, 1) * scale / (i == 3 ? 10 : 1));
        const double s = double(in.mm[i]) * axes[i].steps_per_mm;
        in.steps[i] = int32_t(std::max(-2e9, std::min(2e9, std::round(s))));
        if (u(0, 1) < 0.1) in.steps[i] = int32_t(u(-2.5, 2.5));  // a step or two, whatever the distance
      }
      if (!moves(in)) continue;
      in.rapid = u(0, 1) < 0.2;
      in.feed = float(logu(1, 1e7));
      if (p.full()) {
        const am::PathBlock<4>* b = p.take();
        ASSERT_NE(b, nullptr);
        expect_feasible(*b);
        const float k = per_mm(queued.front(), b->events);
        if (prev_per_mm > 0) {
          ASSERT_EQ(b->entry, prev.exit * (k / prev_per_mm));
        } else {
          ASSERT_EQ(b->entry, 0.0f);  // the round's first block
        }
        prev = *b;
        prev_per_mm = k;
        ++taken;
        p.done();
        queued.pop_front();
        if (::testing::Test::HasFatalFailure()) return;
      }
      ASSERT_EQ(p.add(in.steps, in.mm, in.feed, in.rapid), P::Status::queued);
      queued.push_back(in);
      P copy = p;
      const am::PathBlock<4>* last = nullptr;
      while (const am::PathBlock<4>* t = copy.take()) {
        expect_feasible(*t);
        last = t;
      }
      ASSERT_EQ(last->exit, 0.0f);
      if (::testing::Test::HasFatalFailure()) return;
    }
  }
  EXPECT_GT(taken, 10000);
}

}  // namespace
