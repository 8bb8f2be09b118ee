#include "bench/io/progress.h"

#include <unistd.h>

#include <cmath>

namespace markerbench {
namespace {

constexpr int kBarWidth = 30;
constexpr double kRedrawInterval_s = 0.25;

double SecondsBetween(std::chrono::steady_clock::time_point a,
                      std::chrono::steady_clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

}  // namespace

std::string DurationText(double seconds) {
  const long s = std::lround(std::max(0.0, seconds));
  char text[32];
  if (s >= 3600) {
    std::snprintf(text, sizeof(text), "%ldh%02ldm", s / 3600, s / 60 % 60);
  } else if (s >= 60) {
    std::snprintf(text, sizeof(text), "%ldm%02lds", s / 60, s % 60);
  } else {
    std::snprintf(text, sizeof(text), "%lds", s);
  }
  return text;
}

Progress::Progress(std::string label, size_t total, size_t done, double line_interval_s)
    : label_(std::move(label)),
      total_(total),
      done_(done),
      done_at_start_(done),
      terminal_(::isatty(STDERR_FILENO) != 0),
      line_interval_s_(line_interval_s),
      start_(std::chrono::steady_clock::now()),
      last_print_(start_) {}

void Progress::Advance(size_t items) {
  done_ += items;
  const auto now = std::chrono::steady_clock::now();
  const double since = SecondsBetween(last_print_, now);
  if (since >= (terminal_ ? kRedrawInterval_s : line_interval_s_)) Print(false);
}

void Progress::Finish() { Print(true); }

void Progress::Print(bool final_line) {
  const auto now = std::chrono::steady_clock::now();
  last_print_ = now;
  const double elapsed = SecondsBetween(start_, now);
  const double rate = elapsed > 0.0 ? static_cast<double>(done_ - done_at_start_) / elapsed : 0.0;
  const double eta = rate > 0.0 ? static_cast<double>(total_ - done_) / rate : 0.0;
  const double fraction = total_ ? static_cast<double>(done_) / static_cast<double>(total_) : 1.0;
  std::string text = label_ + ' ';
  if (terminal_) {
    const int filled = static_cast<int>(fraction * kBarWidth);
    text += '[' + std::string(filled, '#') + std::string(kBarWidth - filled, '.') + "] ";
  }
  char numbers[128];
  std::snprintf(numbers,
                sizeof(numbers),
                "%3.0f%% %zu/%zu frames, %.1f frames/s, %s %s",
                100.0 * fraction,
                done_,
                total_,
                rate,
                final_line ? "took" : "ETA",
                DurationText(final_line ? elapsed : eta).c_str());
  text += numbers;
  if (terminal_) {
    std::fprintf(stderr, "\r%s\033[K%s", text.c_str(), final_line ? "\n" : "");
  } else {
    std::fprintf(stderr, "%s\n", text.c_str());
  }
  std::fflush(stderr);
}

}  // namespace markerbench
