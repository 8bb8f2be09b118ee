#include "bench/report/sequence_report.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace markerbench {
namespace {

// A cell's row over its videos: the sums, the medians over the videos and their 95 %
// intervals (the binomial ranks of MedianInterval: the 2nd and 9th of 10), times included.
TEST(SequenceSummary, MediansOverTheVideosWithTheirIntervals) {
  SequenceSummaryRow cell;
  cell.scenario = "handheld";
  cell.marker = "circles_a";
  cell.tracker = "circle";
  std::vector<SequenceMetrics> videos;
  for (int k = 1; k <= 10; ++k) {
    SequenceMetrics m;
    m.visible = 100;
    m.lost = k == 3 ? 10 : 0;
    m.ate_m = 1e-3 * (11 - k);
    m.tracking_ms = 1.0 + 0.1 * k;            // 1.1 .. 2.0
    m.detection_ms = k == 5 ? NAN : 2.0 + k;  // a video never detected again: left out
    m.reacquire_s = {0.1 * k, k == 7 ? std::numeric_limits<double>::infinity() : 0.2};
    videos.push_back(m);
  }
  const SequenceSummaryRow s = SummaryOfSequences(cell, videos);
  EXPECT_EQ(s.scenario, "handheld");
  EXPECT_EQ(s.tracker, "circle");
  EXPECT_EQ(s.sequences, 10);
  EXPECT_EQ(s.visible, 1000);
  EXPECT_EQ(s.lost, 10);
  EXPECT_LT(s.lost_rate_ci.lo, 0.01);
  EXPECT_GT(s.lost_rate_ci.hi, 0.01);
  EXPECT_DOUBLE_EQ(s.ate_m, 5.5e-3);
  EXPECT_DOUBLE_EQ(s.ate_ci_m.lo, 2e-3);
  EXPECT_DOUBLE_EQ(s.ate_ci_m.hi, 9e-3);
  EXPECT_DOUBLE_EQ(s.tracking_ms, 1.55);
  EXPECT_DOUBLE_EQ(s.tracking_ci_ms.lo, 1.2);
  EXPECT_DOUBLE_EQ(s.tracking_ci_ms.hi, 1.9);
  // 9 videos: 3, 4, 6, ..., 12; the 2nd and 8th of 9.
  EXPECT_DOUBLE_EQ(s.detection_ms, 8.0);
  EXPECT_DOUBLE_EQ(s.detection_ci_ms.lo, 4.0);
  EXPECT_DOUBLE_EQ(s.detection_ci_ms.hi, 11.0);
  EXPECT_EQ(s.occlusions, 20);
  EXPECT_EQ(s.never_reacquired, 1);
  // Five videos cannot give a 95 % interval of their median.
  videos.resize(5);
  const SequenceSummaryRow few = SummaryOfSequences(cell, videos);
  EXPECT_DOUBLE_EQ(few.tracking_ms, 1.3);
  EXPECT_TRUE(std::isnan(few.tracking_ci_ms.lo));
  EXPECT_TRUE(std::isnan(few.tracking_ci_ms.hi));
}

// The CSV names each figure's interval beside it.
TEST(SequenceSummary, CsvCarriesTheTimesIntervals) {
  SequenceSummaryRow s;
  s.scenario = "orbit";
  s.sweep_parameter = "noise_var";
  s.tracking_ms = 1.5;
  s.tracking_ci_ms = {1.25, 1.75};
  s.detection_ms = 2.5;
  const std::string csv = SequenceSummaryCsv({s});
  const std::string header = csv.substr(0, csv.find('\n'));
  EXPECT_NE(header.find(",tracking_median_ms,tracking_median_lo_ms,tracking_median_hi_ms,"
                        "detection_median_ms,detection_median_lo_ms,detection_median_hi_ms"),
            std::string::npos);
  const std::string times = ",1.5,1.25,1.75,2.5,,\n";  // no interval of detection
  EXPECT_EQ(csv.substr(csv.size() - times.size()), times);
}

}  // namespace
}  // namespace markerbench
