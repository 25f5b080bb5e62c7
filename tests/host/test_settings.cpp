// The settings block and table (core/board/settings.h): the layout per
// board shape, the block's round trip, corruption and older versions, every
// range edge, the engine's limits, the parsing and the conversions.
#include "core/board/settings.h"

#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "core/text/gcode_interpreter.h"

namespace {

using namespace am::settings;

// The three shapes the boards have: m32-direct (4 axes, switches on X Y Z),
// m32-cnc (4 axes, no switches), the m32 printer (switches and a heater).
using Direct = Layout<4, 0x07, 0>;
using Cnc = Layout<4, 0, 0>;
using Printer = Layout<4, 0x07, kHeaterGains>;
// The m1284: the printer's with every part.
using Whole = Layout<4, 0x07, kHeaterGains | kPinPolarities | kPathAccels | kRetraction>;

std::vector<uint16_t> numbers_of(uint8_t count, Entry (*at)(uint8_t)) {
  std::vector<uint16_t> n;
  for (uint8_t i = 0; i < count; ++i) n.push_back(number(at(i)));
  return n;
}

TEST(Settings, TheLayoutsListGrblsNumbersInOrder) {
  const std::vector<uint16_t> cnc = {11, 100, 101, 102, 103, 110, 111, 112, 113, 120, 121, 122, 123, 200};
  EXPECT_EQ(numbers_of(Cnc::count(), Cnc::at), cnc);
  const std::vector<uint16_t> direct = {11,  20,  21,  22,  23,  100, 101, 102, 103, 110, 111, 112, 113, 120, 121,
                                        122, 123, 130, 131, 132, 200, 240, 241, 242, 250, 251, 252, 270, 271, 272};
  EXPECT_EQ(numbers_of(Direct::count(), Direct::at), direct);
  std::vector<uint16_t> printer = direct;
  for (uint16_t n : {300, 301, 302}) printer.push_back(n);
  EXPECT_EQ(numbers_of(Printer::count(), Printer::at), printer);
  // One switch on axis 2 only: its travel and homing entries name axis 2.
  using OneSwitch = Layout<3, 0x04, 0>;
  const std::vector<uint16_t> one = {11, 20, 21, 22, 23, 100, 101, 102, 110, 111, 112,
                                     120, 121, 122, 132, 200, 242, 252, 272};
  EXPECT_EQ(numbers_of(OneSwitch::count(), OneSwitch::at), one);
  for (uint8_t i = 0; i < Direct::count(); ++i) EXPECT_EQ(Direct::find(number(Direct::at(i))), i);
  EXPECT_EQ(Direct::find(24), -1);
  EXPECT_EQ(Direct::find(103 + 30), -1);
  EXPECT_EQ(Cnc::find(20), -1);
  EXPECT_EQ(unsigned(Cnc::Values::kSummed), 4u + 4u * 14);  // and the sum: 62 bytes of EEPROM
}

TEST(Settings, TheOptionalPartsTakeTheirPlacesInGrblsOrder) {
  std::vector<uint16_t> whole = {3, 5};
  for (uint16_t n : numbers_of(Printer::count(), Printer::at)) {
    whole.push_back(n);
    if (n == 200)
      for (uint16_t m : {210, 211, 212, 220, 221, 222, 223, 224}) whole.push_back(m);
  }
  EXPECT_EQ(numbers_of(Whole::count(), Whole::at), whole);
  EXPECT_EQ(unsigned(Whole::count()), 43u);
  // M204's three slots name their slot as the entry's axis.
  for (uint8_t k = 0; k < 3; ++k) EXPECT_EQ(Whole::at(uint8_t(Whole::find(uint16_t(210 + k)))).axis, k);
  // No switches: the direction mask alone.
  using NoSwitch = Layout<4, 0, kPinPolarities>;
  std::vector<uint16_t> no_switch = {3};
  for (uint16_t n : numbers_of(Cnc::count(), Cnc::at)) no_switch.push_back(n);
  EXPECT_EQ(numbers_of(NoSwitch::count(), NoSwitch::at), no_switch);
  EXPECT_EQ(Printer::find(3), -1);
  EXPECT_EQ(Printer::find(5), -1);
}

// A block as the m32 images' defaults make it (1000 steps/mm, 2400 mm/min,
// 500 mm/s^2; the printer's homing).
template <typename L>
typename L::Values defaults() {
  typename L::Values b;
  std::memset(&b, 0, sizeof b);
  for (uint8_t i = 0; i < L::count(); ++i) {
    const Entry e = L::at(i);
    uint32_t& v = b.value[i];
    switch (e.kind) {
      case Kind::junction: v = 10; break;
      case Kind::soft_limits: case Kind::hard_limits: case Kind::homing: v = 1; break;
      case Kind::steps: v = 1000000; break;
      case Kind::rate: v = rate_mm(40000, 1000000); break;
      case Kind::accel: v = accel_mm(500000, 1000000); break;
      case Kind::travel: v = length_mm(e.axis == 2 ? 180000 : 200000, 1000000); break;
      case Kind::protocol: v = 0; break;
      case Kind::locate: v = rate_mm(e.axis == 2 ? 500 : 1000, 1000000); break;
      case Kind::seek: v = rate_mm(e.axis == 2 ? 4000 : 25000, 1000000); break;
      case Kind::pull_off: v = length_mm(1000, 1000000); break;
      case Kind::gain_p: v = 22200; break;
      case Kind::gain_i: v = 1080; break;
      case Kind::gain_d: v = 114000; break;
      case Kind::retract_length: v = 3000; break;
      case Kind::retract_feed: v = 2700000; break;
      case Kind::recover_feed: v = 480000; break;
      default: break;
    }
  }
  L::seal(b, 3);
  return b;
}

const EngineLimits<4> kM32{{40000, 40000, 40000, 40000}, 800000};

TEST(Settings, TheDefaultsAreTheBoardsFiguresInMillimetres) {
  const auto b = defaults<Printer>();
  EXPECT_EQ(b.value[Printer::find(110)], 2400000u);  // 40000 steps/s at 1000 steps/mm: 2400 mm/min
  EXPECT_EQ(b.value[Printer::find(120)], 500000u);   // 500 mm/s^2
  EXPECT_EQ(b.value[Printer::find(250)], 1500000u);  // 25 mm/s
  EXPECT_EQ(b.value[Printer::find(252)], 240000u);   // 4 mm/s
  EXPECT_EQ(b.value[Printer::find(132)], 180000u);   // 180 mm
  EXPECT_EQ(Printer::validate(b, kM32), Error::none);
  EXPECT_EQ(Printer::examine(b, 3, kM32), Loaded::ok);
}

TEST(Settings, ABlockSurvivesItsBytesAndAnyChangedByteIsSeen) {
  const auto b = defaults<Direct>();
  std::vector<uint8_t> bytes(sizeof b);
  std::memcpy(bytes.data(), &b, sizeof b);
  Direct::Values back;
  std::memcpy(&back, bytes.data(), sizeof back);
  EXPECT_EQ(Direct::examine(back, 3, kM32), Loaded::ok);
  EXPECT_EQ(std::memcmp(&back, &b, sizeof b), 0);
  // Every bit of every byte: never ok again.
  for (size_t i = 0; i < Direct::Values::kSummed + 2u; ++i) {  // the bytes the EEPROM holds (the host pads)
    for (uint8_t bit = 0; bit < 8; ++bit) {
      std::vector<uint8_t> torn = bytes;
      torn[i] ^= uint8_t(1u << bit);
      Direct::Values t;
      std::memcpy(&t, torn.data(), sizeof t);
      const Loaded l = Direct::examine(t, 3, kM32);
      EXPECT_NE(l, Loaded::ok) << "byte " << i << " bit " << int(bit);
      // A changed byte past the header is a checksum failure.
      if (i >= sizeof(Header)) {
        EXPECT_EQ(l, Loaded::corrupt) << i;
      }
    }
  }
  // Erased cells, and zeros: no tag.
  std::memset(&back, 0xFF, sizeof back);
  EXPECT_EQ(Direct::examine(back, 3, kM32), Loaded::blank);
  std::memset(&back, 0, sizeof back);
  EXPECT_EQ(Direct::examine(back, 3, kM32), Loaded::blank);
}

TEST(Settings, AnOlderVersionOrAnotherLayoutIsNotTaken) {
  auto b = defaults<Direct>();
  EXPECT_EQ(Direct::examine(b, 4, kM32), Loaded::older);  // this firmware is version 4, the block 3
  Direct::seal(b, 2);
  EXPECT_EQ(Direct::examine(b, 3, kM32), Loaded::older);
  Direct::seal(b, 3);
  b.header.count = Cnc::count();  // another board's layout under the same tag
  b.sum = checksum(&b, Direct::Values::kSummed);
  EXPECT_EQ(Direct::examine(b, 3, kM32), Loaded::older);
  // A sealed block whose value is out of its range (written by a build
  // with other ranges) is corrupt, not used.
  b = defaults<Direct>();
  b.value[Direct::find(11)] = 0;
  Direct::seal(b, 3);
  EXPECT_EQ(Direct::examine(b, 3, kM32), Loaded::corrupt);
}

std::string text(const char* fmt, double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, fmt, v);
  return buf;
}

