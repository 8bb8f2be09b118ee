// Progress of a long run on standard error: a bar with rate and ETA, redrawn in place on a
// terminal, and a plain line every `line_interval_s` otherwise (logs, CI).
#pragma once

#include <chrono>
#include <cstdio>
#include <string>

namespace markerbench {

class Progress {
 public:
  // `done` items of `total` were finished before this run (a resumed sweep).
  Progress(std::string label, size_t total, size_t done, double line_interval_s = 10.0);
  // More items finished. Called by one thread at a time.
  void Advance(size_t items = 1);
  // The final line.
  void Finish();

 private:
  void Print(bool final_line);

  std::string label_;
  size_t total_;
  size_t done_;
  size_t done_at_start_;
  bool terminal_;
  double line_interval_s_;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_print_;
};

// "1h02m", "3m05s", "12s".
std::string DurationText(double seconds);

}  // namespace markerbench
