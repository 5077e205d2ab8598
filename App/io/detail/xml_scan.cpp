#include "io/detail/xml_scan.h"

namespace vorohex::io::detail {
namespace {

bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r';
}
bool is_name_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
         c == ':' || c == '-' || c == '.';
}

std::string decode_entities(std::string_view v) {
  std::string out;
  out.reserve(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (v[i] != '&') {
      out += v[i];
      continue;
    }
    static const std::pair<std::string_view, char> kEntities[] = {
        {"&lt;", '<'}, {"&gt;", '>'}, {"&amp;", '&'}, {"&quot;", '"'}, {"&apos;", '\''}};
    bool done = false;
    for (const auto& [name, c] : kEntities)
      if (v.substr(i, name.size()) == name) {
        out += c;
        i += name.size() - 1;
        done = true;
        break;
      }
    if (!done) out += '&';
  }
  return out;
}

class Scanner {
 public:
  Scanner(std::string_view text, std::string_view opaque, XmlDocument* doc, std::string* error)
      : t_(text), opaque_(opaque), doc_(doc), error_(error) {}

  bool run() {
    std::vector<std::size_t> open;
    std::size_t pos = 0;
    while (true) {
      const std::size_t lt = t_.find('<', pos);
      if (lt == std::string_view::npos) break;
      if (starts(lt, "<?")) {
        if (!skip_past(lt, "?>", &pos)) return fail("unterminated processing instruction");
      } else if (starts(lt, "<!--")) {
        if (!skip_past(lt, "-->", &pos)) return fail("unterminated comment");
      } else if (starts(lt, "<![CDATA[")) {
        if (!skip_past(lt, "]]>", &pos)) return fail("unterminated CDATA section");
      } else if (starts(lt, "<!")) {
        if (!skip_past(lt, ">", &pos)) return fail("unterminated declaration");
      } else if (starts(lt, "</")) {
        std::size_t p = lt + 2;
        const std::size_t name_begin = p;
        while (p < t_.size() && is_name_char(t_[p])) ++p;
        const std::string_view name = t_.substr(name_begin, p - name_begin);
        while (p < t_.size() && is_space(t_[p])) ++p;
        if (p >= t_.size() || t_[p] != '>') return fail("truncated end tag");
        if (open.empty() || doc_->elements[open.back()].name != name)
          return fail("unexpected end tag </" + std::string(name) + ">");
        doc_->elements[open.back()].content_end = lt;
        open.pop_back();
        pos = p + 1;
      } else {
        bool self_closing = false;
        std::size_t index = 0;
        if (!start_tag(lt, &pos, &self_closing, &index)) return false;
        if (open.empty()) {
          if (index != 0) return fail("more than one root element");
        } else {
          doc_->elements[open.back()].children.push_back(index);
        }
        XmlElement& e = doc_->elements[index];
        e.content_begin = pos;
        e.content_end = pos;
        if (!self_closing) {
          if (!opaque_.empty() && e.name == opaque_) {
            e.content_end = t_.size();
            doc_->opaque_element = index;
            return true;
          }
          open.push_back(index);
        }
      }
    }
    if (doc_->elements.empty()) return fail("no XML element found");
    if (!open.empty())
      return fail("the file ends inside <" + doc_->elements[open.back()].name + "> (truncated?)");
    return true;
  }

 private:
  bool starts(std::size_t pos, std::string_view s) const { return t_.substr(pos, s.size()) == s; }
  bool skip_past(std::size_t from, std::string_view end, std::size_t* pos) const {
    const std::size_t e = t_.find(end, from);
    if (e == std::string_view::npos) return false;
    *pos = e + end.size();
    return true;
  }
  bool fail(const std::string& what) {
    *error_ = "XML: " + what;
    return false;
  }

  bool start_tag(std::size_t lt, std::size_t* pos, bool* self_closing, std::size_t* index) {
    std::size_t p = lt + 1;
    const std::size_t name_begin = p;
    while (p < t_.size() && is_name_char(t_[p])) ++p;
    if (p == name_begin) return fail("invalid tag at byte " + std::to_string(lt));
    XmlElement e;
    e.name = std::string(t_.substr(name_begin, p - name_begin));
    while (true) {
      while (p < t_.size() && is_space(t_[p])) ++p;
      if (p >= t_.size()) return fail("truncated start tag <" + e.name + ">");
      if (t_[p] == '>') {
        ++p;
        break;
      }
      if (t_[p] == '/') {
        if (p + 1 >= t_.size() || t_[p + 1] != '>') return fail("malformed tag <" + e.name + ">");
        *self_closing = true;
        p += 2;
        break;
      }
      const std::size_t key_begin = p;
      while (p < t_.size() && is_name_char(t_[p])) ++p;
      if (p == key_begin) return fail("malformed attribute in <" + e.name + ">");
      std::string key(t_.substr(key_begin, p - key_begin));
      while (p < t_.size() && is_space(t_[p])) ++p;
      if (p >= t_.size() || t_[p] != '=') return fail("attribute " + key + " has no value");
      ++p;
      while (p < t_.size() && is_space(t_[p])) ++p;
      if (p >= t_.size() || (t_[p] != '"' && t_[p] != '\''))
        return fail("attribute " + key + " is not quoted");
      const char quote = t_[p++];
      const std::size_t close = t_.find(quote, p);
      if (close == std::string_view::npos) return fail("unterminated attribute " + key);
      e.attributes.emplace_back(std::move(key), decode_entities(t_.substr(p, close - p)));
      p = close + 1;
    }
    *pos = p;
    *index = doc_->elements.size();
    doc_->elements.push_back(std::move(e));
    return true;
  }

  std::string_view t_;
  std::string_view opaque_;
  XmlDocument* doc_;
  std::string* error_;
};

}  // namespace

const std::string* XmlElement::attribute(std::string_view key) const {
  for (const auto& [k, v] : attributes)
    if (k == key) return &v;
  return nullptr;
}

std::vector<std::size_t> XmlDocument::children_named(std::size_t parent,
                                                     std::string_view name) const {
  std::vector<std::size_t> out;
  for (std::size_t c : elements[parent].children)
    if (elements[c].name == name) out.push_back(c);
  return out;
}

std::size_t XmlDocument::child_named(std::size_t parent, std::string_view name) const {
  for (std::size_t c : elements[parent].children)
    if (elements[c].name == name) return c;
  return kNoElement;
}

bool scan_xml(std::string_view text, std::string_view opaque, XmlDocument* doc,
              std::string* error) {
  doc->elements.clear();
  doc->opaque_element = kNoElement;
  return Scanner(text, opaque, doc, error).run();
}

}  // namespace vorohex::io::detail
