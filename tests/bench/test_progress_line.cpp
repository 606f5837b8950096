// The progress lines of a sweep (bench/lib/sweep.hpp): an estimate only once
// an item is done; before that "about 0 s left" would say nothing.
#include <gtest/gtest.h>

#include "bench/lib/sweep.hpp"

namespace rb {
namespace {

TEST(ProgressLine, NoEstimateBeforeTheFirstItemIsDone) {
  EXPECT_EQ(progress_line("references", 0, 13, 0.0, "scenes"), "references: 0/13 scenes");
}

TEST(ProgressLine, TheEstimateIsTheTimePerItemSoFarTimesWhatIsLeft) {
  EXPECT_EQ(progress_line("accuracy", 2, 10, 1.5), "accuracy: 2/10 runs, 1.5 s elapsed, about 6 s left");
  EXPECT_EQ(progress_line("accuracy", 10, 10, 7.0), "accuracy: 10/10 runs, 7 s elapsed, about 0 s left");
}

}  // namespace
}  // namespace rb
