// The README tells a new user which Debian packages the set-up script
// installs; the list must be exactly the script's.
#include <gtest/gtest.h>

#include <fstream>
#include <set>
#include <sstream>
#include <string>

namespace {

std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::set<std::string> words(const std::string& s) {
  std::set<std::string> out;
  std::istringstream in(s);
  for (std::string w; in >> w;) out.insert(w);
  return out;
}

// scripts/setup.sh: the words of its packages=( ... ) array.
std::set<std::string> setup_packages() {
  const std::string sh = slurp(std::string(AVRMOTION_SOURCE_DIR) + "/scripts/setup.sh");
  const size_t a = sh.find("packages=(");
  if (a == std::string::npos) return {};
  const size_t b = sh.find(')', a);
  return words(sh.substr(a + 10, b - a - 10));
}

// README.md: the indented line that lists the packages (the one naming gcc-avr).
std::set<std::string> readme_packages() {
  std::istringstream in(slurp(std::string(AVRMOTION_SOURCE_DIR) + "/README.md"));
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("    ", 0) == 0 && line.find("gcc-avr") != std::string::npos) return words(line);
  }
  return {};
}

TEST(SetupDocs, ReadmeListsExactlyThePackagesSetupInstalls) {
  const std::set<std::string> script = setup_packages(), readme = readme_packages();
  ASSERT_FALSE(script.empty()) << "no packages=( ... ) in scripts/setup.sh";
  ASSERT_FALSE(readme.empty()) << "no package line in README.md";
  EXPECT_EQ(readme, script);
  // The ones the issue found missing from the README.
  for (const char* p : {"libgtest-dev", "g++", "make", "xz-utils"}) EXPECT_EQ(readme.count(p), 1u) << p;
}

TEST(SetupDocs, SetupShowsWhatItInstalls) {
  const std::string sh = slurp(std::string(AVRMOTION_SOURCE_DIR) + "/scripts/setup.sh");
  // apt's own output is not thrown away or quietened, and the packages are
  // named before apt starts.
  std::istringstream in(sh);
  int apt_lines = 0;
  for (std::string line; std::getline(in, line);) {
    if (line.find("apt-get ") == std::string::npos || line.find("echo") != std::string::npos) continue;
    ++apt_lines;
    EXPECT_EQ(line.find("/dev/null"), std::string::npos) << line;
    EXPECT_EQ(line.find("-q"), std::string::npos) << line;
  }
  EXPECT_EQ(apt_lines, 2);  // update and install
  EXPECT_NE(sh.find("echo \"setup: installing"), std::string::npos);
}

TEST(SetupDocs, DemoPicturesGoToTheBuildTreeUnderTheirOwnNames) {
  const std::string demo = slurp(std::string(AVRMOTION_SOURCE_DIR) + "/scripts/demo.sh");
  EXPECT_EQ(demo.find("build/demo.svg"), std::string::npos);
  EXPECT_NE(demo.find("--plot \"build/"), std::string::npos);
  const std::string readme = slurp(std::string(AVRMOTION_SOURCE_DIR) + "/README.md");
  // Every --plot / --vcd in the README writes into build/.
  for (const char* opt : {"--plot ", "--vcd "}) {
    for (size_t i = readme.find(opt); i != std::string::npos; i = readme.find(opt, i + 1)) {
      EXPECT_EQ(readme.compare(i + std::string(opt).size(), 6, "build/"), 0) << readme.substr(i, 40);
    }
  }
}

}  // namespace
