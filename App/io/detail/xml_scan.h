// A small, bounds-checked XML scanner for VTK XML files: elements, attributes and the
// byte range of each element's content. No DTDs, namespaces or character references in
// content (VTK never writes them); the five predefined entities are decoded in attributes.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace vorohex::io::detail {

struct XmlElement {
  std::string name;
  std::vector<std::pair<std::string, std::string>> attributes;
  std::vector<std::size_t> children;  // indices into XmlDocument::elements
  std::size_t content_begin = 0;      // first byte after the start tag
  std::size_t content_end = 0;        // first byte of the end tag

  // Attribute value, or nullptr when absent.
  const std::string* attribute(std::string_view key) const;
};

struct XmlDocument {
  std::vector<XmlElement> elements;  // elements[0] is the root
  // Set when scanning stopped at the opaque element (see scan_xml).
  std::size_t opaque_element = static_cast<std::size_t>(-1);

  // Children of `parent` named `name`, in document order.
  std::vector<std::size_t> children_named(std::size_t parent, std::string_view name) const;
  // First child named `name`, or -1.
  std::size_t child_named(std::size_t parent, std::string_view name) const;
};

constexpr std::size_t kNoElement = static_cast<std::size_t>(-1);

// Scans `text`. When the start tag of an element named `opaque` is met (VTK's
// AppendedData, whose content is raw bytes), scanning stops there: that element is
// recorded with its content_begin and content_end = text.size(), and elements still open
// are accepted as they are. Returns false with *error on malformed or truncated input.
bool scan_xml(std::string_view text, std::string_view opaque, XmlDocument* doc, std::string* error);

}  // namespace vorohex::io::detail
