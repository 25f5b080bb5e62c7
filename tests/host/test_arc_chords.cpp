// ArcChords (core/motion/arc_chords.h) against geometry done here in doubles
// from the integers it is given: the sweep by atan2 of the exact cross and
// dot products, the chord count from the sag formula, every chord end on the
// spiral (radius linear in the angle) and at its angle, the linear axes from
// the exact rounding of (to - from) k / n, the last point equal to `to`.
// Then arcs given in steps (as the firmware gives them) are stepped as the
// firmware steps them: the steps between consecutive chord ends run through
// LineDda event by event, and every stepped point is measured against the
// arc, at 1000, 80 and 25 steps/mm with a quarter step of tolerance: within
// half a step (chord end) + the tolerance + half a step (LineDda's minor
// axis; 0.71 when a helix axis dominates), docs/interpolation.md. The tests
// print how far and how often a point is more than one step off.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <random>
#include <vector>

#include "core/motion/arc_chords.h"
#include "core/motion/line_dda.h"

namespace {

constexpr uint8_t kAxes = 4;  // X Y Z E
using Point = int32_t[kAxes];
constexpr double kPi = 3.14159265358979323846;

struct Arc {
  int32_t from[kAxes], to[kAxes];
  uint8_t plane0, plane1;
  int32_t centre[2];  // centre - start
  bool cw;
  float tol;
};

// Exact geometry of an arc, in doubles.
struct Geometry {
  double c[2];   // absolute centre
  double s[2];   // start - centre
  double r0, r1;
  double sweep;  // signed, radians
  double radius(double phi) const { return r0 + (r1 - r0) * phi / std::fabs(sweep); }
};

Geometry geometry(const Arc& a) {
  Geometry g;
  const uint8_t p[2] = {a.plane0, a.plane1};
  int64_t s[2], e[2];
  for (int j = 0; j < 2; ++j) {
    g.c[j] = double(int64_t(a.from[p[j]]) + a.centre[j]);
    s[j] = -int64_t(a.centre[j]);
    e[j] = int64_t(a.to[p[j]]) - a.from[p[j]] - a.centre[j];
    g.s[j] = double(s[j]);
  }
  g.r0 = std::hypot(double(s[0]), double(s[1]));
  g.r1 = std::hypot(double(e[0]), double(e[1]));
  const int64_t cross = s[0] * e[1] - s[1] * e[0], dot = s[0] * e[0] + s[1] * e[1];
  double a0 = std::atan2(double(cross), double(dot));  // exact sign from the integers
  if (a.cw) g.sweep = a0 < 0 ? a0 : a0 - 2 * kPi;
  else g.sweep = a0 > 0 ? a0 : a0 + 2 * kPi;
  return g;
}

double sag(double r, double sweep, unsigned n) {
  const double h = std::sin(std::fabs(sweep) / (4.0 * n));
  return 2 * r * h * h;  // r (1 - cos(dphi / 2))
}

// Angle of p - c from the start vector, in the arc's direction, unwrapped
// next to `near` (radians).
double angle_along(const Geometry& g, const double (&p)[2], double near) {
  const double v[2] = {p[0] - g.c[0], p[1] - g.c[1]};
  double phi = std::atan2(g.s[0] * v[1] - g.s[1] * v[0], g.s[0] * v[0] + g.s[1] * v[1]);
  if (g.sweep < 0) phi = -phi;
  while (phi < near - kPi) phi += 2 * kPi;
  while (phi > near + kPi) phi -= 2 * kPi;
  return phi;
}

double dist(const Geometry& g, const double (&p)[2]) { return std::hypot(p[0] - g.c[0], p[1] - g.c[1]); }

int32_t linear_point(int32_t from, int32_t to, uint32_t k, uint32_t n) {
  const int64_t d = int64_t(to) - from, m = d < 0 ? -d : d;
  const int64_t q = (m * k + n / 2) / n;  // half rounds away from zero
  return int32_t(from + (d < 0 ? -q : q));
}

struct ChordStats {
  double worst_radial = 0;  // units, chord end from the spiral
  unsigned arcs = 0;
  unsigned long chords = 0;
};

using Chords = std::vector<std::vector<int32_t>>;

// Every check on the chord ends; `out` gets the points (the last one is `to`).
void check_chords(const Arc& a, ChordStats& st, const char* what, Chords& out) {
  out.clear();
  am::ArcChords<kAxes> arc;
  ASSERT_TRUE(arc.start(a.from, a.to, a.plane0, a.plane1, a.centre, a.cw, a.tol)) << what;
  const Geometry g = geometry(a);
  const unsigned n = arc.chords();
  const double rmax = std::max(g.r0, g.r1);
  // Minimal: n chords keep the sag, n - 1 would not (float: 1e-5 relative slack).
  EXPECT_GE(n, 1u) << what;
  EXPECT_LE(sag(rmax, g.sweep, n), a.tol * (1 + 1e-5)) << what << " n " << n;
  if (n > 1) {
    EXPECT_GT(sag(rmax, g.sweep, n - 1), a.tol * (1 - 1e-5)) << what << " n " << n;
  }

  Point p;
  double prev = 0;
  for (unsigned k = 1; k <= n; ++k) {
    ASSERT_TRUE(arc.next(p)) << what << ": next() ended at " << k << " of " << n;
    out.emplace_back(p, p + kAxes);
    for (uint8_t i = 0; i < kAxes; ++i) {
      if (i != a.plane0 && i != a.plane1) {
        ASSERT_EQ(p[i], linear_point(a.from[i], a.to[i], k, n)) << what << " axis " << int(i) << " k " << k;
      }
    }
    if (k == n) break;
    const double q[2] = {double(p[a.plane0]), double(p[a.plane1])};
    const double phi = angle_along(g, q, prev);
    const double nominal = std::fabs(g.sweep) * k / n;
    // At its angle (float angles: 1e-6 rad, plus the rounding: up to 0.71 unit along the arc
    // to the grid line, 0.36 more rounding across it) and in the arc's direction.
    ASSERT_NEAR(phi, nominal, 1e-6 + 1.07 / std::min(g.r0, g.r1)) << what << " k " << k;
    ASSERT_GE(phi, prev) << what << " k " << k;
    // The lattice point nearest the spiral across it: within half a unit radially (0.01 of
    // float error before the rounding).
    const double radial = std::fabs(dist(g, q) - g.radius(phi));
    st.worst_radial = std::max(st.worst_radial, radial);
    ASSERT_LE(radial, 0.5 + 0.01 + 0.5 * 0.5 / g.r0) << what << " k " << k << " of " << n;
    prev = phi;
  }
  for (uint8_t i = 0; i < kAxes; ++i) EXPECT_EQ(p[i], a.to[i]) << what << " axis " << int(i);
  EXPECT_FALSE(arc.next(p)) << what;
  ++st.arcs;
  st.chords += n;
}

struct Stepped {
  double worst_planar = 0, worst_helix = 0;  // steps from the arc
  unsigned long points = 0, over_one = 0;    // stepped points, and those more than 1 step off
};

// The bound on a stepped point's distance from the arc, in steps (docs/interpolation.md): a
// chord end is within 0.51 of the spiral, the exact chord between two ends within the
// tolerance of them (its ends may sit half a step further along the arc, which lengthens the
// chord and its sag by the second term), LineDda's minor axes within half a step of the
// chord (both plane axes when a helix axis dominates).
double stepped_bound(const Arc& a, const Geometry& g, bool helix) {
  const double rmin = std::min(g.r0, g.r1);
  const double offset = 0.51 + a.tol * (1 + 2 / std::sqrt(2 * rmin * a.tol)) + (helix ? 0.7072 : 0.5) + 0.01;
  // An offset turns the angle by up to offset / room, the radius by (r1 - r0) / sweep per radian,
  // never by more than |r1 - r0|.
  const double room = rmin - offset;
  const double turn = room > 0 ? std::min(1.0, offset / (std::fabs(g.sweep) * room)) : 1.0;
  return offset + std::fabs(g.r1 - g.r0) * turn;
}

// Steps the chords (in steps) as the firmware does: the steps between ends through LineDda,
// every event's point measured against the arc (the circle of the radius interpolated at the
// point's angle). Returns the worst distance, in steps.
double step_chords(const Arc& a, const Chords& chords, int32_t (&end_steps)[kAxes], Stepped& st) {
  const Geometry g = geometry(a);
  int32_t pos[kAxes];
  for (uint8_t i = 0; i < kAxes; ++i) pos[i] = a.from[i];
  const double sweep = std::fabs(g.sweep);
  double phi = 0, worst = 0;
  auto measure = [&]() {
    const double q[2] = {double(pos[a.plane0]), double(pos[a.plane1])};
    phi = angle_along(g, q, phi);
    const double at = std::min(std::max(phi, 0.0), sweep);
    const double d = std::fabs(dist(g, q) - g.radius(at));
    worst = std::max(worst, d);
    ++st.points;
    st.over_one += d > 1;
  };
  measure();
  for (const auto& c : chords) {
    int32_t delta[kAxes];
    for (uint8_t i = 0; i < kAxes; ++i) delta[i] = c[i] - pos[i];
    am::LineDda<kAxes> dda;
    EXPECT_TRUE(dda.start(delta));
    while (!dda.finished()) {
      const am::StepEvent ev = dda.next();
      for (uint8_t i = 0; i < kAxes; ++i)
        if (ev.axes & (1u << i)) pos[i] += (ev.dirs & (1u << i)) ? 1 : -1;
      measure();
    }
  }
  for (uint8_t i = 0; i < kAxes; ++i) end_steps[i] = pos[i];
  const bool helix = a.to[2] != a.from[2] || a.to[3] != a.from[3];
  EXPECT_LE(worst, stepped_bound(a, g, helix));
  double& w = helix ? st.worst_helix : st.worst_planar;
  w = std::max(w, worst);
  return worst;
}

// A G17 arc of radius r (units) around c, from angle a0 sweeping `deg` degrees
// (negative: G2), end radius r + mismatch; Z and E move by dz, de.
Arc make_arc(double r, double a0, double deg, double mismatch, const int32_t (&c)[2], int32_t dz, int32_t de,
             float tol) {
  Arc a = {};
  a.plane0 = 0;
  a.plane1 = 1;
  a.cw = deg < 0;
  a.tol = tol;
  const double a1 = a0 + deg * kPi / 180;
  a.from[0] = c[0] + int32_t(std::lround(r * std::cos(a0)));
  a.from[1] = c[1] + int32_t(std::lround(r * std::sin(a0)));
  a.from[2] = 123456;
  a.from[3] = -98765;
  a.centre[0] = c[0] - a.from[0];
  a.centre[1] = c[1] - a.from[1];
  if (std::fabs(deg) == 360) {
    a.to[0] = a.from[0];
    a.to[1] = a.from[1];
  } else {
    a.to[0] = c[0] + int32_t(std::lround((r + mismatch) * std::cos(a1)));
    a.to[1] = c[1] + int32_t(std::lround((r + mismatch) * std::sin(a1)));
  }
  a.to[2] = a.from[2] + dz;
  a.to[3] = a.from[3] + de;
  return a;
}

// Radii 0.05 .. 500 mm (lu), log-spaced.
std::vector<double> radii(int count) {
  std::vector<double> r;
  for (int i = 0; i < count; ++i) r.push_back(500.0 * std::pow(1e4, double(i) / (count - 1)));
  return r;
}

const double kSweeps[] = {3, 7, 45, 90, 135, 180, 181, 200, 270, 300, 359, 360};

TEST(ArcChordsSweep, EveryChordEndOnTheSpiralAndTheCountMinimal) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> angle(-kPi, kPi), unit(-1, 1);
  ChordStats st;
  const int32_t tols[] = {1, 5, 62, 200};
  for (double r : radii(41))
    for (double deg : kSweeps)
      for (int dir = 0; dir < 2; ++dir) {
        const int32_t c[2] = {int32_t(unit(rng) * 1e6), int32_t(unit(rng) * 1e6)};
        // Radius mismatch within the interpreter's tolerance (max(50 lu, r / 1000)), not on full circles.
        const double mismatch = deg == 360 ? 0 : unit(rng) * std::max(50.0, r / 1000);
        const bool helix = rng() & 1;
        const int32_t tol = tols[rng() % 4];
        const int32_t dz = helix ? int32_t(unit(rng) * 2e5) : 0, de = helix ? int32_t(unit(rng) * 3e5) : 0;
        const Arc a = make_arc(r, angle(rng), dir ? -deg : deg, mismatch, c, dz, de, tol);
        char what[120];
        std::snprintf(what, sizeof what, "r %.0f lu, %s%.0f deg, tol %d", r, dir ? "-" : "", deg, int(tol));
        Chords chords;
        check_chords(a, st, what, chords);
        if (HasFatalFailure()) return;
      }
  std::printf("ArcChords: %u arcs, %lu chords, worst chord end %.3f lu from the spiral\n", st.arcs, st.chords,
              st.worst_radial);
}

