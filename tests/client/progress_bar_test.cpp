#include "client/cli/progress_bar.h"

#include <gtest/gtest.h>

namespace soiq::cli {
namespace {

TEST(ProgressBar, LineShowsDoneOverTotalAndAFilledBar) {
  EXPECT_EQ(ProgressBar::line("stage2", 3, 4), "stage2  3/4 [######################........]");
  EXPECT_EQ(ProgressBar::line("stage2", 0, 0), "stage2  0/0 [..............................]");
  EXPECT_EQ(ProgressBar::line("stage2", 9, 4), "stage2  9/4 [##############################]");
}

}  // namespace
}  // namespace soiq::cli
