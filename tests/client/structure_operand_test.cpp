#include "client/cli/structure_operand.h"

#include <gtest/gtest.h>

#include "client/cli/remote_options.h"

namespace soiq::cli {
namespace {

TEST(StructureOperandKind, DigitsWithNoSuchFileAreAStoredStructure) {
  const auto k = structure_operand_kind("42", /*file_exists=*/false);
  ASSERT_TRUE(k.ok());
  EXPECT_EQ(*k, OperandKind::kStored);
}

TEST(StructureOperandKind, DigitsThatAreAlsoAFileAreRefusedNamingBothSpellings) {
  const auto k = structure_operand_kind("42", /*file_exists=*/true);
  ASSERT_FALSE(k.ok());
  EXPECT_EQ(k.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(k.status().message().find("id:42"), std::string::npos) << k.status().message();
  EXPECT_NE(k.status().message().find("./42"), std::string::npos) << k.status().message();
}

TEST(StructureOperandKind, IdPrefixIsAStoredStructureEvenWhenSuchAFileExists) {
  const auto k = structure_operand_kind("id:42", /*file_exists=*/true);
  ASSERT_TRUE(k.ok());
  EXPECT_EQ(*k, OperandKind::kStored);
}

TEST(StructureOperandKind, PathsAndNamesWithExtensionsAreFiles) {
  for (const char* operand : {"./42", "42.stl", "meshes/42", "hippo_L.vtp"}) {
    const auto k = structure_operand_kind(operand, /*file_exists=*/false);
    ASSERT_TRUE(k.ok()) << operand;
    EXPECT_EQ(*k, OperandKind::kFile) << operand;
  }
}

TEST(ParseStructureId, AcceptsTheIdPrefix) {
  const auto id = parse_structure_id("id:42");
  ASSERT_TRUE(id.ok());
  EXPECT_EQ(*id, 42);
  EXPECT_FALSE(parse_structure_id("id:").ok());
  EXPECT_FALSE(parse_structure_id("id:0").ok());
  EXPECT_FALSE(parse_structure_id("id:4x").ok());
}

}  // namespace
}  // namespace soiq::cli