TEST(ArcChordsSweep, FullCirclesFromManyStartAngles) {
  ChordStats st;
  for (double r : {500.0, 5237.0, 49999.0, 731234.0, 5000000.0})
    for (int i = 0; i < 72; ++i) {
      const int32_t c[2] = {-31234, 77777};
      const Arc a = make_arc(r, i * 5.1 * kPi / 180, i & 1 ? -360 : 360, 0, c, (i % 3) * 5000, 0, 5);
      Chords chords;
      check_chords(a, st, "full circle", chords);
      if (HasFatalFailure()) return;
    }
  std::printf("ArcChords: %u full circles, worst chord end %.3f lu from the circle\n", st.arcs, st.worst_radial);
}

// Arcs of 0.05 .. 500 mm in steps at steps_per_mm, the tolerance a quarter step, stepped;
// half of them helices (Z and E moving). Prints the worst distances.
void stepped_sweep(double steps_per_mm, int count) {
  std::mt19937 rng{uint32_t(steps_per_mm)};
  std::uniform_real_distribution<double> angle(-kPi, kPi), unit(-1, 1);
  ChordStats cs;
  Stepped st;
  const float tol = 0.25f;
  const double per_lu = steps_per_mm / 1e4;
  for (double r_lu : radii(count))
    for (double deg : kSweeps)
      for (int dir = 0; dir < 2; ++dir) {
        const double r = std::max(1.0, r_lu * per_lu);
        const int32_t c[2] = {int32_t(unit(rng) * 1e5), int32_t(unit(rng) * 1e5)};
        const double mismatch = deg == 360 ? 0 : unit(rng) * std::max(50.0, r_lu / 1000) * per_lu;
        const bool helix = rng() & 1;
        const int32_t dz = helix ? int32_t(unit(rng) * 1e4) : 0, de = helix ? int32_t(unit(rng) * 1e4) : 0;
        const Arc a = make_arc(r, angle(rng), dir ? -deg : deg, mismatch, c, dz, de, tol);
        Chords chords;
        check_chords(a, cs, "stepped", chords);
        if (::testing::Test::HasFatalFailure()) return;
        int32_t end[kAxes];
        step_chords(a, chords, end, st);
        for (uint8_t i = 0; i < kAxes; ++i) EXPECT_EQ(end[i], a.to[i]);
      }
  std::printf("ArcChords: %.0f steps/mm, tolerance %.2f step: %u arcs, %lu chords, %lu stepped points; "
              "worst %.3f step from the arc (plane only), %.3f (helix); %.3f %% of the points beyond 1 step\n",
              steps_per_mm, double(tol), cs.arcs, cs.chords, st.points, st.worst_planar, st.worst_helix,
              100.0 * st.over_one / st.points);
}

