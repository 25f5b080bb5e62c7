// Lookahead (core/motion/lookahead.h) junction speeds against grbl's junction
// deviation formula evaluated here in double precision:
//   cos(theta) = -u.w (theta: the angle between the reversed previous
//   direction and the new one), h = sin(theta/2) = sqrt((1 - cos theta) / 2),
//   v^2 = a d h / (1 - h), a = min_i a_i / |j_i| with j = (w - u) / |w - u|,
// capped by both blocks' nominal path speeds. Angles below are deflections
// (0 = straight on, 180 = reversal), theta = 180 - deflection. Stated
// tolerance: 0.05 % of v^2 plus 1 (lu/s)^2 at every deflection (measured:
// within 0.02 %); the planner takes deflections below about 2e-6 rad as
// straight on and within that of 180 degrees as a reversal.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/motion/lookahead.h"

namespace {

constexpr double kTolerance = 5e-4;

// Fast axes (1 M steps/s, the slowest Z at 2.5 m/s) so a G1 block of up to
// 100 m/min runs at its feed: the cap is then floor(F / 60)^2, computed
// independently below.
const am::LookaheadAxis kUnequal[3] = {{80000, 1000000, 80000}, {100000, 1000000, 50000}, {400000, 1000000, 80000}};
const am::LookaheadAxis kEqual[3] = {{80000, 1000000, 80000}, {100000, 1000000, 100000}, {400000, 1000000, 400000}};

double axis_accel_lu(const am::LookaheadAxis& a) { return double(a.max_accel) * 1e7 / a.steps_per_m; }

// grbl's formula on the blocks' integer lengths (lu).
double formula(const am::LookaheadAxis (&axes)[3], const int32_t (&l1)[3], const int32_t (&l2)[3], double dev) {
  double u[3], w[3], nu = 0, nw = 0;
  for (int i = 0; i < 3; ++i) {
    u[i] = l1[i];
    w[i] = l2[i];
    nu += u[i] * u[i];
    nw += w[i] * w[i];
  }
  nu = std::sqrt(nu);
  nw = std::sqrt(nw);
  double dot = 0;
  for (int i = 0; i < 3; ++i) {
    u[i] /= nu;
    w[i] /= nw;
    dot += u[i] * w[i];
  }
  const double cos_theta = -dot;
  const double h = std::sqrt(std::max(0.0, 0.5 * (1 - cos_theta)));
  if (h >= 1) return 1e300;
  double j[3], nj = 0;
  for (int i = 0; i < 3; ++i) {
    j[i] = w[i] - u[i];
    nj += j[i] * j[i];
  }
  nj = std::sqrt(nj);
  double a = 1e300;
  for (int i = 0; i < 3; ++i)
    if (j[i] != 0) a = std::min(a, axis_accel_lu(axes[i]) / (std::fabs(j[i]) / nj));
  return a * dev * h / (1 - h);
}

void steps_of(const am::LookaheadAxis (&axes)[3], const int32_t (&len)[3], int32_t (&steps)[3]) {
  for (int i = 0; i < 3; ++i) steps[i] = int32_t(std::lround(len[i] * double(axes[i].steps_per_m) / 1e7));
}

// The second block's junction limit after a first block along l1.
uint64_t junction(const am::LookaheadAxis (&axes)[3], const int32_t (&l1)[3], const int32_t (&l2)[3], uint32_t dev,
                  int32_t feed) {
  am::Lookahead<3, 4> p(axes, dev);
  int32_t s1[3], s2[3];
  steps_of(axes, l1, s1);
  steps_of(axes, l2, s2);
  EXPECT_EQ(p.add(s1, l1, feed, false), am::LookaheadStatus::queued);
  EXPECT_EQ(p.add(s2, l2, feed, false), am::LookaheadStatus::queued);
  return p.block(1).max_entry_sqr.value();
}

double cap_of(int32_t feed) {
  const double v = std::floor(feed / 60.0);
  return v * v;
}

struct Frame {
  double u[3], p[3];  // direction of the first move, and the plane it turns in
};

std::vector<Frame> frames() {
  std::vector<Frame> out;
  for (int k = 0; k < 7; ++k) {
    const double az = 0.1 + 0.9 * k, el = -0.9 + 0.3 * k;
    Frame f{{std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el)}, {0, 0, 0}};
    // A unit vector perpendicular to u, rotated about u by k.
    const double a[3] = {-std::sin(az), std::cos(az), 0};
    const double b[3] = {-std::sin(el) * std::cos(az), -std::sin(el) * std::sin(az), std::cos(el)};
    for (int i = 0; i < 3; ++i) f.p[i] = std::cos(0.7 * k) * a[i] + std::sin(0.7 * k) * b[i];
    out.push_back(f);
  }
  return out;
}

