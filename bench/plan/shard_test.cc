// The shard split: every frame in exactly one shard, every shard with its share of every
// sweep value and marker, and I/N parsed strictly.
#include "bench/plan/shard.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <map>

#include "core/config_error.h"

namespace markerbench {
namespace {

TEST(ShardTest, EveryFrameIsInOneShardAndEveryCellIsSharedEvenly) {
  const int cells = 5, trials = 13, markers = 3;
  for (const int count : {1, 2, 3, 7, 20}) {
    std::map<std::pair<int, int>, int> per_shard_and_cell;  // (shard, cell) -> frames
    for (int cell = 0; cell < cells; ++cell) {
      for (int trial = 0; trial < trials; ++trial) {
        for (int marker = 0; marker < markers; ++marker) {
          PlannedFrame frame;
          frame.cell = cell;
          frame.trial = trial;
          frame.marker_index = marker;
          int owners = 0;
          for (int index = 0; index < count; ++index) {
            if (InShard(frame, trials, {index, count})) {
              ++owners;
              ++per_shard_and_cell[{index, cell}];
            }
          }
          EXPECT_EQ(owners, 1) << count;
        }
      }
    }
    // Every shard holds about trials / count pose groups of each cell, all markers of each.
    for (const auto& [key, frames] : per_shard_and_cell) {
      EXPECT_EQ(frames % markers, 0);
      EXPECT_LE(std::abs(frames / markers - trials / count), 1) << count;
    }
  }
}

TEST(ShardTest, ParsesIOfNStrictly) {
  EXPECT_EQ(ParseShard("0/1").count, 1);
  EXPECT_EQ(ParseShard("6/7").index, 6);
  for (const std::string bad : {"", "1", "1/1", "-1/2", "0/0", "a/2", "0/2x", " 0/2", "0/-3"}) {
    EXPECT_THAT(
        [&] { ParseShard(bad); },
        ::testing::ThrowsMessage<ConfigError>(::testing::HasSubstr("--shard: expected I/N")))
        << bad;
  }
}

}  // namespace
}  // namespace markerbench