TEST(ArcChordsStepped, At1000StepsPerMm) { stepped_sweep(1000, 21); }
TEST(ArcChordsStepped, At80StepsPerMm) { stepped_sweep(80, 41); }
TEST(ArcChordsStepped, At25StepsPerMm) { stepped_sweep(25, 41); }

// seed-002 §4's circular-DDA vectors (steps, start at 0, 0).
TEST(ArcChordsSeedVectors, EndExactly) {
  struct V {
    int32_t x, y, i, j;
    bool cw;
  } const vs[] = {{-100, 100, -100, 0, false}, {-100, -100, -100, 0, true}, {1000, -1000, 0, -1000, true},
                  {-200, 0, -100, 0, false}};
  for (const V& v : vs) {
    Arc a = {};
    a.plane0 = 0;
    a.plane1 = 1;
    a.to[0] = v.x;
    a.to[1] = v.y;
    a.centre[0] = v.i;
    a.centre[1] = v.j;
    a.cw = v.cw;
    a.tol = 0.25f;
    ChordStats st;
    Chords chords;
    check_chords(a, st, "seed vector", chords);
    if (HasFatalFailure()) return;
    int32_t end[kAxes];
    Stepped stepped;
    step_chords(a, chords, end, stepped);
    EXPECT_EQ(end[0], v.x);
    EXPECT_EQ(end[1], v.y);
  }
}

