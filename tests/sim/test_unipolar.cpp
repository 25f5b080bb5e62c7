// ULN2003 outputs (28BYJ-48) on the real images: the coil patterns on the
// four IN pins, checked against the seed-003 tables (IN1 = A+ = bit 0).
#include <map>
#include <vector>

#include "sim_fixture.h"

namespace {

// The IN1..IN4 pattern after every change of the four pins (changes in the
// same cycle are one port write).
std::vector<uint8_t> patterns(const std::string& image, const std::vector<std::string>& lines, char port,
                              uint8_t first_bit) {
  sim::Machine m(simtest::image(image));
  std::vector<const std::vector<sim::PinEdge>*> logs;
  for (uint8_t k = 0; k < 4; ++k) logs.push_back(&m.watch_pin(port, uint8_t(first_bit + k)));
  for (const std::string& l : lines) m.serial().add_line(l);
  EXPECT_EQ(m.run_script(uint64_t(5) * m.f_cpu()), sim::RunEnd::done);
  std::map<uint64_t, std::vector<std::pair<int, bool>>> by_cycle;
  for (int k = 0; k < 4; ++k) {
    for (const sim::PinEdge& e : *logs[k]) by_cycle[e.cycle].push_back({k, e.level});
  }
  std::vector<uint8_t> out;
  uint8_t p = 0;
  for (const auto& kv : by_cycle) {
    for (const auto& change : kv.second) p = uint8_t(change.second ? p | (1 << change.first) : p & ~(1 << change.first));
    if (out.empty() || out.back() != p) out.push_back(p);
  }
  return out;
}

}  // namespace

TEST(Unipolar, HalfStepForwardFollowsTheUln2003Table) {
  // Coils off at power-up, A+ held when the move starts, then seed-003's
  // half-step table 0x01, 0x03, 0x02, 0x06, 0x04, 0x0C, 0x08, 0x09.
  const std::vector<uint8_t> expected = {0x00, 0x01, 0x03, 0x02, 0x06, 0x04, 0x0C, 0x08, 0x09, 0x01};
  EXPECT_EQ(patterns("m16", {"MODE U2", "MOVE U8"}, 'C', 2), expected);
}

TEST(Unipolar, HalfStepReverseWalksTheTableBackwards) {
  const std::vector<uint8_t> expected = {0x00, 0x01, 0x09, 0x08, 0x0C, 0x04};
  EXPECT_EQ(patterns("m16", {"MODE U2", "MOVE U-4"}, 'C', 2), expected);
}

TEST(Unipolar, WaveAndTwoPhase) {
  // Wave 0x01, 0x02, 0x04, 0x08.
  const std::vector<uint8_t> wave = {0x00, 0x01, 0x02, 0x04, 0x08, 0x01};
  EXPECT_EQ(patterns("m16", {"MODE U0", "MOVE U4"}, 'C', 2), wave);
  // The default, two-phase: held B-A+ then 0x03, 0x06, 0x0C, 0x09.
  const std::vector<uint8_t> two_phase = {0x00, 0x09, 0x03, 0x06, 0x0C, 0x09};
  EXPECT_EQ(patterns("m16", {"MOVE U4"}, 'C', 2), two_phase);
}

TEST(Unipolar, ReleaseSwitchesEveryInputOff) {
  const std::vector<uint8_t> got = patterns("m16", {"MOVE U3", "RELEASE"}, 'C', 2);
  ASSERT_FALSE(got.empty());
  EXPECT_EQ(got.back(), 0x00);
}