// Every settable entry's range: the edges taken, one unit beyond refused
// with nothing changed. Steps/mm are set so that the derived figures stay
// inside generous engine limits (the edges of the ranges, not of the
// engine).
TEST(Settings, EveryRangeEdgeOfEveryEntry) {
  const EngineLimits<4> wide{{0xFFFFFFFFu, 0xFFFFFFFFu, 0xFFFFFFFFu, 0xFFFFFFFFu}, 0xFFFFFFFFu};
  int edges = 0;
  for (uint8_t i = 0; i < Whole::count(); ++i) {
    const Entry e = Whole::at(i);
    if (read_only(e.kind) || e.kind == Kind::dir_invert) continue;  // $3: its own test (masks below 100)
    const Range r = range(e.kind);
    const double unit = digits(e.kind) ? 1000.0 : 1.0;
    const char* fmt = digits(e.kind) ? "%.3f" : "%.0f";
    for (int high = 0; high < 2; ++high) {
      auto b = defaults<Whole>();
      // Small figures need many steps per mm to be a step at all; large ones few.
      for (uint8_t a = 0; a < 4; ++a) b.value[Whole::find(uint16_t(100 + a))] = high ? 1000 : 10000000;
      for (uint8_t k = 0; k < Whole::count(); ++k) {
        const Kind kk = Whole::at(k).kind;
        if (kk == Kind::seek || kk == Kind::locate) b.value[k] = 60000;   // 60 mm/min
        if (kk == Kind::pull_off) b.value[k] = 0;
      }
      if (e.kind == Kind::steps) {  // every derived figure fits both ends
        for (uint8_t k = 0; k < Whole::count(); ++k) {
          const Kind kk = Whole::at(k).kind;
          if (kk == Kind::rate || kk == Kind::seek || kk == Kind::locate) b.value[k] = 60000;  // 60 mm/min
          if (kk == Kind::accel) b.value[k] = 10000;
          if (kk == Kind::travel) b.value[k] = 1000000;
        }
      }
      ASSERT_EQ(Whole::validate(b, wide), Error::none) << number(e);
      const uint32_t edge = high ? r.max : r.min;
      EXPECT_EQ(Whole::set(b, number(e), text(fmt, edge / unit).c_str(), wide), Error::none)
          << number(e) << "=" << text(fmt, edge / unit);
      EXPECT_EQ(b.value[i], edge) << number(e);
      const auto before = b;
      const double beyond = high ? (double(edge) + 1) / unit : (double(edge) - 1) / unit;
      EXPECT_EQ(Whole::set(b, number(e), text(fmt, beyond).c_str(), wide), Error::out_of_range)
          << number(e) << "=" << text(fmt, beyond);
      EXPECT_EQ(std::memcmp(&b, &before, sizeof b), 0) << number(e);
      ++edges;
    }
  }
  EXPECT_EQ(edges, 2 * (Whole::count() - 3));  // all but the read-only $21 and $23, and $3
}