TEST(ArcChordsPlanes, G18AndG19WithTheNormalAxisAsHelix) {
  ChordStats st;
  for (int plane = 0; plane < 2; ++plane)
    for (int cw = 0; cw < 2; ++cw) {
      // G18: (Z, X), G19: (Y, Z); build the G17 arc and move its axes.
      const int32_t c[2] = {1000, -2000};
      const Arc g17 = make_arc(123456, 0.3, cw ? -250 : 250, 40, c, 77777, 5555, 5);
      const uint8_t first = plane ? 1 : 2, second = plane ? 2 : 0, normal = plane ? 0 : 1;
      Arc a = g17;
      a.plane0 = first;
      a.plane1 = second;
      a.from[first] = g17.from[0], a.to[first] = g17.to[0];
      a.from[second] = g17.from[1], a.to[second] = g17.to[1];
      a.from[normal] = g17.from[2], a.to[normal] = g17.to[2];
      Chords chords;
      check_chords(a, st, plane ? "G19" : "G18", chords);
    }
  EXPECT_EQ(st.arcs, 4u);
}

TEST(ArcChordsCount, SmallArcIsOneChordAndLargeToleranceToo) {
  am::ArcChords<2> arc;
  const int32_t from[2] = {0, 0}, to[2] = {10, 1}, centre[2] = {0, 1000};  // a 0.57 degree arc
  ASSERT_TRUE(arc.start(from, to, 0, 1, centre, false, 5));
  EXPECT_EQ(arc.chords(), 1u);
  int32_t p[2];
  ASSERT_TRUE(arc.next(p));
  EXPECT_EQ(p[0], 10);
  EXPECT_EQ(p[1], 1);
  EXPECT_FALSE(arc.next(p));
  // A full circle with the tolerance at least its diameter: one chord back to the start.
  ASSERT_TRUE(arc.start(from, from, 0, 1, centre, true, 2000));
  EXPECT_EQ(arc.chords(), 1u);
  // Just below: the sag of a half circle is r, so 2 chords.
  ASSERT_TRUE(arc.start(from, from, 0, 1, centre, true, 1999));
  EXPECT_EQ(arc.chords(), 2u);
  // Exactly r (1 - cos 60 deg) = r / 2 for three chords.
  ASSERT_TRUE(arc.start(from, from, 0, 1, centre, true, 500));
  EXPECT_EQ(arc.chords(), 3u);
}

