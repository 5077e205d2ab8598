#include <gtest/gtest.h>

#include <random>

#include "io/detail/base64.h"
#include "io/detail/xml_scan.h"

namespace vorohex::io::detail {
namespace {

std::string encode(const std::string& s) {
  std::string out(base64_encoded_size(s.size()), '\0');
  base64_encode(reinterpret_cast<const std::uint8_t*>(s.data()), s.size(), out.data());
  return out;
}

std::string decode(const std::string& s, bool* ok) {
  std::vector<std::uint8_t> bytes;
  *ok = base64_decode(s.data(), s.data() + s.size(), &bytes);
  return std::string(bytes.begin(), bytes.end());
}

TEST(Base64, MatchesRfc4648Vectors) {
  EXPECT_EQ(encode(""), "");
  EXPECT_EQ(encode("f"), "Zg==");
  EXPECT_EQ(encode("fo"), "Zm8=");
  EXPECT_EQ(encode("foo"), "Zm9v");
  EXPECT_EQ(encode("foobar"), "Zm9vYmFy");
  bool ok = false;
  EXPECT_EQ(decode("Zm9v\nYmE=", &ok), "fooba");
  EXPECT_TRUE(ok);
}

TEST(Base64, RoundTripsAndDecodesConcatenatedStreams) {
  std::mt19937 rng(3);
  for (std::size_t n = 0; n < 70; ++n) {
    std::string a(n, '\0'), b(n / 2 + 1, '\0');
    for (char& c : a) c = static_cast<char>(rng());
    for (char& c : b) c = static_cast<char>(rng());
    bool ok = false;
    EXPECT_EQ(decode(encode(a), &ok), a);
    EXPECT_TRUE(ok);
    EXPECT_EQ(decode(encode(a) + "\n " + encode(b), &ok), a + b);
    EXPECT_TRUE(ok);
  }
}

TEST(Base64, RejectsInvalidInput) {
  bool ok = true;
  decode("Zm9v*", &ok);
  EXPECT_FALSE(ok);
  decode("Z", &ok);
  EXPECT_FALSE(ok);
  decode("Z===", &ok);
  EXPECT_FALSE(ok);
  decode("Zg=a", &ok);
  EXPECT_FALSE(ok);
}

TEST(XmlScan, ElementsAttributesAndContent) {
  const std::string text =
      "<?xml version=\"1.0\"?><!-- c --><A x='1' y = \"a&amp;b\">"
      "<B/><C>hello</C><C n=\"2\"></C></A>";
  XmlDocument doc;
  std::string error;
  ASSERT_TRUE(scan_xml(text, "", &doc, &error)) << error;
  ASSERT_EQ(doc.elements.size(), 4u);
  EXPECT_EQ(doc.elements[0].name, "A");
  EXPECT_EQ(*doc.elements[0].attribute("y"), "a&b");
  EXPECT_EQ(doc.elements[0].attribute("z"), nullptr);
  const auto cs = doc.children_named(0, "C");
  ASSERT_EQ(cs.size(), 2u);
  const XmlElement& c = doc.elements[cs[0]];
  EXPECT_EQ(text.substr(c.content_begin, c.content_end - c.content_begin), "hello");
  EXPECT_EQ(doc.child_named(0, "D"), kNoElement);
}

TEST(XmlScan, StopsAtTheOpaqueElementAndRejectsBrokenInput) {
  XmlDocument doc;
  std::string error;
  const std::string text = "<A><B/><Raw enc=\"raw\">_\x01<</A>\xff";
  ASSERT_TRUE(scan_xml(text, "Raw", &doc, &error)) << error;
  ASSERT_NE(doc.opaque_element, kNoElement);
  EXPECT_EQ(text[doc.elements[doc.opaque_element].content_begin], '_');
  for (const char* bad :
       {"<A><B></A>", "<A x=1/>", "<A", "<A><B/>", "no xml", "<A x=\"1/>", "<A/><B/>", "</A>"}) {
    EXPECT_FALSE(scan_xml(bad, "", &doc, &error)) << bad;
  }
}

}  // namespace
}  // namespace vorohex::io::detail