// $3 takes every mask of the four axes and nothing above; $5 is 0 or 1;
// both whole numbers; a refusal leaves the block as it was.
TEST(Settings, ThePolaritiesTakeTheirMasksAndNothingElse) {
  const EngineLimits<4> limits{{40000, 40000, 40000, 40000}, 800000};
  auto b = defaults<Whole>();
  ASSERT_EQ(Whole::validate(b, limits), Error::none);
  for (int v = 0; v <= 120; ++v) {
    const auto before = b;
    const Error e = Whole::set(b, 3, std::to_string(v).c_str(), limits);
    if (v < 16) {
      EXPECT_EQ(e, Error::none) << v;
      EXPECT_EQ(b.value[Whole::find(3)], uint32_t(v));
    } else {
      EXPECT_EQ(e, Error::out_of_range) << v;
      EXPECT_EQ(std::memcmp(&b, &before, sizeof b), 0) << v;
    }
    const Error l = Whole::set(b, 5, std::to_string(v).c_str(), limits);
    EXPECT_EQ(l, v < 2 ? Error::none : Error::out_of_range) << v;
  }
  EXPECT_EQ(Whole::set(b, 3, "1.0", limits), Error::bad_number);
  EXPECT_EQ(Whole::set(b, 5, "-1", limits), Error::out_of_range);
  // A stored block whose mask is beyond the axes is not taken.
  b.value[Whole::find(3)] = 16;
  Whole::seal(b, 3);
  EXPECT_EQ(Whole::examine(b, 3, limits), Loaded::corrupt);
}

