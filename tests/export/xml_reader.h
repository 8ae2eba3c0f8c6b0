#pragma once
// A small XML reader for the SVG tests: elements, attributes (single or double quotes), text,
// comments, the <?xml?> prolog; it checks well-formedness (matching tags, one root, quoted
// attributes, known entities) and throws std::runtime_error naming the offset otherwise. An
// independent reader of what export/svg*.cpp write, not a general parser (no DTD, no CDATA).
#include <cctype>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace windplan::test {

struct XmlElement {
  std::string name;
  std::map<std::string, std::string> attrs;
  std::vector<std::unique_ptr<XmlElement>> children;
  std::string text;  ///< character data directly inside, entities decoded

  std::string attr(const std::string& k) const {
    auto it = attrs.find(k);
    return it == attrs.end() ? "" : it->second;
  }
  /// Every descendant (depth first, self excluded) for which pred holds.
  template <class Pred>
  void find_all(Pred pred, std::vector<const XmlElement*>* out) const {
    for (const auto& c : children) {
      if (pred(*c)) out->push_back(c.get());
      c->find_all(pred, out);
    }
  }
  std::vector<const XmlElement*> by_name(const std::string& n) const {
    std::vector<const XmlElement*> out;
    find_all([&](const XmlElement& e) { return e.name == n; }, &out);
    return out;
  }
  const XmlElement* by_id(const std::string& id) const {
    std::vector<const XmlElement*> out;
    find_all([&](const XmlElement& e) { return e.attr("id") == id; }, &out);
    return out.empty() ? nullptr : out.front();
  }
};

class XmlReader {
 public:
  static std::unique_ptr<XmlElement> parse(const std::string& s) {
    XmlReader r(s);
    r.skip_misc();
    if (r.i_ >= s.size() || s[r.i_] != '<') r.fail("no root element");
    auto root = r.element();
    r.skip_misc();
    if (r.i_ != s.size()) r.fail("content after the root element");
    return root;
  }

 private:
  explicit XmlReader(const std::string& s) : s_(s) {}
  [[noreturn]] void fail(const std::string& what) const {
    throw std::runtime_error("xml: " + what + " at offset " + std::to_string(i_));
  }
  bool starts(const char* p) const {
    return s_.compare(i_, std::char_traits<char>::length(p), p) == 0;
  }
  void ws() {
    while (i_ < s_.size() && (s_[i_] == ' ' || s_[i_] == '\n' || s_[i_] == '\t' || s_[i_] == '\r'))
      ++i_;
  }
  void skip_misc() {
    for (;;) {
      ws();
      if (starts("<?")) {
        const auto e = s_.find("?>", i_);
        if (e == std::string::npos) fail("unterminated <?");
        i_ = e + 2;
      } else if (starts("<!--")) {
        const auto e = s_.find("-->", i_);
        if (e == std::string::npos) fail("unterminated comment");
        i_ = e + 3;
      } else {
        return;
      }
    }
  }
  std::string name() {
    const std::size_t b = i_;
    while (i_ < s_.size() && (std::isalnum(static_cast<unsigned char>(s_[i_])) || s_[i_] == ':' ||
                              s_[i_] == '-' || s_[i_] == '_' || s_[i_] == '.'))
      ++i_;
    if (i_ == b) fail("expected a name");
    return s_.substr(b, i_ - b);
  }
  std::string decode(const std::string& t) {
    std::string o;
    for (std::size_t k = 0; k < t.size(); ++k) {
      if (t[k] == '<') fail("'<' in text or attribute");
      if (t[k] != '&') {
        o += t[k];
        continue;
      }
      const auto e = t.find(';', k);
      if (e == std::string::npos) fail("unterminated entity");
      const std::string ent = t.substr(k + 1, e - k - 1);
      if (ent == "amp")
        o += '&';
      else if (ent == "lt")
        o += '<';
      else if (ent == "gt")
        o += '>';
      else if (ent == "quot")
        o += '"';
      else if (ent == "apos")
        o += '\'';
      else if (!ent.empty() && ent[0] == '#')
        o += '?';
      else
        fail("unknown entity &" + ent + ";");
      k = e;
    }
    return o;
  }
  std::unique_ptr<XmlElement> element() {
    ++i_;  // '<'
    auto e = std::make_unique<XmlElement>();
    e->name = name();
    for (;;) {
      ws();
      if (i_ >= s_.size()) fail("unterminated start tag <" + e->name);
      if (starts("/>")) {
        i_ += 2;
        return e;
      }
      if (s_[i_] == '>') {
        ++i_;
        break;
      }
      const std::string k = name();
      ws();
      if (i_ >= s_.size() || s_[i_] != '=') fail("attribute " + k + " without '='");
      ++i_;
      ws();
      const char q = i_ < s_.size() ? s_[i_] : 0;
      if (q != '"' && q != '\'') fail("unquoted attribute " + k);
      const auto end = s_.find(q, i_ + 1);
      if (end == std::string::npos) fail("unterminated attribute " + k);
      if (e->attrs.count(k)) fail("duplicate attribute " + k);
      e->attrs[k] = decode(s_.substr(i_ + 1, end - i_ - 1));
      i_ = end + 1;
    }
    for (;;) {
      const auto lt = s_.find('<', i_);
      if (lt == std::string::npos) fail("unterminated element <" + e->name);
      e->text += decode(s_.substr(i_, lt - i_));
      i_ = lt;
      if (starts("</")) {
        i_ += 2;
        const std::string n = name();
        if (n != e->name) fail("</" + n + "> closes <" + e->name + ">");
        ws();
        if (i_ >= s_.size() || s_[i_] != '>') fail("bad end tag");
        ++i_;
        return e;
      }
      if (starts("<!--")) {
        const auto end = s_.find("-->", i_);
        if (end == std::string::npos) fail("unterminated comment");
        i_ = end + 3;
        continue;
      }
      e->children.push_back(element());
    }
  }
  const std::string& s_;
  std::size_t i_ = 0;
};

}  // namespace windplan::test