TEST(ArcChordsCount, FullCircleAtOneLuOfToleranceIsThousandsOfChords) {
  am::ArcChords<2> arc;
  const int32_t from[2] = {0, 0}, centre[2] = {5000000, 0};
  ASSERT_TRUE(arc.start(from, from, 0, 1, centre, false, 1));
  // 2 pi / (4 asin(sqrt(1 / 2r))) = 4967.29
  EXPECT_EQ(arc.chords(), 4968u);
}

TEST(ArcChordsRefuses, BadInputChangesNothing) {
  am::ArcChords<3> arc;
  const int32_t from[3] = {100, 200, 300}, to[3] = {2100, 200, 900}, centre[2] = {1000, 0};
  ASSERT_TRUE(arc.start(from, to, 0, 1, centre, false, 5));
  const unsigned n = arc.chords();
  int32_t first[3], p[3];
  ASSERT_TRUE(arc.next(first));

  const int32_t zero[2] = {0, 0}, far[2] = {1000000000, 0}, huge[2] = {INT32_MIN, 0};
  const int32_t edge_from[3] = {2147482000, 0, 0}, edge_to[3] = {2147482000, 0, 0};
  const int32_t to_centre[3] = {1100, 200, 0};
  EXPECT_FALSE(arc.start(from, to, 0, 1, zero, false, 5));             // zero radius
  EXPECT_FALSE(arc.start(from, to_centre, 0, 1, centre, false, 5));    // ends on the centre
  EXPECT_FALSE(arc.start(from, to, 0, 1, centre, false, 0));           // tolerance
  EXPECT_FALSE(arc.start(from, to, 1, 1, centre, false, 5));           // plane
  EXPECT_FALSE(arc.start(from, to, 0, 3, centre, false, 5));           // plane
  EXPECT_FALSE(arc.start(from, from, 0, 1, far, false, 1));            // 70248 chords
  EXPECT_FALSE(arc.start(from, to, 0, 1, huge, false, 5));             // -centre does not fit
  EXPECT_FALSE(arc.start(edge_from, edge_to, 0, 1, centre, false, 5));  // circle beyond int32
  const int32_t big_centre[2] = {1000000000, 0};
  const int32_t low[3] = {-2147000000, 0, 0}, high[3] = {2147000000, 0, 0};
  EXPECT_FALSE(arc.start(edge_from, edge_to, 0, 1, big_centre, false, 5));  // from + centre overflows
  EXPECT_FALSE(arc.start(low, high, 0, 1, centre, false, 5));               // to - centre overflows

  EXPECT_EQ(arc.chords(), n);  // the first arc goes on where it was
  am::ArcChords<3> fresh;
  ASSERT_TRUE(fresh.start(from, to, 0, 1, centre, false, 5));
  ASSERT_TRUE(fresh.next(p));
  for (int i = 0; i < 3; ++i) ASSERT_EQ(p[i], first[i]);
  for (unsigned k = 2; k <= n; ++k) {
    int32_t q[3];
    ASSERT_TRUE(arc.next(p));
    ASSERT_TRUE(fresh.next(q));
    for (int i = 0; i < 3; ++i) ASSERT_EQ(p[i], q[i]);
  }
  EXPECT_FALSE(arc.next(p));
  EXPECT_FALSE(am::ArcChords<3>().next(p));  // nothing started
}

}  // namespace
