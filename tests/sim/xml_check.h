// A small XML well-formedness checker for the tests (so CI needs no xmllint)
// and a DOM just big enough to look at the pictures' elements.
//
// Checks: one root element; every start tag closed by its own end tag, in
// order; names that start with a letter, '_' or ':'; quoted attribute values
// without '<'; no attribute twice on an element; only the five predefined
// entities and numeric character references; no '<' or bare '&' in text;
// comments without "--" inside; an optional <?xml ...?> declaration (other
// processing instructions allowed); nothing but whitespace, comments and
// processing instructions around the root. (No DTDs: the pictures have none,
// so a DOCTYPE is reported as an error.)
#pragma once
#include <cctype>
#include <cstdlib>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace xmlcheck {

struct Element {
  std::string name;
  std::vector<std::pair<std::string, std::string>> attrs;  // values with entities decoded
  std::vector<std::unique_ptr<Element>> children;
  std::string text;  // all character data directly inside, decoded

  const std::string* attr(const std::string& key) const {
    for (const auto& a : attrs) {
      if (a.first == key) return &a.second;
    }
    return nullptr;
  }
  std::string attr_or(const std::string& key, const std::string& fallback = "") const {
    const std::string* v = attr(key);
    return v ? *v : fallback;
  }
  // Every element below this one (depth first, document order) for which
  // pred(element) holds.
  template <typename Pred>
  void find_all(Pred pred, std::vector<const Element*>& out) const {
    for (const auto& c : children) {
      if (pred(*c)) out.push_back(c.get());
      c->find_all(pred, out);
    }
  }
};

class Parser {
 public:
  explicit Parser(const std::string& doc) : s_(doc) {}

  // Returns the root, or null with error() saying what and where.
  std::unique_ptr<Element> parse() {
    std::unique_ptr<Element> root;
    misc();
    if (failed()) return nullptr;
    if (peek("<!DOCTYPE")) return fail("DOCTYPE not supported");
    if (!peek("<")) return fail("no root element");
    root = element();
    if (!root) return nullptr;
    misc();
    if (failed()) return nullptr;
    if (i_ != s_.size()) return fail("content after the root element");
    return root;
  }
  const std::string& error() const { return error_; }

