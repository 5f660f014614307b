// soiqd --db: which store a location names, what is refused, and what a log may show of it.
#include "server/app/store_location.h"

#include <gtest/gtest.h>

#include "tests/support/temp_dir.h"

namespace soiq::server {
namespace {

TEST(StoreLocation, APathOrSqlitePathIsASqliteFile) {
  auto plain = parse_store_location("var/soiq.db");
  ASSERT_TRUE(plain.ok());
  EXPECT_EQ(plain->kind, StoreLocation::Kind::kSqlite);
  EXPECT_EQ(plain->target, "var/soiq.db");
  auto prefixed = parse_store_location("sqlite:/data/a b.db");
  ASSERT_TRUE(prefixed.ok());
  EXPECT_EQ(prefixed->kind, StoreLocation::Kind::kSqlite);
  EXPECT_EQ(prefixed->target, "/data/a b.db");
}

TEST(StoreLocation, APostgresqlUriIsAPostgresDatabaseGivenWhole) {
  for (const std::string uri : {"postgresql://soiq@db:5432/soiq?sslmode=require", "postgres://u@h/d"}) {
    auto where = parse_store_location(uri);
    ASSERT_TRUE(where.ok()) << uri;
    EXPECT_EQ(where->kind, StoreLocation::Kind::kPostgres);
    EXPECT_EQ(where->target, uri);
  }
}

TEST(StoreLocation, AnotherSchemeOrNothingIsInvalidNamingWhatIsTaken) {
  const auto mysql = parse_store_location("mysql://u@h/d");
  ASSERT_EQ(mysql.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(mysql.status().message().find("'mysql://' is not a store soiqd knows"), std::string::npos);
  EXPECT_NE(mysql.status().message().find("postgresql://USER@HOST:PORT/DATABASE"), std::string::npos);
  EXPECT_EQ(parse_store_location("").status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(parse_store_location("sqlite:").status().code(), StatusCode::kInvalidArgument);
}

TEST(StoreLocation, ALogShowsNoPassword) {
  EXPECT_EQ(redacted_store_location("postgresql://soiq:s3cr:et@db:5432/soiq"), "postgresql://soiq:***@db:5432/soiq");
  EXPECT_EQ(redacted_store_location("postgresql://soiq@db/soiq"), "postgresql://soiq@db/soiq");
  EXPECT_EQ(redacted_store_location("postgresql://db/soiq?user=a@b"), "postgresql://db/soiq?user=a@b");
  EXPECT_EQ(redacted_store_location("var/soiq.db"), "var/soiq.db");
}

TEST(StoreLocation, AnUnreachablePostgresIsUnavailableNamingTheServer) {
  auto where = parse_store_location("postgresql://soiq@127.0.0.1:1/soiq?connect_timeout=2");
  ASSERT_TRUE(where.ok());
  auto store = open_store(*where, {});
  ASSERT_FALSE(store.ok());
  EXPECT_EQ(store.status().code(), StatusCode::kUnavailable);
  EXPECT_NE(store.status().message().find("127.0.0.1:1/soiq"), std::string::npos) << store.status().message();
}

TEST(StoreLocation, ASqliteFileIsMadeWithItsFolder) {
  soiq::testing::TempDir dir;
  auto where = parse_store_location("sqlite:" + dir.file("a/b/soiq.db"));
  ASSERT_TRUE(where.ok());
  auto store = open_store(*where, {});
  ASSERT_TRUE(store.ok()) << store.status().to_string();
  EXPECT_TRUE((*store)->counts().ok());
}

}  // namespace
}  // namespace soiq::server
