#include "db/page_token.h"

#include <gtest/gtest.h>

namespace soiq::db {
namespace {

TEST(PageToken, RoundTripsAnyKeyBytes) {
  for (const std::string& key : {std::string("P001"), std::string("1.2.840.1"), std::string("\0\xff.x", 4)}) {
    auto back = parse_page_token("patients", make_page_token("patients", key));
    ASSERT_TRUE(back.ok());
    EXPECT_EQ(*back, key);
  }
}

TEST(PageToken, EmptyTokenIsTheFirstPage) { EXPECT_EQ(*parse_page_token("patients", ""), ""); }

TEST(PageToken, TokenOfAnotherListOrGarbageIsInvalidArgument) {
  for (const std::string& bad : {make_page_token("studies", "x"), std::string("v1zz"), std::string("hello"),
                                 make_page_token("patients", "x") + "0", make_page_token("patients", "x") + "g0"}) {
    auto r = parse_page_token("patients", bad);
    ASSERT_FALSE(r.ok()) << bad;
    EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
    EXPECT_NE(r.status().message().find("page_token"), std::string::npos);
  }
}

TEST(PageToken, PageSizeZeroIsHundredAndLargeIsClampedToThousand) {
  EXPECT_EQ(*effective_page_size(0), 100);
  EXPECT_EQ(*effective_page_size(1), 1);
  EXPECT_EQ(*effective_page_size(1000), 1000);
  EXPECT_EQ(*effective_page_size(5000), 1000);
  EXPECT_EQ(effective_page_size(-1).status().code(), StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace soiq::db
