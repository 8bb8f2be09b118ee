// `markerbench render` in its two forms (architecture.md, "CLI"): frames of a scenario, or
// explicit poses of one marker. Writes frame_NNNNNN.png and groundtruth.csv into a folder.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "bench/plan/scenario.h"
#include "core/rigid3.h"
#include "renderer/render_frame.h"

namespace markerbench {

// Renders the scenario's frames in (cell, trial, marker) order, at most `limit` (0: all),
// into an empty folder (bench/io/output_folder.h: CreateEmptyOutputFolder). With write_float,
// also frame_NNNNNN.exr: the linear float image after noise and clipping.
void RenderScenario(const std::string& scenario_path,
                    const std::string& out_dir,
                    int limit,
                    bool write_float,
                    bool overwrite);

struct ExplicitRenderOptions {
  std::string marker_path;
  std::string camera_path;
  std::string poses_path;
  std::string out_dir;
  Degradations degradations;  // the options set noise_var, blur_sigma_px and gamma
  uint64_t seed = 0;
  bool write_float = false;  // also frame_NNNNNN.exr (linear, after noise and clipping)
  bool overwrite = false;    // replace the dataset rendered in out_dir before
  // Each frame's Cramér-Rao bound in groundtruth.csv (about as long as its render); else
  // its columns are empty, as a scenario's with crlb: false.
  bool crlb = true;
};

void RenderPoses(const ExplicitRenderOptions& options);

// The explicit form's inputs (render, crlb): a marker, a camera and poses, and what every
// frame of them shares. Throws ConfigError naming the bad file or option.
struct ExplicitFrames {
  MarkerSpec marker;
  Camera camera;
  std::vector<Rigid3> poses;
  Degradations degradations;
  int channels = 1;

  // The frame of poses[i]; refers to `marker`, so keep this alive while it is used.
  FrameRequest Request(size_t i) const;
};
ExplicitFrames LoadExplicitFrames(const std::string& marker_path,
                                  const std::string& camera_path,
                                  const std::string& poses_path,
                                  const Degradations& degradations,
                                  Channels channels);

// POSES.csv: header r11,r12,r13,r21,r22,r23,r31,r32,r33,tx,ty,tz, then one cam_from_marker
// per row. Throws ConfigError naming the file, line and column.
std::vector<Rigid3> LoadPosesCsv(const std::string& path);

}  // namespace markerbench
