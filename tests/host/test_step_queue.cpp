#include <gtest/gtest.h>

#include "core/motion/step_queue.h"

TEST(StepSegment, LongIntervalsSplitIntoEqualTimerPeriods) {
  for (uint32_t interval : {1u, 2u, 65535u, 65536u, 65537u, 65983u, 131072u, 131073u, 1000000u,
                            8800000u, am::kMaxSegmentInterval}) {
    const am::StepSegment s = am::StepSegment::make(interval, 1, 1, 1);
    // The periods add up to the interval exactly...
    EXPECT_EQ(uint64_t(s.wraps) * (s.wrap_compare + 1u) + s.compare + 1u, interval) << interval;
    EXPECT_EQ(s.interval(), interval);
    // ...each fits the 16-bit timer, and none is short when the interval wraps.
    EXPECT_EQ(s.wraps, (interval - 1) / 65536) << interval;
    if (s.wraps > 0) {
      EXPECT_GE(s.wrap_compare + 1u, 32768u) << interval;
      EXPECT_GE(s.compare + 1u, 32768u) << interval;
    }
  }
}

TEST(StepQueue, FifoOrderFullAndEmpty) {
  am::StepQueue<4> q;
  EXPECT_TRUE(q.empty());
  for (uint16_t i = 1; i <= 4; ++i) EXPECT_TRUE(q.push(am::StepSegment::make(100, i, 1, 0)));
  EXPECT_TRUE(q.full());
  EXPECT_FALSE(q.push(am::StepSegment::make(100, 9, 1, 0)));
  for (uint16_t i = 1; i <= 4; ++i) {
    ASSERT_FALSE(q.empty());
    EXPECT_EQ(q.front().count, i);
    q.pop();
  }
  EXPECT_TRUE(q.empty());
}

TEST(StepQueue, IndicesWrapAroundTheByteRange) {
  am::StepQueue<4> q;
  for (int i = 0; i < 600; ++i) {
    ASSERT_TRUE(q.push(am::StepSegment::make(7, uint16_t(i), 1, 0)));
    ASSERT_EQ(q.size(), 1);
    EXPECT_EQ(q.front().count, uint16_t(i));
    q.pop();
  }
}
