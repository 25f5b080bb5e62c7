// docs/gcode.md's "Codes per image": every line of the table sent, in the
// table's order from power-up, to every image of its columns, and each
// answer classified as the table says: ok (taken), unsupported (Marlin's
// `echo:Unknown command: "<line>"` and `ok`; grbl's `error:20`) or refused
// (any other refusal). The table cannot drift from the images.
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "sim_fixture.h"

namespace {

struct Row {
  std::string line;
  std::vector<std::string> cells;  // by column
};

std::vector<std::string> split_cells(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream ss(line.substr(1));
  std::string cell;
  while (std::getline(ss, cell, '|')) {
    const size_t a = cell.find_first_not_of(' '), b = cell.find_last_not_of(' ');
    out.push_back(a == std::string::npos ? "" : cell.substr(a, b - a + 1));
  }
  return out;
}

// The table: its image columns and rows.
bool read_table(std::vector<std::string>& images, std::vector<Row>& rows) {
  std::ifstream in(std::string(AVRMOTION_SOURCE_DIR) + "/docs/gcode.md");
  std::string line;
  bool in_section = false;
  while (std::getline(in, line)) {
    if (line.rfind("### ", 0) == 0) in_section = line == "### Codes per image";
    if (!in_section || line.rfind("| ", 0) != 0) continue;
    const std::vector<std::string> cells = split_cells(line);
    if (cells.size() < 3) return false;
    if (cells[0] == "code") {
      images.assign(cells.begin() + 2, cells.end());
      continue;
    }
    if (cells[1].size() < 3 || cells[1].front() != '`' || cells[1].back() != '`') return false;
    rows.push_back(Row{cells[1].substr(1, cells[1].size() - 2), {cells.begin() + 2, cells.end()}});
  }
  return !images.empty() && !rows.empty();
}

std::string classify(const sim::Response& r, const sim::SerialHost& host) {
  const std::vector<std::string> msgs = host.messages();
  for (const std::string& m : msgs)
    if (m == "echo:Unknown command: \"" + r.line + "\"") return r.answer == "ok" ? "unsupported" : "?" + r.answer;
  if (r.answer == "error:20") return "unsupported";
  if (r.answer.rfind("ok", 0) == 0) return "ok";
  if (r.answer.rfind("Error:", 0) == 0 || r.answer.rfind("error:", 0) == 0) return "refused";
  return "?" + r.answer;
}

}  // namespace

TEST(CodeTable, EveryImageAnswersEveryCodeAsTheDocsTableSays) {
  std::vector<std::string> images;
  std::vector<Row> rows;
  ASSERT_TRUE(read_table(images, rows)) << "docs/gcode.md: ### Codes per image";
  ASSERT_GE(rows.size(), 40u);
  ASSERT_EQ(images.size(), 6u);
  std::vector<std::string> lines;
  for (const Row& r : rows) {
    ASSERT_EQ(r.cells.size(), images.size()) << r.line;
    lines.push_back(r.line);
  }
  for (size_t c = 0; c < images.size(); ++c) {
    SCOPED_TRACE(images[c]);
    auto m = simtest::run(images[c], lines, 20);
    const std::vector<sim::Response>& got = m->serial().responses();
    ASSERT_EQ(got.size(), rows.size());
    std::map<std::string, int> count;
    for (size_t i = 0; i < rows.size(); ++i) {
      const std::string cls = classify(got[i], m->serial());
      EXPECT_EQ(cls, rows[i].cells[c]) << images[c] << ": " << rows[i].line << " answered " << got[i].answer;
      ++count[cls];
    }
    std::printf("%s: %d ok, %d unsupported, %d refused of %zu codes\n", images[c].c_str(), count["ok"],
                count["unsupported"], count["refused"], rows.size());
  }
}