 private:
  bool failed() const { return !error_.empty(); }
  std::nullptr_t fail(const std::string& what) {
    if (error_.empty()) error_ = what + " at offset " + std::to_string(i_);
    return nullptr;
  }
  bool peek(const char* lit) const { return s_.compare(i_, std::char_traits<char>::length(lit), lit) == 0; }
  bool eat(const char* lit) {
    if (!peek(lit)) return false;
    i_ += std::char_traits<char>::length(lit);
    return true;
  }
  void spaces() {
    while (i_ < s_.size() && (s_[i_] == ' ' || s_[i_] == '\t' || s_[i_] == '\n' || s_[i_] == '\r')) ++i_;
  }
  static bool name_start(char c) {
    return std::isalpha(static_cast<unsigned char>(c)) || c == '_' || c == ':' || static_cast<unsigned char>(c) >= 0x80;
  }
  static bool name_char(char c) {
    return name_start(c) || std::isdigit(static_cast<unsigned char>(c)) || c == '-' || c == '.';
  }
  std::string name() {
    if (i_ >= s_.size() || !name_start(s_[i_])) {
      fail("expected a name");
      return "";
    }
    const size_t a = i_;
    while (i_ < s_.size() && name_char(s_[i_])) ++i_;
    return s_.substr(a, i_ - a);
  }
  // Comments and processing instructions (and whitespace) outside the root.
  void misc() {
    for (;;) {
      spaces();
      if (peek("<!--")) {
        comment();
      } else if (peek("<?")) {
        pi();
      } else {
        return;
      }
      if (failed()) return;
    }
  }
  void comment() {
    i_ += 4;
    const size_t end = s_.find("--", i_);
    if (end == std::string::npos) {
      fail("unterminated comment");
      return;
    }
    i_ = end;
    if (!eat("-->")) fail("\"--\" inside a comment");
  }
  void pi() {
    i_ += 2;
    name();
    if (failed()) return;
    const size_t end = s_.find("?>", i_);
    if (end == std::string::npos) {
      fail("unterminated processing instruction");
      return;
    }
    i_ = end + 2;
  }
  // Decodes an entity or character reference at i_ ('&' already seen).
  bool reference(std::string& out) {
    ++i_;
    const size_t semi = s_.find(';', i_);
    if (semi == std::string::npos || semi - i_ > 10) {
      fail("bare '&'");
      return false;
    }
    const std::string ref = s_.substr(i_, semi - i_);
    i_ = semi + 1;
    if (ref == "amp")
      out += '&';
    else if (ref == "lt")
      out += '<';
    else if (ref == "gt")
      out += '>';
    else if (ref == "quot")
      out += '"';
    else if (ref == "apos")
      out += '\'';
    else if (ref.size() > 1 && ref[0] == '#') {
      const bool hex = ref[1] == 'x';
      const std::string digits = ref.substr(hex ? 2 : 1);
      if (digits.empty() ||
          digits.find_first_not_of(hex ? "0123456789abcdefABCDEF" : "0123456789") != std::string::npos) {
        fail("bad character reference &" + ref + ";");
        return false;
      }
      const long cp = std::strtol(digits.c_str(), nullptr, hex ? 16 : 10);
      if (cp <= 0 || cp > 0x10FFFF) {
        fail("character reference out of range");
        return false;
      }
      out += cp < 0x80 ? char(cp) : '?';  // enough for looking at text
    } else {
      fail("undefined entity &" + ref + ";");
      return false;
    }
    return true;
  }
  std::unique_ptr<Element> element() {
    ++i_;  // '<'
    std::unique_ptr<Element> e(new Element);
    e->name = name();
    if (failed()) return nullptr;
    for (;;) {
      const size_t before = i_;
      spaces();
      if (eat("/>")) return e;
      if (eat(">")) break;
      if (i_ == before) return fail("expected whitespace before an attribute");
      std::string key = name();
      if (failed()) return nullptr;
      if (e->attr(key)) return fail("attribute " + key + " twice");
      spaces();
      if (!eat("=")) return fail("attribute without '='");
      spaces();
      if (i_ >= s_.size() || (s_[i_] != '"' && s_[i_] != '\'')) return fail("unquoted attribute value");
      const char q = s_[i_++];
      std::string value;
      for (;;) {
        if (i_ >= s_.size()) return fail("unterminated attribute value");
        const char c = s_[i_];
        if (c == q) {
          ++i_;
          break;
        }
        if (c == '<') return fail("'<' in an attribute value");
        if (c == '&') {
          if (!reference(value)) return nullptr;
          continue;
        }
        value += c;
        ++i_;
      }
      e->attrs.emplace_back(key, value);
    }
    // Content.
    for (;;) {
      if (i_ >= s_.size()) return fail("element <" + e->name + "> not closed");
      if (peek("</")) {
        i_ += 2;
        const std::string end = name();
        if (failed()) return nullptr;
        if (end != e->name) return fail("</" + end + "> closes <" + e->name + ">");
        spaces();
        if (!eat(">")) return fail("malformed end tag");
        return e;
      }
      if (peek("<!--")) {
        comment();
        if (failed()) return nullptr;
        continue;
      }
      if (peek("<![CDATA[")) {
        const size_t end = s_.find("]]>", i_);
        if (end == std::string::npos) return fail("unterminated CDATA");
        e->text += s_.substr(i_ + 9, end - i_ - 9);
        i_ = end + 3;
        continue;
      }
      if (peek("<?")) {
        pi();
        if (failed()) return nullptr;
        continue;
      }
      if (peek("<")) {
        std::unique_ptr<Element> child = element();
        if (!child) return nullptr;
        e->children.push_back(std::move(child));
        continue;
      }
      const char c = s_[i_];
      if (c == '&') {
        if (!reference(e->text)) return nullptr;
        continue;
      }
      if (peek("]]>")) return fail("\"]]>\" in text");
      e->text += c;
      ++i_;
    }
  }

  const std::string s_;  // a copy: the parser may outlive a temporary argument
  size_t i_ = 0;
  std::string error_;
};

}  // namespace xmlcheck