void turn(const Frame& f, double deflection_deg, double mm1, double mm2, int32_t (&l1)[3], int32_t (&l2)[3]) {
  const double t = deflection_deg * M_PI / 180;
  for (int i = 0; i < 3; ++i) {
    l1[i] = int32_t(std::lround(f.u[i] * mm1 * 10000));
    l2[i] = int32_t(std::lround((std::cos(t) * f.u[i] + std::sin(t) * f.p[i]) * mm2 * 10000));
  }
}

}  // namespace

TEST(LookaheadJunction, SweepOfDeflectionsAndSpeedsMatchesTheFormula) {
  std::vector<double> degrees = {0.01, 0.02, 0.05, 0.1, 0.2, 0.5, 179.5, 179.8, 179.9, 179.95, 179.99};
  for (double d = 1; d < 180; d += 1) degrees.push_back(d);
  int uncapped = 0, capped = 0;
  double worst = 0;
  for (const auto* axes : {&kUnequal, &kEqual}) {
    for (const Frame& f : frames()) {
      for (uint32_t dev : {5u, 100u, 2000u}) {
        for (int32_t feed : {1000000000, 30000000, 600000}) {  // 100 m/min, 3000 mm/min, 60 mm/min
          for (double deg : degrees) {
            int32_t l1[3], l2[3];
            turn(f, deg, 5.0, 0.7, l1, l2);
            const double want = std::min(formula(*axes, l1, l2, dev), cap_of(feed));
            const double got = double(junction(*axes, l1, l2, dev, feed));
            ASSERT_NEAR(got, want, want * kTolerance + 1) << deg << " deg, d " << dev << ", F " << feed;
            if (want < cap_of(feed)) {
              ++uncapped;
              if (want > 1e6) worst = std::max(worst, std::fabs(got - want) / want);  // above 0.1 mm/s
            } else {
              ++capped;
            }
          }
        }
      }
    }
  }
  EXPECT_GT(uncapped, 2000);
  EXPECT_GT(capped, 1000);
  std::printf("junction: %d uncapped cases, worst relative error %.2e above 0.1 mm/s; %d capped\n", uncapped, worst,
              capped);
}

TEST(LookaheadJunction, TheJunctionAccelerationIsTheAxisLimitAlongTheTurn) {
  // X then Y at 90 degrees: the turn (w - u) is (-1, 1) / sqrt(2), so the
  // junction acceleration is min(1000, 500) * sqrt(2) mm/s^2 (Y limits):
  // v^2 = 707.1 * 0.01 * 0.7071 / (1 - 0.7071) = 17.07 mm^2/s^2.
  const int32_t l1[3] = {100000, 0, 0}, l2[3] = {0, 100000, 0};
  const double want = 500 * std::sqrt(2.0) * 0.01 * std::sqrt(0.5) / (1 - std::sqrt(0.5)) * 1e8;  // (lu/s)^2
  EXPECT_NEAR(double(junction(kUnequal, l1, l2, 100, 1000000000)), want, want * kTolerance);
  // With Y as fast as X the same corner is twice as fast in v^2.
  EXPECT_NEAR(double(junction(kEqual, l1, l2, 100, 1000000000)), 2 * want, 2 * want * kTolerance);
}

