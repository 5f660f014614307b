// multipart/related (server/http/multipart.h): what soiq writes it reads back byte for byte, the
// forms clients send (a preamble, quoted boundaries, parts without headers), and malformed bodies
// refused without reading past them.
#include "server/http/multipart.h"

#include <gtest/gtest.h>

namespace soiq::server::http {
namespace {

TEST(Multipart, WhatIsWrittenIsReadBackByteForByte) {
  const std::string binary("\0\r\n--x\r\n\xff", 8);
  const std::vector<std::string_view> parts = {"first", binary, ""};
  const WrittenMultipart w = write_multipart_related({parts.begin(), parts.end()}, "application/dicom");
  const std::string body = w.body();
  Result<ParsedMultipart> r =
      parse_multipart_related("multipart/related; type=\"application/dicom\"; boundary=" + w.boundary, body, 10);
  ASSERT_TRUE(r.ok()) << r.status().to_string();
  EXPECT_EQ(r->type, "application/dicom");
  ASSERT_EQ(r->parts.size(), 3u);
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(r->parts[i].bytes, parts[i]);
    EXPECT_EQ(r->parts[i].content_type, "application/dicom");
  }
}

TEST(Multipart, ClientFormsAreRead) {
  // dicomweb-client: a CRLF before the first boundary, the boundary quoted, no CRLF at the end.
  const std::string body = "\r\n--b1\r\nContent-Type: application/dicom\r\n\r\nAB\r\n--b1\r\n\r\nCD\r\n--b1--";
  Result<ParsedMultipart> r =
      parse_multipart_related("Multipart/Related; boundary=\"b1\"; type=\"application/dicom\"", body, 10);
  ASSERT_TRUE(r.ok()) << r.status().to_string();
  ASSERT_EQ(r->parts.size(), 2u);
  EXPECT_EQ(r->parts[0].bytes, "AB");
  EXPECT_EQ(r->parts[1].content_type, "");  // no headers
  EXPECT_EQ(r->parts[1].bytes, "CD");
  EXPECT_TRUE(is_multipart_related("multipart/related;boundary=x"));
  EXPECT_FALSE(is_multipart_related("multipart/form-data; boundary=x"));
  EXPECT_EQ(header_parameter("a/b; type=\"x;y\"; q=1", "TYPE"), "x;y");
}

TEST(Multipart, MalformedBodiesAreRefused) {
  const std::string ct = "multipart/related; boundary=b";
  for (const std::string& body : {std::string("no boundary here"), std::string("--b\r\nContent-Type: x\r\n"),
                                  std::string("--b\r\n\r\nunterminated part"), std::string("--b")}) {
    Result<ParsedMultipart> r = parse_multipart_related(ct, body, 10);
    ASSERT_FALSE(r.ok()) << body;
    EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
  }
  EXPECT_FALSE(parse_multipart_related("multipart/related", "--b--", 10).ok());  // no boundary
  EXPECT_FALSE(parse_multipart_related("multipart/related; boundary=" + std::string(71, 'x'), "", 10).ok());
  std::string many;
  for (int i = 0; i < 3; ++i) many += "--b\r\n\r\nx\r\n";
  many += "--b--";
  Result<ParsedMultipart> r = parse_multipart_related(ct, many, 2);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("more than 2 parts"), std::string::npos);
}

}  // namespace
}  // namespace soiq::server::http
