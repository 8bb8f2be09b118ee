#include "trackers/tracker.h"

#include <gtest/gtest.h>

namespace markerbench {
namespace {

TEST(TrackStatus, NamesRoundTrip) {
  for (TrackStatus s : {TrackStatus::kOk,
                        TrackStatus::kNotDetected,
                        TrackStatus::kWrongId,
                        TrackStatus::kPoseFailed,
                        TrackStatus::kError}) {
    EXPECT_EQ(TrackStatusFromString(ToString(s)), s);
  }
  EXPECT_STREQ(ToString(TrackStatus::kNotDetected), "not_detected");
  EXPECT_FALSE(TrackStatusFromString("lost").has_value());
}

}  // namespace
}  // namespace markerbench
