// soiqd --pacs AE@HOST:PORT on its own.
#include "server/app/pacs_address.h"

#include <gtest/gtest.h>

namespace soiq::server {
namespace {

TEST(PacsAddress, AeHostAndPortMakeAPeer) {
  Result<dicom::PacsPeer> p = parse_pacs_address("ORTHANC@pacs.example.org:4242", "SOIQ", 30);
  ASSERT_TRUE(p.ok()) << p.status().to_string();
  EXPECT_EQ(p->called_ae, "ORTHANC");
  EXPECT_EQ(p->host, "pacs.example.org");
  EXPECT_EQ(p->port, 4242);
  EXPECT_EQ(p->calling_ae, "SOIQ");
  EXPECT_EQ(p->timeout_seconds, 30);
}

TEST(PacsAddress, AMalformedAddressIsInvalidArgumentShowingTheExpectedForm) {
  for (const char* bad : {"", "ORTHANC", "ORTHANC@host", "@host:4242", "ORTHANC@:4242",
                          "ORTHANC@host:", "ORTHANC@host:port", "ORTHANC@host:70000", "ORTHANC@host:0"}) {
    Result<dicom::PacsPeer> p = parse_pacs_address(bad, "SOIQ", 30);
    EXPECT_EQ(p.status().code(), StatusCode::kInvalidArgument) << "'" << bad << "'";
    EXPECT_NE(p.status().message().find("AE@HOST:PORT"), std::string::npos) << p.status().message();
  }
}

}  // namespace
}  // namespace soiq::server
