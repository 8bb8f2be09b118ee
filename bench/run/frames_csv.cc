#include "bench/run/frames_csv.h"

#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "bench/run/frame_bound.h"
#include "bench/run/pose_columns.h"
#include "core/joined.h"
#include "core/number_text.h"

namespace markerbench {
namespace {

// The Cramér-Rao bound's columns (frame_bound.h): its RMS and median ones after the errors,
// the variances last.
constexpr size_t kBoundColumnsBeforePoses = 4;

const std::vector<std::string>& Columns() {
  static const std::vector<std::string> kColumns = [] {
    std::vector<std::string> c = {"scenario",
                                  "sweep_parameter",
                                  "sweep_value",
                                  "trial",
                                  "frame",
                                  "marker",
                                  "tracker",
                                  "seed",
                                  "apparent_size_px",
                                  "distance_m",
                                  "status",
                                  "hypotheses",
                                  "position_error_m",
                                  "rotation_error_deg",
                                  "best_position_error_m",
                                  "best_rotation_error_deg",
                                  "flip"};
    const auto& bound = FrameBoundColumns();
    c.insert(c.end(), bound.begin(), bound.begin() + kBoundColumnsBeforePoses);
    for (const char* p : kPoseColumns) c.push_back(std::string("gt_") + p);
    for (const char* p : kPoseColumns) c.push_back(p);
    c.push_back("message");
    c.push_back("grid");
    c.insert(c.end(), bound.begin() + kBoundColumnsBeforePoses, bound.end());
    return c;
  }();
  return kColumns;
}

double ParseNumber(const std::vector<std::string>& f, size_t i, bool optional) {
  if (optional && f[i].empty()) return NAN;
  char* end = nullptr;
  const double v = std::strtod(f[i].c_str(), &end);
  if (f[i].empty() || *end != '\0') {
    throw std::runtime_error("column '" + Columns()[i] + "': expected a number, got '" + f[i] +
                             "'");
  }
  return v;
}

// A whole number in [0, INT_MAX] (trial, frame, hypotheses).
int ParseCount(const std::vector<std::string>& f, size_t i) {
  const std::optional<long long> v = ParseWholeNumber(f[i], 0.0, std::numeric_limits<int>::max());
  if (!v) {
    throw std::runtime_error("column '" + Columns()[i] + "': expected a whole number >= 0, got '" +
                             f[i] + "'");
  }
  return static_cast<int>(*v);
}

// The scenario seed: a whole decimal number of 64 bits.
uint64_t ParseSeed(const std::vector<std::string>& f, size_t i) {
  const std::optional<uint64_t> seed = ParseUnsigned64(f[i]);
  if (!seed) {
    throw std::runtime_error("column '" + Columns()[i] + "': expected a whole number, got '" +
                             f[i] + "'");
  }
  return *seed;
}

}  // namespace

void SetTrackResult(TrackStatus status, const std::vector<Rigid3>& hypotheses, FrameRow* row) {
  const bool has_pose = status == TrackStatus::kOk && !hypotheses.empty();
  row->status = status;
  row->hypotheses = static_cast<int>(hypotheses.size());
  row->errors = ComputePoseErrors(has_pose ? hypotheses : std::vector<Rigid3>{}, row->truth);
  row->estimate = has_pose ? std::optional<Rigid3>(hypotheses.front()) : std::nullopt;
}

std::string CsvField(std::string text) {
  for (char& ch : text) {
    if (ch == '\n' || ch == '\r') ch = ' ';
  }
  if (text.find_first_of(",\"") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char ch : text) quoted += ch == '"' ? std::string("\"\"") : std::string(1, ch);
  return quoted + '"';
}

std::vector<std::string> SplitCsvLine(const std::string& line) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (size_t i = 0; i < line.size(); ++i) {
    const char ch = line[i];
    if (quoted) {
      if (ch == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        fields.back() += '"';
        ++i;
      } else if (ch == '"') {
        quoted = false;
      } else {
        fields.back() += ch;
      }
    } else if (ch == '"') {
      quoted = true;
    } else if (ch == ',') {
      fields.emplace_back();
    } else {
      fields.back() += ch;
    }
  }
  return fields;
}

std::string FramesCsvHeader() { return Joined(Columns(), ",") + '\n'; }