TEST(Settings, TheEngineLimitsHoldWhateverIsSet) {
  auto b = defaults<Direct>();
  const auto before = b;
  // 2400 mm/min is 40000 steps/s at 1000 steps/mm: the top; 2400.001 is
  // 40000.02 steps/s, rounded to 40000 (taken); 2400.030 is 40000.5: refused.
  EXPECT_EQ(Direct::set(b, 110, "2400.001", kM32), Error::none);
  EXPECT_EQ(Direct::set(b, 110, "2400.030", kM32), Error::engine_limit);
  EXPECT_EQ(b.value[Direct::find(110)], 2400001u);
  EXPECT_EQ(Direct::set(b, 110, "2400", kM32), Error::none);
  EXPECT_EQ(std::memcmp(&b, &before, sizeof b), 0);
  // 800 mm/s^2 is 800000 steps/s^2, the top.
  EXPECT_EQ(Direct::set(b, 121, "800", kM32), Error::none);
  EXPECT_EQ(Direct::set(b, 121, "800.001", kM32), Error::engine_limit);
  EXPECT_EQ(b.value[Direct::find(121)], 800000u);
  // Steps/mm that would make the rates above the engine's: refused, the
  // rate stays what it was.
  EXPECT_EQ(Direct::set(b, 100, "1000.001", kM32), Error::none);  // 40000.04 steps/s: 40000
  EXPECT_EQ(Direct::set(b, 100, "1000.02", kM32), Error::engine_limit);  // 40000.8
  EXPECT_EQ(b.value[Direct::find(100)], 1000001u);
  EXPECT_EQ(Direct::set(b, 100, "1000", kM32), Error::none);
  EXPECT_EQ(Direct::set(b, 102, "500", kM32), Error::none);  // half: 20000 steps/s
  EXPECT_EQ(b.value[Direct::find(102)], 500000u);
  // A homing feed beyond 65535 steps/s or the axis's rate: refused.
  EXPECT_EQ(Direct::set(b, 250, "2400", kM32), Error::none);
  EXPECT_EQ(Direct::set(b, 250, "2401", kM32), Error::engine_limit);
  // A rate below one step a second: refused. At 1 step/mm Z's 2400
  // mm/min are 40 steps/s, its locate feed of 30 mm/min half a step: one.
  EXPECT_EQ(Direct::set(b, 102, "1", kM32), Error::none);
  EXPECT_EQ(Direct::set(b, 112, "1", kM32), Error::engine_limit);  // 0.017 steps/s
  EXPECT_EQ(Direct::set(b, 112, "29.999", kM32), Error::engine_limit);  // 0.49998
  EXPECT_EQ(Direct::set(b, 112, "30", kM32), Error::none);          // 0.5: one
  EXPECT_EQ(Direct::set(b, 242, "29.999", kM32), Error::engine_limit);
}

