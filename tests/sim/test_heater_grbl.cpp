// The heater's lines in grbl style, on the m32-grbl image (the printer's
// program for grbl hosts, firmware/boards/m32-grbl.h): a grbl host reads
// `ok`, `error:N`, `ALARM:N`, `<...>` reports and `[MSG:...]` lines, and
// takes anything else for noise or an answer. So every status, gain and
// fault line the heater prints is a `[MSG:...]` there, a refusal is
// `[MSG:reason]` and `error:107`, and M105 answers its status and then
// `ok`. The Marlin-style lines are tests/sim/test_heater.cpp's.
#include <regex>
#include <string>
#include <vector>

#include "heater_rig.h"

namespace {

using heatertest::HotEnd;
using heatertest::kHz;

const std::regex kGrblLine(R"(ok|error:\d+|ALARM:\d+|\[MSG:.*\]|<.*>|Grbl 1\.1h \['\$' for help\])");
const std::regex kStatusMsg(R"(\[MSG:T:(\d+\.\d\d) /(\d+\.\d\d) @:(\d+)\])");

TEST(HeaterGrbl, EveryHeaterLineIsAGrblLine) {
  HotEnd h(25, 40, "m32-grbl");
  for (const char* l : {"M105", "M104 S300", "M301 P30.5 I2 D80", "M155 S1", "M109 S50", "M155 S0", "M500"}) h.send(l);
  h.plant->inject_at(16.0, sim::ThermalFault::sensor_open);
  h.run_until(18.0);
  h.m->serial().send_raw("M104 S60\n");
  h.run_until(19.0);
  const std::vector<std::string>& got = h.m->serial().received();
  const auto at = [&](size_t i) { return double(h.m->serial().received_cycles()[i]) / kHz; };
  // Index of the first received line equal to `line` from `from` on.
  const auto find = [&](const std::string& line, size_t from) {
    for (size_t i = from; i < got.size(); ++i)
      if (got[i] == line) return i;
    return got.size();
  };
  for (size_t i = 0; i < got.size(); ++i) EXPECT_TRUE(std::regex_match(got[i], kGrblLine)) << i << ": " << got[i];

  // M105: its status line, then ok; the reading near the plant's 25 C.
  const size_t banner = h.m->serial().banner_lines();
  std::smatch s;
  ASSERT_TRUE(std::regex_match(got.at(banner), s, kStatusMsg)) << got.at(banner);
  EXPECT_NEAR(std::stod(s[1]), 25.0, 1.0);
  EXPECT_EQ(s[2], "0.00");
  EXPECT_EQ(got.at(banner + 1), "ok");
  // The refused target: its reason, error:107, and nothing changed.
  EXPECT_EQ(got.at(banner + 2), "[MSG:temperature must be 0 .. 260 C]");
  EXPECT_EQ(got.at(banner + 3), "error:107");
  EXPECT_EQ(got.at(banner + 4), "[MSG:p:30.50 i:2.00 d:80.00]");
  EXPECT_EQ(got.at(banner + 5), "ok");

  // M155 S1 and M109 S50: status lines a second apart, the target 50 while
  // waiting, until the wait's ok; M155 S0's ok ends the reports.
  const size_t wait_ok = find("ok", banner + 7);
  ASSERT_LT(wait_ok, got.size());
  std::vector<double> status_at;
  for (size_t i = banner + 7; i < wait_ok; ++i) {
    ASSERT_TRUE(std::regex_match(got[i], s, kStatusMsg)) << got[i];
    EXPECT_EQ(s[2], "50.00");
    status_at.push_back(at(i));
  }
  ASSERT_GE(status_at.size(), 10u);  // 25 -> 49 C takes well over 10 s
  double reached = -1;  // the plant's thermistor at 49 C (Marlin's 1 C window)
  for (const sim::ThermalSample& t : h.plant->log())
    if (reached < 0 && t.sensor_c > 49.0) reached = t.t_s;
  EXPECT_NEAR(at(wait_ok), reached, 1.5);
  EXPECT_EQ(got.at(wait_ok + 1), "ok");  // M155 S0
  EXPECT_EQ(got.at(wait_ok + 2), "[MSG:Settings Stored: p:30.50 i:2.00 d:80.00]");
  EXPECT_EQ(got.at(wait_ok + 3), "ok");

  // The thermistor breaks at 16 s: one fault line within a second, the
  // heater off, and the next target refused with the fault's name.
  std::vector<size_t> faults;
  for (size_t i = 0; i < got.size(); ++i)
    if (got[i].find("heater halted until reset") != std::string::npos) faults.push_back(i);
  ASSERT_EQ(faults.size(), 1u);
  const std::string& line = got[faults[0]];
  const bool mintemp = line.find("MINTEMP") != std::string::npos;  // an open sensor may read below 5 C first
  const std::string fault = mintemp ? "MINTEMP triggered" : "Thermistor open";
  EXPECT_EQ(line, "[MSG:" + fault + ", heater halted until reset]");
  EXPECT_GT(at(faults[0]), 16.0);
  EXPECT_LE(at(faults[0]), 17.0);
  const size_t refused = find("[MSG:heater halted (" + fault + "), reset to clear]", faults[0]);
  ASSERT_LT(refused + 1, got.size());
  EXPECT_EQ(got[refused + 1], "error:107");
  const auto& pin = h.plant->heater_pin();
  ASSERT_FALSE(pin.empty());
  EXPECT_FALSE(pin.back().level);
  EXPECT_LE(double(pin.back().cycle) / kHz, 17.0);
  std::printf("grbl style: %zu status lines during M109 S50 (%.1f s), fault line %.0f ms after the break\n",
              status_at.size(), at(wait_ok), (at(faults[0]) - 16.0) * 1000);
}

}  // namespace
