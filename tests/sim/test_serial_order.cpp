// Bytes that wait in the UART's receive buffer two at a time (the MCU took
// the first late: its receive interrupt held off by a long one) reach the
// line reader in the order they came, on every image with a G-code line
// protocol: Marlin's numbered and checksummed lines on the m32, grbl's on
// the Uno and on the m32-cnc, whose receive interrupt also filters the
// realtime bytes. Each line's text is then exactly what was sent (a checked
// move ends on its exact steps; a numbered line's checksum holds).
#include <string>
#include <vector>

#include "sim_fixture.h"

namespace {

int checksum(const std::string& s) {
  int x = 0;
  for (const char c : s) x ^= uint8_t(c);
  return x;
}

}  // namespace

TEST(SerialOrder, BytesWaitingTwoAtATimeKeepTheirOrder) {
  for (const char* image : {"m32", "uno", "m32-cnc"}) {
    SCOPED_TRACE(image);
    const bool marlin = std::string(image) == "m32";
    sim::Machine m(simtest::image(image));
    m.serial().add_line("G91");
    ASSERT_EQ(m.run_script(16000000), sim::RunEnd::done);
    // Moves whose every digit matters: a swap of any two bytes changes a
    // target, a word, or (Marlin) the checksum's place.
    // One line at a time, as a host that waits for each answer; each
    // line's bytes come two at a time.
    long x = 0, y = 0;
    size_t oks = 0, refusals = 0;
    for (int i = 1; i <= 12; ++i) {
      const int dx = 100 + 37 * i, dy = 1000 - 61 * i;
      x += dx, y += dy;
      char text[48];
      std::snprintf(text, sizeof text, "G1 X%d.%03d Y%d.%03d F1200", dx / 1000, dx % 1000, dy / 1000, dy % 1000);
      std::string line = text;
      if (marlin) {
        line = "N" + std::to_string(i) + " " + line;
        line += "*" + std::to_string(checksum(line));
      }
      const std::vector<std::string>& got = m.serial().received();
      const size_t before = got.size();
      const auto answered = [&] {
        for (size_t k = before; k < got.size(); ++k)
          if (got[k] == "ok" || got[k].rfind("error:", 0) == 0) return true;
        return false;
      };
      m.serial().send_raw(line + "\n", 2);
      ASSERT_EQ(m.run(answered, 16000000ull * 2), sim::RunEnd::done) << line;
      for (size_t k = before; k < got.size(); ++k) {
        oks += got[k] == "ok";
        refusals += got[k].rfind("Error:", 0) == 0 || got[k].rfind("error:", 0) == 0;
        if (got[k] != "ok") std::printf("%s: %s -> %s\n", image, line.c_str(), got[k].c_str());
      }
    }
    m.serial().add_line("M400");
    ASSERT_EQ(m.run_script(16000000ull * 4), sim::RunEnd::done);
    EXPECT_EQ(refusals, 0u);
    EXPECT_EQ(oks, 12u);
    const double per_um = m.axis('X')->steps_per_mm / 1000;  // steps per um
    EXPECT_EQ(long(m.axis('X')->steps() + 0.5), long(x * per_um + 0.5));
    EXPECT_EQ(long(m.axis('Y')->steps() + 0.5), long(y * per_um + 0.5));
  }
}