std::string FormatFrameRow(const FrameRow& r) {
  const std::array<double, kFrameBoundColumns> bound = BoundValues(r.bound);
  std::string out =
      CsvField(r.scenario) + ',' + r.sweep_parameter + ',' + NumberText(r.sweep_value) + ',' +
      std::to_string(r.trial) + ',' + std::to_string(r.frame) + ',' + CsvField(r.marker) + ',' +
      CsvField(r.tracker) + ',' + std::to_string(r.seed) + ',' + NumberText(r.apparent_size_px) +
      ',' + NumberText(r.distance_m) + ',' + ToString(r.status) + ',' +
      std::to_string(r.hypotheses) + ',' + NumberTextOrEmpty(r.errors.position_error_m) + ',' +
      NumberTextOrEmpty(r.errors.rotation_error_deg) + ',' +
      NumberTextOrEmpty(r.errors.best_position_error_m) + ',' +
      NumberTextOrEmpty(r.errors.best_rotation_error_deg) + ',' + (r.errors.flip ? "1" : "0") +
      ',' + NumberTextOrEmpty(bound[0]);
  for (size_t k = 1; k < kBoundColumnsBeforePoses; ++k) out += ',' + NumberTextOrEmpty(bound[k]);
  out += PoseFields(r.truth) + (r.estimate ? PoseFields(*r.estimate) : std::string(12, ','));
  out += ',' + CsvField(r.message) + ',' + CsvField(r.grid);
  for (size_t k = kBoundColumnsBeforePoses; k < kFrameBoundColumns; ++k) {
    out += ',' + NumberTextOrEmpty(bound[k]);
  }
  return out + '\n';
}

FrameRow ParseFrameRow(const std::string& line) {
  const std::vector<std::string> f = SplitCsvLine(line);
  if (f.size() != Columns().size()) {
    throw std::runtime_error("expected " + std::to_string(Columns().size()) + " columns, got " +
                             std::to_string(f.size()));
  }
  FrameRow r;
  r.scenario = f[0];
  r.sweep_parameter = f[1];
  r.sweep_value = ParseNumber(f, 2, false);
  r.trial = ParseCount(f, 3);
  r.frame = ParseCount(f, 4);
  r.marker = f[5];
  r.tracker = f[6];
  r.seed = ParseSeed(f, 7);
  r.apparent_size_px = ParseNumber(f, 8, false);
  r.distance_m = ParseNumber(f, 9, false);
  const std::optional<TrackStatus> status = TrackStatusFromString(f[10]);
  if (!status) throw std::runtime_error("column 'status': unknown status '" + f[10] + "'");
  r.status = *status;
  r.hypotheses = ParseCount(f, 11);
  r.errors.position_error_m = ParseNumber(f, 12, true);
  r.errors.rotation_error_deg = ParseNumber(f, 13, true);
  r.errors.best_position_error_m = ParseNumber(f, 14, true);
  r.errors.best_rotation_error_deg = ParseNumber(f, 15, true);
  r.errors.flip = f[16] == "1";
  std::array<double, kFrameBoundColumns> bound;
  for (size_t k = 0; k < kBoundColumnsBeforePoses; ++k) bound[k] = ParseNumber(f, 17 + k, true);
  // Poses as sweep wrote them: trackers' estimates need not be exact rotations.
  r.truth = PoseFromFields(f, ConsecutiveColumns(21), "", RotationCheck::kNone, "gt_");
  if (!f[33].empty())
    r.estimate = PoseFromFields(f, ConsecutiveColumns(33), "", RotationCheck::kNone);
  r.message = f[45];
  r.grid = f[46];
  for (size_t k = kBoundColumnsBeforePoses; k < kFrameBoundColumns; ++k) {
    bound[k] = ParseNumber(f, 47 + k - kBoundColumnsBeforePoses, true);
  }
  r.bound = BoundFromValues(bound);
  return r;
}

std::string TimingCsvHeader() { return "frame,scenario,tracker,success,time_ms,round_trip_ms\n"; }

std::string FormatTimingRow(const FrameRow& row, double time_ms, double round_trip_ms) {
  const bool success = IsSuccess(
      row.estimate.has_value(), row.errors.position_error_m, row.distance_m, kSuccessFraction);
  char ms[64];
  std::snprintf(ms, sizeof(ms), "%.4f,%.4f", time_ms, round_trip_ms);
  return std::to_string(row.frame) + ',' + CsvField(row.scenario) + ',' + CsvField(row.tracker) +
         (success ? ",1," : ",0,") + ms + '\n';
}

}  // namespace markerbench
