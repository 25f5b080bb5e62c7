// Both line protocols in the m32-direct image, chosen at run time by the
// setting $200 (board::kProtocolSwitch, docs/protocol.md "Choosing the style
// at run time"), and the settings' Marlin codes (M92 M201 M203 M205
// M500..M503, docs/settings.md), on the real image: the switch by `$200=1`,
// a Marlin host's numbered and checksummed exchange after it, the style kept
// through a power cycle, the way back, M503 against `$$`, M502, M501 and
// M500 against what the EEPROM holds, a corrupt block.
#include <sim_avr.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "board_info.h"
#include "printcore_run.h"
#include "pty_client.h"
#include "sim_fixture.h"

namespace {

const char kImage[] = "m32-direct";
constexpr uint32_t kBytes = 4 + 4 * 30 + 2;  // the block: header, 30 values, sum (docs/settings.md)
const char kGrblCorrupt[] = "[MSG:EEPROM settings corrupt: defaults loaded]";
const char kMarlinCorrupt[] = "echo:EEPROM settings corrupt: defaults loaded";

std::vector<uint8_t> eeprom_of(sim::Machine& m) {
  std::vector<uint8_t> bytes = m.eeprom(kBytes);
  EXPECT_EQ(bytes.size(), kBytes);
  return bytes;
}

// A fresh machine (its EEPROM `bytes`, or erased), booted: nothing sent yet.
std::unique_ptr<sim::Machine> machine(const std::vector<uint8_t>& bytes = {}) {
  std::unique_ptr<sim::Machine> m(new sim::Machine(simtest::image(kImage)));
  if (!bytes.empty()) m->set_eeprom(bytes);
  return m;
}

// Sends `lines` (after those already sent) and runs until they are answered
// and motion has ended; returns the index of the first new response.
size_t send(sim::Machine& m, const std::vector<std::string>& lines, double seconds = 10) {
  const size_t first = m.serial().responses().size();
  for (const std::string& l : lines) m.serial().add_line(l);
  EXPECT_EQ(m.run_script(uint64_t(seconds * m.f_cpu())), sim::RunEnd::done);
  return first;
}

// Marlin's checksum: the XOR of every byte before the '*'.
std::string numbered(int n, const std::string& line, int flip = 0) {
  const std::string body = "N" + std::to_string(n) + " " + line;
  int sum = 0;
  for (char c : body) sum ^= uint8_t(c);
  return body + "*" + std::to_string(sum ^ flip);
}

// The lines received from index `from` on.
std::vector<std::string> received_from(sim::Machine& m, size_t from) {
  const std::vector<std::string>& rx = m.serial().received();
  return std::vector<std::string>(rx.begin() + long(std::min(from, rx.size())), rx.end());
}

// The exchange as docs/protocol.md shows it: `> ` what was sent, `< ` what
// came back, in the order of their cycles (the host's closing WAIT left out).
void print_transcript(sim::Machine& m, size_t first_response = 0, size_t first_rx = 0) {
  const std::vector<sim::Response>& sent = m.serial().responses();
  const std::vector<std::string>& rx = m.serial().received();
  const std::vector<uint64_t>& at = m.serial().received_cycles();
  size_t i = first_response, j = first_rx;
  const uint64_t last = sent.empty() ? 0 : sent.back().answer_cycle;
  while (i < sent.size() || (j < rx.size() && at[j] <= last)) {
    if (i < sent.size() && (j >= rx.size() || sent[i].sent_cycle < at[j])) {  // an answer first: its end sends the next
      std::printf("    > %s\n", sent[i++].line.c_str());
    } else {
      // A line after the first sent one that answers none of them is the
      // host's WAIT's.
      bool ours = first_response >= sent.size() || at[j] <= sent[first_response].sent_cycle;
      for (size_t k = first_response; k < sent.size() && !ours; ++k)
        ours = sent[k].sent_cycle < at[j] && at[j] <= sent[k].answer_cycle;
      if (ours) std::printf("    < %s\n", rx[j].c_str());
      ++j;
    }
  }
}

size_t count_of(const std::vector<std::string>& lines, const std::string& line) {
  size_t n = 0;
  for (const std::string& l : lines) n += l == line;
  return n;
}

// `$N=value` lines (grbl's `$$`) among `lines`, by number.
std::map<int, std::string> dollar_lines(const std::vector<std::string>& lines) {
  std::map<int, std::string> s;
  for (const std::string& l : lines) {
    const size_t eq = l.find('=');
    if (l.size() > 1 && l[0] == '$' && eq != std::string::npos) s[std::stoi(l.substr(1, eq - 1))] = l.substr(eq + 1);
  }
  return s;
}

std::string mm3(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f", v);
  return buf;
}

// M503's lines read back into `$N` numbers and values in the settings'
// units: `M92 X.. Y.. Z.. E..` is $100..$103, M203 (mm/s) $110..$113 (in
// mm/min, so times 60), M201 $120..$123, `M205 J` $11, `$N=value` itself.
// Each M-code's numbers are kept as printed (M203's: the mm/s figure), the
// caller compares them with the `$$` figure converted.
struct M503 {
  std::map<int, std::string> value;  // by $ number, as printed
  size_t lines = 0;
  bool well_formed = true;
};
M503 read_m503(const std::vector<std::string>& lines, const std::string& prefix) {
  M503 r;
  const std::string axes = "XYZE";
  for (const std::string& l : lines) {
    if (l.rfind(prefix + "  ", 0) != 0) continue;
    ++r.lines;
    std::string body = l.substr(prefix.size() + 2);
    if (!prefix.empty() && prefix[0] == '[') {
      if (body.empty() || body.back() != ']') r.well_formed = false;
      else body.pop_back();
    }
    if (body[0] == '$') {
      const size_t eq = body.find('=');
      r.value[std::stoi(body.substr(1, eq - 1))] = body.substr(eq + 1);
      continue;
    }
    std::stringstream ss(body);
    std::string code, word;
    ss >> code;
    const int base = code == "M92" ? 100 : code == "M203" ? 110 : code == "M201" ? 120 : code == "M205" ? 11 : -1;
    if (base < 0) r.well_formed = false;
    while (ss >> word) {
      if (base == 11) {
        if (word[0] != 'J') r.well_formed = false;
        r.value[11] = word.substr(1);
        continue;
      }
      const size_t a = axes.find(word[0]);
      if (a == std::string::npos) r.well_formed = false;
      else r.value[base + int(a)] = word.substr(1);
    }
  }
  return r;
}

// Every `$$` setting appears in M503 once, its value the same (M203's in
// mm/s: the `$$` mm/min over 60, to three decimals).
void expect_m503_matches(const M503& got, const std::map<int, std::string>& dollars) {
  EXPECT_TRUE(got.well_formed);
  EXPECT_EQ(got.value.size(), dollars.size());
  for (const auto& d : dollars) {
    const auto it = got.value.find(d.first);
    ASSERT_NE(it, got.value.end()) << "$" << d.first;
    const std::string want = d.first >= 110 && d.first <= 113 ? mm3(std::stod(d.second) / 60) : d.second;
    EXPECT_EQ(it->second, want) << "$" << d.first;
  }
}

TEST(ProtocolSwitch, DollarTwoHundredSwitchesToMarlinAndAMarlinHostIsServed) {
  auto m = machine();
  size_t r = send(*m, {"$$", "$200=1"});
  EXPECT_TRUE(m->serial().marlin());  // the host follows an answered `$200=1` (sim/serial_host.h)
  EXPECT_EQ(m->serial().banner(), "Grbl 1.1h ['$' for help]");
  EXPECT_EQ(dollar_lines(m->serial().messages())[200], "0");
  EXPECT_EQ(m->serial().responses()[r + 1].answer, "ok");  // in grbl's style, before the switch
  const size_t rx = m->serial().received().size();
  const double spmm = m->axis('X')->steps_per_mm;
  r = send(*m, {"M110 N0", numbered(1, "G91"), numbered(2, "G1 X1 F600"),
                numbered(3, "G1 X5 F600", 0x01),  // a bad checksum: refused, not run
                numbered(3, "G1 X2 F600"), numbered(5, "G1 X4 F600"),  // a gap: refused
                numbered(4, "M400"), "M114", "M115", "M105", "G7"});
  const std::vector<sim::Response>& got = m->serial().responses();
  ASSERT_EQ(got.size(), r + 11);
  for (size_t i : {0u, 1u, 2u, 4u, 6u, 7u, 8u, 9u, 10u}) EXPECT_TRUE(sim::SerialHost::is_ok(got[r + i].answer)) << got[r + i].line;
  EXPECT_EQ(got[r + 3].answer, "Error:checksum mismatch, Last Line: 2");
  EXPECT_EQ(got[r + 5].answer, "Error:Line Number is not Last Line Number+1, Last Line: 3");
  print_transcript(*m);  // docs/protocol.md
  const std::vector<std::string> lines = received_from(*m, rx);
  for (size_t i = 0; i < lines.size(); ++i) {
    if (lines[i].rfind("Error:checksum", 0) == 0 || lines[i].rfind("Error:Line Number", 0) == 0) {
      ASSERT_LT(i + 2, lines.size());
      EXPECT_EQ(lines[i + 1], "Resend: " + std::to_string(lines[i].back() - '0' + 1));
      EXPECT_EQ(lines[i + 2], "ok");
    }
  }
  // Only the good lines moved X: 1 + 2 mm, the pins and M114 agree.
  EXPECT_EQ(m->axis('X')->steps(), std::round(3 * spmm));
  char m114[96];
  std::snprintf(m114, sizeof m114, "X:3.0000 Y:0.0000 Z:0.0000 E:0.0000 Count X:%.0f Y:0 Z:0 E:0", std::round(3 * spmm));
  EXPECT_EQ(count_of(lines, m114), 1u);
  EXPECT_EQ(count_of(lines, "FIRMWARE_NAME:avrmotion 0.1.0 SOURCE_CODE_URL:local PROTOCOL_VERSION:1.0 "
                            "MACHINE_TYPE:m32-direct EXTRUDER_COUNT:1"),
            1u);
  EXPECT_EQ(count_of(lines, "Cap:EEPROM:1"), 1u);
  EXPECT_EQ(count_of(lines, "Cap:AUTOREPORT_TEMP:0"), 1u);  // no heater: no M155
  // No heater: M105 is an unknown command (no `Error:` for a host's poll),
  // G7 too; neither ends the exchange.
  EXPECT_EQ(count_of(lines, "echo:Unknown command: \"M105\""), 1u);
  EXPECT_EQ(count_of(lines, "echo:Unknown command: \"G7\""), 1u);
  for (const std::string& l : lines) EXPECT_NE(l.rfind("[MSG:", 0), 0u) << l;  // nothing in grbl's style
}

// Power cycle: the style is the stored $200 (Marlin's banner `start`);
// `$200=0` is read in Marlin style too, the way back.
TEST(ProtocolSwitch, ThePowerCycleKeepsTheStyleAndDollarTwoHundredZeroSwitchesBack) {
  auto first = machine();
  send(*first, {"$200=1"});
  auto second = machine(eeprom_of(*first));
  size_t r = send(*second, {"M115", "G4 P300", "M400", "G4 S1", "M400", "$200=2", "$200=0"});
  EXPECT_FALSE(second->serial().marlin());  // Marlin's banner; the answered `$200=0` turned the host back
  EXPECT_EQ(second->serial().banner(), "start");
  EXPECT_EQ(second->serial().received()[1], "echo:avrmotion 0.1.0 board=m32-direct mcu=atmega32 f_cpu=16000000");
  print_transcript(*second);  // docs/protocol.md
  const std::vector<sim::Response>& got = second->serial().responses();
  ASSERT_EQ(got.size(), r + 7);
  // Marlin's G4: P in milliseconds, S in seconds (grbl's P is seconds).
  const double f = second->f_cpu();
  const double p300 = double(got[r + 2].answer_cycle - got[r + 1].sent_cycle) / f;
  const double s1 = double(got[r + 4].answer_cycle - got[r + 3].sent_cycle) / f;
  EXPECT_GT(p300, 0.300);
  EXPECT_LT(p300, 0.400);
  EXPECT_GT(s1, 1.000);
  EXPECT_LT(s1, 1.100);
  EXPECT_EQ(got[r + 5].answer, "Error:setting out of range");
  EXPECT_EQ(got[r + 6].answer, "ok");
  // grbl from the next line on, and after the next power cycle.
  const size_t rx = second->serial().received().size();
  r = send(*second, {"G7", "G4 P0.2", "M400"});
  print_transcript(*second, r, rx);
  EXPECT_EQ(got[r].answer, "error:20");
  const double p02 = double(got[r + 2].answer_cycle - got[r + 1].sent_cycle) / f;
  std::printf("G4 P300: %.4f s, G4 S1: %.4f s (Marlin); G4 P0.2: %.4f s (grbl), from the line's first byte to M400's ok\n",
              p300, s1, p02);
  EXPECT_GT(p02, 0.200);
  EXPECT_LT(p02, 0.300);
  auto third = machine(eeprom_of(*second));
  send(*third, {"$$"});
  EXPECT_FALSE(third->serial().marlin());
  EXPECT_EQ(third->serial().banner(), "Grbl 1.1h ['$' for help]");
  EXPECT_EQ(dollar_lines(third->serial().messages())[200], "0");
}

// M503 reports the settings in force: every `$$` value, Marlin's codes for
// those Marlin has (checked line by line against `$$` of the same block),
// and the settings-changing codes set what `$$` then lists.
TEST(ProtocolSwitch, M503ReportsWhatDollarDollarListsAndTheMarlinCodesSetIt) {
  auto m = machine();
  send(*m, {"$100=80", "$111=1234.5", "$122=12.25", "$11=0.05", "$132=95.5", "$$", "M503"});
  const std::map<int, std::string> dollars = dollar_lines(m->serial().messages());
  ASSERT_EQ(dollars.size(), 30u);
  const M503 grbl = read_m503(m->serial().messages(), "[MSG:");  // M503 in grbl style: info lines
  expect_m503_matches(grbl, dollars);
  EXPECT_EQ(grbl.lines, 30u - 3 * 4 + 3);  // M92, M203, M201 one line each
  send(*m, {"$200=1"});
  m->serial().set_marlin(true);
  size_t rx = m->serial().received().size();
  send(*m, {"M503"});
  std::map<int, std::string> now = dollars;
  now[200] = "1";
  const std::vector<std::string> report = received_from(*m, rx);
  print_transcript(*m, m->serial().responses().size() - 1, rx);  // docs/settings.md
  const M503 marlin = read_m503(report, "echo:");
  expect_m503_matches(marlin, now);
  EXPECT_EQ(marlin.lines, grbl.lines);
  EXPECT_EQ(report.back(), "ok");
  // The Marlin codes set the table: M92 steps/mm, M203 mm/s, M201 mm/s^2,
  // M205 J (its other words taken, not used); all of a line or nothing.
  size_t r = send(*m, {"M92 X160 E93.5", "M203 Y20.5", "M201 Z250 E40", "M205 J0.02 X5 S0", "M92 X80 Y0.5",
                       "M92 Q1", "M203 Z41", "M201 X", "G90 G1 X10 F600", "M400"});
  const std::vector<sim::Response>& got = m->serial().responses();
  for (size_t i : {0u, 1u, 2u, 3u, 8u, 9u}) EXPECT_EQ(got[r + i].answer, "ok") << got[r + i].line;
  EXPECT_EQ(got[r + 4].answer, "Error:setting out of range");
  EXPECT_EQ(got[r + 5].answer, "Error:no such setting");
  EXPECT_EQ(got[r + 6].answer, "Error:setting beyond the engine's step rate or acceleration");
  EXPECT_EQ(got[r + 7].answer, "Error:bad number");
  EXPECT_EQ(m->axis('X')->steps(), 1600);  // 10 mm at M92 X160, not the refused X80
  rx = m->serial().received().size();
  send(*m, {"$$"});
  now[100] = "160.000";
  now[103] = "93.500";
  now[111] = "1230.000";
  now[122] = "250.000";
  now[123] = "40.000";
  now[11] = "0.020";
  EXPECT_EQ(dollar_lines(received_from(*m, rx)), now);
}

// M502 restores the defaults ($RST=$) but keeps the style; M501 reloads
// the block the EEPROM holds now; M500 stores the settings in force.
TEST(ProtocolSwitch, M502RestoresM501ReloadsM500Stores) {
  // The defaults as M503 reports them on a fresh machine in Marlin style.
  auto fresh = machine();
  send(*fresh, {"$200=1"});
  fresh->serial().set_marlin(true);
  size_t rx = fresh->serial().received().size();
  send(*fresh, {"M503"});
  const M503 defaults = read_m503(received_from(*fresh, rx), "echo:");
  ASSERT_EQ(defaults.value.size(), 30u);

  auto m = machine();
  send(*m, {"$200=1"});
  m->serial().set_marlin(true);
  send(*m, {"M92 X80", "M203 X10", "M205 J0.5", "M502"});
  rx = m->serial().received().size();
  send(*m, {"M503", "G1 X10 F600", "M400"});
  EXPECT_EQ(read_m503(received_from(*m, rx), "echo:").value, defaults.value);
  EXPECT_EQ(m->axis('X')->steps(), std::round(10 * m->axis('X')->steps_per_mm));
  // Another machine's block (X at 250 steps/mm) put into this one's EEPROM
  // while it runs: M501 takes it.
  auto other = machine();
  send(*other, {"$200=1", "$100=250"});
  m->set_eeprom(eeprom_of(*other));
  rx = m->serial().received().size();
  send(*m, {"M501", "M503"});
  M503 loaded = read_m503(received_from(*m, rx), "echo:");
  EXPECT_EQ(loaded.value[100], "250.000");
  std::map<int, std::string> rest = loaded.value, want = defaults.value;
  rest.erase(100);
  want.erase(100);
  EXPECT_EQ(rest, want);
  // One changed byte of a value: M501 loads the defaults and says so; the
  // style is kept (this is still the Marlin host's session).
  std::vector<uint8_t> torn = eeprom_of(*other);
  torn[4 + 4 * 6] ^= 0x10;
  m->set_eeprom(torn);
  rx = m->serial().received().size();
  send(*m, {"M501", "M503"});
  const std::vector<std::string> after = received_from(*m, rx);
  EXPECT_EQ(count_of(after, kMarlinCorrupt), 1u);
  EXPECT_EQ(read_m503(after, "echo:").value, defaults.value);
  EXPECT_EQ(eeprom_of(*m), torn);  // M501 writes nothing
  // M500 stores the settings in force: the defaults over the bad block.
  send(*m, {"M500"});
  const std::vector<uint8_t> stored = eeprom_of(*m);
  EXPECT_NE(stored, torn);
  auto next = machine(stored);
  send(*next, {"M503"});
  EXPECT_TRUE(next->serial().marlin());
  EXPECT_EQ(count_of(next->serial().received(), kMarlinCorrupt), 0u);
  EXPECT_EQ(read_m503(next->serial().received(), "echo:").value, defaults.value);
  // M500 when the block is good writes nothing.
  send(*next, {"M500"});
  EXPECT_EQ(eeprom_of(*next), stored);
}

// A corrupt block boots on the defaults, grbl being the board's style,
// whatever the bad block said, and says so once after the banner.
TEST(ProtocolSwitch, ACorruptBlockBootsInTheBoardsStyleAndSaysSoOnce) {
  auto first = machine();
  send(*first, {"$200=1"});
  std::vector<uint8_t> torn = eeprom_of(*first);
  for (size_t at : {size_t(4 + 4 * 20), size_t(kBytes - 1)}) {  // $200's value, the sum
    std::vector<uint8_t> bad = torn;
    bad[at] ^= 0x01;
    auto m = machine(bad);
    send(*m, {"$$"});
    EXPECT_FALSE(m->serial().marlin()) << at;
    EXPECT_EQ(m->serial().banner(), "Grbl 1.1h ['$' for help]") << at;
    ASSERT_GE(m->serial().received().size(), 3u);
    EXPECT_EQ(m->serial().received()[2], kGrblCorrupt) << at;
    EXPECT_EQ(count_of(m->serial().received(), kGrblCorrupt), 1u) << at;
    EXPECT_EQ(dollar_lines(m->serial().messages())[200], "0") << at;
  }
}

// M112 in Marlin style on this image: the steps stop, every later line is
// refused until reset, `$200=0` too.
TEST(ProtocolSwitch, M112HaltsUntilReset) {
  auto first = machine();
  send(*first, {"$200=1"});
  auto m = machine(eeprom_of(*first));
  const size_t r = send(*m, {"G1 X5 F600", "M112", "G1 X1 F600", "$200=0"}, 5);
  const std::vector<sim::Response>& got = m->serial().responses();
  ASSERT_GE(got.size(), r + 4);
  for (size_t i = 1; i < 4; ++i) EXPECT_EQ(got[r + i].answer, "Error:Printer halted (M112), reset to restart");
  EXPECT_LT(m->axis('X')->steps(), 5 * m->axis('X')->steps_per_mm);
}

// The settings codes read the block onto the stack (126 bytes, one at a
// time): a Marlin session of all of them, behind motion, stays clear of the
// static data with room to spare (an M503 once held two blocks at once and
// reached it).
TEST(ProtocolSwitch, TheSettingsCodesLeaveTheStackRoom) {
  auto m = machine();
  send(*m, {"$200=1"});
  m->serial().set_marlin(true);
  send(*m, {"G1 X20 Y10 F1200", "M503", "M92 X80 Y80", "M501", "M502", "M500", "M203 X20", "M201 Y100", "M205 J0.02",
            "$$", numbered(1, "M115"), "G1 X0 Y0 F1200", "M503"});
  for (const sim::Response& r : m->serial().responses()) EXPECT_TRUE(sim::SerialHost::is_ok(r.answer)) << r.line;
  std::printf("stack %u of %u bytes free\n", m->stack_bytes(), m->free_ram());
  EXPECT_LT(m->stack_bytes() + 100, m->free_ram());
}

// A real Marlin host: printrun's printcore (as test_printcore.cpp, against
// the m32 printer) prints a small file on the m32-direct through
// `avrmotion-sim --pty`, its EEPROM that of a machine after `$200=1`: the
// banner is Marlin's, every line numbered and checksummed, one broken
// checksum asked for again, every line acknowledged once, the axes on the
// file's last targets.
TEST(ProtocolSwitch, PrintcorePrintsOnTheSwitchedImage) {
  auto first = machine();
  send(*first, {"$200=1"});
  const std::vector<uint8_t> ee = eeprom_of(*first);
  const std::string eeprom = simtest::temp_path("switch.eeprom"), file = simtest::temp_path("switch.gcode"),
                    report = simtest::temp_path("switch.json");
  std::ofstream(eeprom, std::ios::binary).write(reinterpret_cast<const char*>(ee.data()), long(ee.size()));
  // Three layers of a 24-gon with extrusion, in thousandths (exact steps at
  // any whole steps/mm), absolute E reset per layer.
  std::vector<std::string> lines = {"G21", "G90", "M82", "G92 E0"};
  long x = 0, y = 0, z = 0, e_total = 0;
  const auto mm = [](long um) { return mm3(double(um) / 1000); };
  for (int layer = 0; layer < 3; ++layer) {
    z = 200 * (layer + 1);
    lines.push_back("G1 Z" + mm(z) + " F600");
    long e = 0;
    for (int k = 0; k <= 24; ++k) {
      const double a = 2 * 3.14159265358979 * k / 24 + layer;
      x = 10000 + long(std::lround(5000 * std::cos(a)));
      y = 10000 + long(std::lround(5000 * std::sin(a)));
      if (k) e += 130 + k % 7;
      lines.push_back("G1 X" + mm(x) + " Y" + mm(y) + (k ? " E" + mm(e) : "") + " F1800");
    }
    e_total += e;
    lines.push_back("G92 E0");
  }
  lines.push_back("M84");
  {
    std::ofstream out(file);
    for (const std::string& l : lines) out << l << "\n";
  }
  ptytest::SimProcess sim({"--board", kImage, "--eeprom", eeprom, "--pty", "--speed", "max", "--linger", "1",
                           "--max-seconds", "120", "--report", report});
  const std::string port = sim.pty_path();
  ASSERT_FALSE(port.empty()) << sim.stderr_text();
  const long corrupt = long(lines.size() / 2);
  const std::string summary = printcore_run::stream(port, file, "--corrupt " + std::to_string(corrupt));
  std::printf("printcore on the m32-direct: %s\n", summary.c_str());
  ASSERT_EQ(sim.wait_exit(), 0) << sim.stderr_text();
  const std::string json = simtest::slurp(report);
  std::remove(eeprom.c_str());
  std::remove(file.c_str());
  std::remove(report.c_str());
  EXPECT_EQ(ptytest::report_string(json, "banner"), "\"start\"") << json;
  EXPECT_NE(summary.find("\"errors\": [\"Error:checksum mismatch, Last Line: " + std::to_string(corrupt - 1) + "\"]"),
            std::string::npos)
      << summary;
  EXPECT_NE(summary.find("\"resends\": [" + std::to_string(corrupt) + "]"), std::string::npos) << summary;
  const long sent = printcore_run::summary_number(summary, "sent"), oks = printcore_run::summary_number(summary, "oks");
  const long m105 = printcore_run::summary_number(summary, "m105_sent");
  EXPECT_EQ(sent, long(lines.size()) + 2 + 1 + 1) << summary;  // the file, two M110, the resend, M400
  // Every line printcore sent has one `ok`; its M105 at the open (the MCU
  // may still boot) an `ok` too if it was heard (no heater: Marlin's
  // unknown command, no `ok T:`).
  EXPECT_GE(oks, sent) << summary;
  EXPECT_LE(oks, sent + m105) << summary;
  const long m105_lost = m105 - (oks - sent);  // sent while the MCU booted, not heard
  EXPECT_EQ(long(ptytest::report_number(json, "", "lines_answered")),
            long(ptytest::report_number(json, "", "lines_sent")) - m105_lost)
      << json;
  // The targets in steps at the image's own scale (its descriptor; whole
  // thousandths of a mm at whole thousandths of steps/mm: exact).
  const am::BoardDescriptor board = sim::read_board_descriptor(simtest::image(kImage));
  const auto steps = [&](char axis, long um) {
    for (uint8_t i = 0; i < board.axis_count; ++i)
      if (board.axes[i].name == axis) return double(um) * double(board.axes[i].steps_per_m) / 1e6;
    return -1.0;
  };
  EXPECT_EQ(ptytest::report_number(json, "X", "steps"), steps('X', x)) << json;
  EXPECT_EQ(ptytest::report_number(json, "Y", "steps"), steps('Y', y));
  EXPECT_EQ(ptytest::report_number(json, "Z", "steps"), steps('Z', z));
  EXPECT_EQ(ptytest::report_number(json, "E", "steps"), steps('E', e_total));
}

// What the two styles cost, and what the images that keep one are: the
// figures docs/protocol.md and docs/settings.md quote. The m32-direct
// still fits its 32 KB (the link would fail otherwise) with its stack room
// (above); the m32 printer's few bytes are its own (benchmarks.md).
TEST(ProtocolSwitch, ImageSizes) {
  for (const char* name : {"m32-direct", "m32", "m32-i3", "m32-grbl", "m32-cnc", "uno"}) {
    const bool uno = std::string(name) == "uno";
    const simtest::ImageSize s = simtest::avr_size(name, uno ? "atmega328p" : "atmega32");
    const unsigned long room = uno ? 32256 : 32768;  // the Uno's bootloader keeps 512 B
    ASSERT_GT(s.flash, 0u) << name;
    ASSERT_LE(s.flash, room) << name;
    std::printf("%-10s flash %lu B (%lu free of %lu), RAM %lu B\n", name, s.flash, room - s.flash, room, s.ram);
  }
}

}  // namespace