TEST(LookaheadJunction, StraightOnRunsAtTheFullNominalSpeed) {
  // Collinear moves of different lengths (so their unit vectors are rounded
  // differently), in several directions: the junction limit is the nominal
  // speed exactly.
  const int32_t dirs[][3] = {{3, 4, 0}, {1, 0, 0}, {0, -7, 24}, {1000, 1, 0}, {-12345, 6789, 1011}, {1, 1, 1}};
  for (const auto& d : dirs) {
    for (int32_t k1 : {1, 7, 300}) {
      for (int32_t k2 : {2, 13, 1000}) {
        // At least 0.5 mm, at most 50 mm along the largest component.
        const int32_t big = std::max({std::abs(d[0]), std::abs(d[1]), std::abs(d[2])});
        const int32_t m1 = k1 * std::max(1, 5000 / big), m2 = k2 * std::max(1, 5000 / big);
        if (int64_t(big) * m1 > 500000 || int64_t(big) * m2 > 500000) continue;
        const int32_t l1[3] = {d[0] * m1, d[1] * m1, d[2] * m1}, l2[3] = {d[0] * m2, d[1] * m2, d[2] * m2};
        for (int32_t feed : {30000000, 600000}) {
          EXPECT_EQ(double(junction(kUnequal, l1, l2, 100, feed)), cap_of(feed))
              << d[0] << "," << d[1] << "," << d[2] << " x" << m1 << " x" << m2;
        }
      }
    }
  }
  // Rapids are limited by the axes, not a feed: the second block enters at
  // its nominal speed in events/s once the first has room to reach it.
  const am::LookaheadAxis slow[3] = {{80000, 8000, 80000}, {100000, 10000, 100000}, {400000, 4000, 40000}};
  am::Lookahead<3, 4> p(slow);
  const int32_t l1[3] = {600000, 800000, 0}, l2[3] = {300000, 400000, 0};  // 100 mm, 50 mm
  int32_t s1[3], s2[3];
  steps_of(slow, l1, s1);
  steps_of(slow, l2, s2);
  ASSERT_EQ(p.add(s1, l1, 0, true), am::LookaheadStatus::queued);
  ASSERT_EQ(p.add(s2, l2, 0, true), am::LookaheadStatus::queued);
  ASSERT_EQ(p.add(s2, l2, 0, true), am::LookaheadStatus::queued);
  am::LookaheadMove<3> m;
  p.move(1, m);
  EXPECT_GE(m.entry + 1, m.nominal);
  EXPECT_GE(m.exit + 1, m.nominal);
}

TEST(LookaheadJunction, AReversalStops) {
  // Exactly opposite, of equal and of different lengths: 0. Just short of a
  // reversal: small but not 0, and the formula's value.
  const int32_t dirs[][3] = {{3000, 4000, 0}, {1000, 0, 0}, {0, -700, 2400}, {-12345, 6789, 1011}};
  for (const auto& d : dirs) {
    for (int32_t k2 : {-1, -3, -40}) {
      const int32_t l1[3] = {d[0] * 5, d[1] * 5, d[2] * 5};
      const int32_t back[3] = {d[0] * k2, d[1] * k2, d[2] * k2};
      EXPECT_EQ(junction(kUnequal, l1, back, 100, 30000000), 0u) << d[0] << "," << d[1] << "," << d[2] << " x" << k2;
    }
  }
  const Frame f = frames()[3];
  int32_t l1[3], l2[3];
  turn(f, 179.9, 5.0, 0.7, l1, l2);
  const uint64_t v2 = junction(kUnequal, l1, l2, 100, 30000000);
  EXPECT_GT(v2, 0u);
  EXPECT_NEAR(double(v2), formula(kUnequal, l1, l2, 100), formula(kUnequal, l1, l2, 100) * kTolerance + 1);
}

TEST(LookaheadJunction, ZeroDeviationStopsAtEveryCorner) {
  const Frame f = frames()[1];
  for (double deg : {0.5, 30.0, 90.0, 150.0}) {
    int32_t l1[3], l2[3];
    turn(f, deg, 5.0, 0.7, l1, l2);
    EXPECT_EQ(junction(kUnequal, l1, l2, 0, 30000000), 0u) << deg;
  }
  // ...but not on a straight line.
  const int32_t l1[3] = {30000, 40000, 0}, l2[3] = {3000, 4000, 0};
  EXPECT_EQ(double(junction(kUnequal, l1, l2, 0, 30000000)), cap_of(30000000));
}