TEST(Settings, ParsingRoundsAndRefusesWhatIsNotANumber) {
  auto b = defaults<Direct>();
  EXPECT_EQ(Direct::set(b, 100, "80.0005", kM32), Error::none);
  EXPECT_EQ(b.value[Direct::find(100)], 80001u);
  EXPECT_EQ(Direct::set(b, 100, "80.0004999", kM32), Error::none);
  EXPECT_EQ(b.value[Direct::find(100)], 80000u);
  EXPECT_EQ(Direct::set(b, 100, "+79.9995", kM32), Error::none);
  EXPECT_EQ(b.value[Direct::find(100)], 80000u);
  const auto before = b;
  EXPECT_EQ(Direct::set(b, 100, "", kM32), Error::bad_number);
  EXPECT_EQ(Direct::set(b, 100, "abc", kM32), Error::bad_number);
  EXPECT_EQ(Direct::set(b, 100, "80x", kM32), Error::bad_number);
  EXPECT_EQ(Direct::set(b, 100, "80 ", kM32), Error::bad_number);
  EXPECT_EQ(Direct::set(b, 100, "1.2.3", kM32), Error::bad_number);
  EXPECT_EQ(Direct::set(b, 100, "-80", kM32), Error::out_of_range);
  EXPECT_EQ(Direct::set(b, 100, "99999999999", kM32), Error::out_of_range);
  EXPECT_EQ(Direct::set(b, 20, "0.5", kM32), Error::bad_number);  // a flag is whole
  EXPECT_EQ(Direct::set(b, 20, "1.", kM32), Error::bad_number);
  EXPECT_EQ(Direct::set(b, 20, "2", kM32), Error::out_of_range);
  EXPECT_EQ(Direct::set(b, 21, "0", kM32), Error::read_only);
  EXPECT_EQ(Direct::set(b, 23, "1", kM32), Error::read_only);
  EXPECT_EQ(Direct::set(b, 200, "2", kM32), Error::out_of_range);  // the style: 0 grbl, 1 Marlin
  EXPECT_EQ(Direct::set(b, 200, "1.0", kM32), Error::bad_number);
  EXPECT_EQ(Direct::set(b, 24, "1", kM32), Error::unknown);
  EXPECT_EQ(Direct::set(b, 104, "1", kM32), Error::unknown);
  EXPECT_EQ(std::memcmp(&b, &before, sizeof b), 0);
  EXPECT_EQ(Direct::set(b, 20, "0", kM32), Error::none);
  EXPECT_EQ(b.value[Direct::find(20)], 0u);
  EXPECT_EQ(Direct::set(b, 200, "1", kM32), Error::none);
  EXPECT_EQ(b.value[Direct::find(200)], 1u);
}

// Marlin's M203 gives mm/s for a setting in mm/min (per_second): the
// number times 60, then the same checks.
TEST(Settings, SetTimesScalesTheNumberFirst) {
  auto b = defaults<Direct>();
  const auto before = b;
  EXPECT_EQ(Direct::set(b, 110, "40.001", kM32, true), Error::engine_limit);  // 2400.06 mm/min: 40001 steps/s
  EXPECT_EQ(Direct::set(b, 110, "16666.667", kM32, true), Error::out_of_range);  // 1000000.02 mm/min: the range's
  EXPECT_EQ(Direct::set(b, 110, "16666.666", kM32, true), Error::engine_limit);  // in range, beyond the engine
  EXPECT_EQ(Direct::set(b, 110, "35791.395", kM32, true), Error::out_of_range);  // beyond 2^31 - 1 thousandths
  EXPECT_EQ(Direct::set(b, 110, "-1", kM32, true), Error::out_of_range);
  EXPECT_EQ(Direct::set(b, 110, "x", kM32, true), Error::bad_number);
  EXPECT_EQ(std::memcmp(&b, &before, sizeof b), 0);
  EXPECT_EQ(Direct::set(b, 110, "20.5", kM32, true), Error::none);
  EXPECT_EQ(b.value[Direct::find(110)], 1230000u);  // 1230 mm/min
}

TEST(Settings, TheLinesSayNumberAndValue) {
  char buf[24];
  EXPECT_EQ(format(buf, Entry{Kind::steps, 0}, 80000), 11);
  EXPECT_STREQ(buf, "$100=80.000");
  format(buf, Entry{Kind::rate, 3}, 1000000000);
  EXPECT_STREQ(buf, "$113=1000000.000");
  format(buf, Entry{Kind::soft_limits, 0}, 1);
  EXPECT_STREQ(buf, "$20=1");
  format(buf, Entry{Kind::homing_dir, 0}, 0);
  EXPECT_STREQ(buf, "$23=0");
  format(buf, Entry{Kind::junction, 0}, 10);
  EXPECT_STREQ(buf, "$11=0.010");
  format(buf, Entry{Kind::pull_off, 2}, 0);
  EXPECT_STREQ(buf, "$272=0.000");
  format(buf, Entry{Kind::gain_d, 0}, 114000);
  EXPECT_STREQ(buf, "$302=114.000");
}

