#include "client/cli/progress_bar.h"

#include <gtest/gtest.h>

namespace soiq::cli {
namespace {

TEST(ProgressBar, LineShowsDoneOverTotalAndAFilledBar) {
  EXPECT_EQ(ProgressBar::line("stage2", 3, 4), "stage2  3/4 [######################........]");
  EXPECT_EQ(ProgressBar::line("stage2", 0, 0), "stage2  0/0 [..............................]");
  EXPECT_EQ(ProgressBar::line("stage2", 9, 4), "stage2  9/4 [##############################]");
}

TEST(ProgressBar, LineGivesTheRateAndTheTimeLeftOnceHalfASecondHasPassed) {
  EXPECT_EQ(ProgressBar::line("sending", 300, 1000, 0.4), "sending  300/1000 [#########.....................]");
  EXPECT_EQ(ProgressBar::line("sending", 300, 1000, 2.5),
            "sending  300/1000 [#########.....................]  120/s, 6 s left");
  EXPECT_EQ(ProgressBar::line("stage2", 2, 1000, 5),
            "stage2  2/1000 [..............................]  0.4/s, 42 min left");
  EXPECT_EQ(ProgressBar::line("stage2", 4, 4, 2), "stage2  4/4 [##############################]  2.0/s");
  EXPECT_EQ(ProgressBar::line("stage2", 0, 4, 2), "stage2  0/4 [..............................]");
}

}  // namespace
}  // namespace soiq::cli
