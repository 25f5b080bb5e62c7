// A strict reader of the VCD files avrmotion-sim writes, for the tests: it
// checks the structure GTKWave relies on and returns every change.
//
// Checked: the header's keyword sections are each closed by $end; a
// $timescale; $scope / $upscope balanced; every $var is "wire <bits> <id>
// <name>" with a unique id; $enddefinitions before any value; a $dumpvars
// block that gives every variable a value; timestamps "#<n>" strictly
// increasing; every value change names a declared id, with 1-bit values
// 0/1/x/z and vector values "b<digits> <id>" of at most <bits> digits.
#pragma once
#include <cstdint>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace vcdread {

struct Var {
  std::string id, name;  // name with its scopes: "m32.X.step_PC0"
  int bits = 1;
};

struct Change {
  uint64_t time;
  std::string value;  // "0", "1", "x", "z" or the binary digits
};

struct Trace {
  std::string timescale;
  std::string comment;
  std::vector<Var> vars;
  std::map<std::string, std::vector<Change>> changes;  // by id; the $dumpvars value first
  std::vector<uint64_t> stamps;
  std::string error;     // empty when the file is well formed
  size_t redundant = 0;  // values that repeat their signal's last value

  const Var* by_name(const std::string& suffix) const {
    for (const Var& v : vars) {
      if (v.name.size() >= suffix.size() && v.name.compare(v.name.size() - suffix.size(), suffix.size(), suffix) == 0) {
        return &v;
      }
    }
    return nullptr;
  }
  // Times at which `id` went from 0 to 1 (after the initial value).
  std::vector<uint64_t> rising(const std::string& id) const {
    std::vector<uint64_t> out;
    auto it = changes.find(id);
    if (it == changes.end()) return out;
    for (size_t i = 1; i < it->second.size(); ++i) {
      if (it->second[i].value == "1" && it->second[i - 1].value == "0") out.push_back(it->second[i].time);
    }
    return out;
  }
};

inline Trace read(const std::string& path) {
  Trace t;
  std::ifstream in(path);
  if (!in) {
    t.error = "cannot open " + path;
    return t;
  }
  std::stringstream all;
  all << in.rdbuf();
  std::istringstream words(all.str());
  std::vector<std::string> scope;
  std::set<std::string> ids;
  bool definitions = true, dumpvars = false, have_time = false;
  uint64_t now = 0;
  std::set<std::string> dumped;
  const auto fail = [&t](const std::string& what) {
    if (t.error.empty()) t.error = what;
  };
  const auto section = [&](std::vector<std::string>& body) {
    for (std::string w; words >> w;) {
      if (w == "$end") return true;
      body.push_back(w);
    }
    return false;
  };
  for (std::string w; t.error.empty() && words >> w;) {
    if (definitions) {
      std::vector<std::string> body;
      if (w == "$enddefinitions") {
        if (!section(body) || !body.empty()) fail("bad $enddefinitions");
        if (!scope.empty()) fail("unclosed $scope");
        if (t.timescale.empty()) fail("no $timescale");
        definitions = false;
      } else if (w == "$version" || w == "$date" || w == "$comment") {
        if (!section(body)) fail("unterminated " + w);
        if (w == "$comment") {
          for (const auto& b : body) t.comment += b + " ";
        }
      } else if (w == "$timescale") {
        if (!section(body) || body.empty()) fail("bad $timescale");
        for (const auto& b : body) t.timescale += b;
      } else if (w == "$scope") {
        if (!section(body) || body.size() != 2)
          fail("bad $scope");
        else
          scope.push_back(body[1]);
      } else if (w == "$upscope") {
        if (!section(body) || !body.empty() || scope.empty())
          fail("bad $upscope");
        else
          scope.pop_back();
      } else if (w == "$var") {
        if (!section(body) || body.size() != 4 || body[0] != "wire") {
          fail("bad $var");
          continue;
        }
        Var v;
        v.bits = std::atoi(body[1].c_str());
        v.id = body[2];
        if (v.bits < 1 || v.bits > 32) fail("bad $var size " + body[1]);
        if (!ids.insert(v.id).second) fail("id " + v.id + " declared twice");
        if (scope.empty()) fail("$var outside a scope");
        for (const auto& s : scope) v.name += s + ".";
        v.name += body[3];
        t.vars.push_back(v);
      } else {
        fail("unexpected " + w + " in the header");
      }
      continue;
    }
    if (w == "$dumpvars") {
      if (t.stamps.size() > 1) fail("$dumpvars after the first changes");
      dumpvars = true;
      continue;
    }
    if (w == "$end") {
      if (!dumpvars) fail("stray $end");
      dumpvars = false;
      if (dumped.size() != t.vars.size()) fail("$dumpvars does not give every variable a value");
      continue;
    }
    if (w[0] == '$') {
      fail("unexpected " + w + " in the body");
      continue;
    }
    if (w[0] == '#') {
      const std::string digits = w.substr(1);
      if (digits.empty() || digits.find_first_not_of("0123456789") != std::string::npos) {
        fail("bad timestamp " + w);
        continue;
      }
      const uint64_t stamp = std::stoull(digits);
      if (have_time && stamp <= now) fail("timestamp " + w + " not after #" + std::to_string(now));
      now = stamp;
      have_time = true;
      t.stamps.push_back(stamp);
      continue;
    }
    if (!have_time) {
      fail("a value before the first timestamp");
      continue;
    }
    std::string value, id;
    if (w[0] == 'b' || w[0] == 'B') {
      value = w.substr(1);
      if (!(words >> id)) fail("vector value without an id");
      if (value.empty() || value.find_first_not_of("01xz") != std::string::npos) fail("bad vector value " + w);
    } else {
      value = w.substr(0, 1);
      id = w.substr(1);
      if (value.find_first_not_of("01xz") != std::string::npos || id.empty()) fail("bad scalar value " + w);
    }
    const Var* var = nullptr;
    for (const Var& v : t.vars) {
      if (v.id == id) var = &v;
    }
    if (!var) {
      fail("value for undeclared id " + id);
      continue;
    }
    if (w[0] == 'b' && int(value.size()) > var->bits) fail("value " + w + " wider than " + var->name);
    if (w[0] != 'b' && var->bits != 1) fail("scalar value for vector " + var->name);
    if (dumpvars) dumped.insert(id);
    std::vector<Change>& list = t.changes[id];
    if (!list.empty() && list.back().value == value) ++t.redundant;
    list.push_back({now, value});
  }
  if (t.error.empty() && definitions) fail("no $enddefinitions");
  if (t.error.empty() && dumped.size() != t.vars.size()) fail("no complete $dumpvars");
  return t;
}

}  // namespace vcdread