TEST(Settings, ConversionsAgreeWithArithmeticDoneIndependently) {
  EXPECT_EQ(rate_steps(2400000, 1000000), 40000u);
  EXPECT_EQ(rate_steps(500000, 80000), 667u);        // 500 mm/min at 80 steps/mm: 666.67 steps/s
  EXPECT_EQ(accel_steps(500000, 80000), 40000u);     // 500 mm/s^2 at 80 steps/mm
  EXPECT_EQ(length_steps(1000, 80000), 80u);         // 1 mm
  EXPECT_EQ(rate_mm(667, 80000), 500250u);           // 667 steps/s: 500.25 mm/min
  EXPECT_EQ(length_mm(200000, 1000000), 200000u);
  EXPECT_EQ(rate_steps(1000000000u, 10000000u), 166666667u);  // the range's corner: fits
  EXPECT_EQ(accel_steps(1000000000u, 10000000u), 0xFFFFFFFFu);  // 10^10: beyond, said so
  // Down from a board's figure and up again: the figure itself while
  // 0.0005 of the unit is under half a step (kPerRate: 0.5 * spm / 6e7;
  // lengths: 0.5 * spm / 1e6), within one step beyond.
  uint32_t seed = 12345;
  int exact = 0;
  for (int n = 0; n < 20000; ++n) {
    seed = seed * 1103515245u + 12345u;
    const uint32_t spm = 1000 + seed % 10000000;
    seed = seed * 1103515245u + 12345u;
    const uint32_t steps = 1 + seed % 800000;
    const double mm = double(steps) * 60e6 / spm;
    if (mm > 2147483647.0) continue;
    EXPECT_NEAR(double(rate_mm(steps, spm)), mm, 0.5 + 1e-6);  // against double arithmetic
    EXPECT_EQ(rate_steps(rate_mm(steps, spm), spm), steps) << spm << " " << steps;  // always: spm <= 1e7
    const uint32_t a = accel_steps(accel_mm(steps, spm), spm);
    if (spm < 1000000) {
      EXPECT_EQ(a, steps) << spm << " " << steps;
      ++exact;
    } else {
      EXPECT_NEAR(double(a), double(steps), 0.5 * spm / 1e6 + 0.5) << spm << " " << steps;
    }
  }
  EXPECT_GT(exact, 1000);
}

// The interpreter's scale changed at rest: the machine position in steps
// and the G92 offset stay, the program position follows.
TEST(Settings, TheInterpreterKeepsStepsWhenTheScaleChanges) {
  am::GcodeAxis axes[2] = {{'X', 0, 1000000}, {'Y', 0, 80000}};
  am::GcodeInterpreter<2, false, false> in(axes);
  am::GcodeAction<2> a;
  ASSERT_EQ(in.run("G1 X10 Y2.5 F100", a), am::GcodeError::none);
  EXPECT_EQ(in.state().axis[0].steps, 10000);
  EXPECT_EQ(in.state().axis[1].steps, 200);
  ASSERT_EQ(in.run("G92 X1", a), am::GcodeError::none);  // offset 9000 steps on X
  axes[0].steps_per_m = 800000;  // $100=800
  axes[1].steps_per_m = 40000;   // $101=40
  in.rescale();
  EXPECT_EQ(in.state().axis[0].steps, 10000);
  EXPECT_EQ(in.state().axis[0].offset, 9000);
  EXPECT_EQ(in.state().axis[0].coord, 12500);  // (10000 - 9000) / 800 mm = 1.25 mm
  EXPECT_EQ(in.state().axis[1].steps, 200);
  EXPECT_EQ(in.state().axis[1].coord, 50000);  // 200 / 40 = 5 mm
  ASSERT_EQ(in.run("G1 X2.25 Y6", a), am::GcodeError::none);
  EXPECT_EQ(a.target[0], 10000 + 800);  // 1 mm more at 800 steps/mm
  EXPECT_EQ(a.target[1], 240);          // 6 mm at 40
}

}  // namespace
