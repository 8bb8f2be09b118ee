// The printed edges of a marker as one image sees them: short pieces of every boundary across
// which the printed colour changes, with the colour jump across each. The Cramér-Rao bound
// (pose_crlb.h) integrates the jump times the edge's normal image velocity along them
// (crlb.md, "Model").
//
// Edges are those of the marker's painted layers (disks, crescents, sectors, grid cells); a
// piece counts once, for the top-most layer that changes colour across it, so edges hidden
// under a higher layer or shared by two layers are never counted twice. The sheet's edge and
// the horizon are left out: they carry pose information that no marker tracker is told about.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <vector>

#include "renderer/scene.h"

namespace markerbench {

struct BoundaryPiece {
  Eigen::Vector2d a_px;          // first end, in pixels (distortion applied)
  Eigen::Vector2d b_px;          // second end
  Eigen::Vector3d mid_cam;       // the edge's point at the middle of the piece, camera frame
  Eigen::Vector2d normal_px;     // perpendicular to b - a, as long as it, towards the plus side
  std::array<double, 3> jump{};  // colour on the plus side minus the other, per channel
};

// Pieces of at most max_piece_px in the image, in front of the camera and with an end inside
// `window_px`; `channels` 1 gives jumps in Rec. 601 luma (as the rasteriser), 3 in RGB.
std::vector<BoundaryPiece> ImageBoundaryPieces(const Scene& scene,
                                               int channels,
                                               const Eigen::AlignedBox2d& window_px,
                                               double max_piece_px);

// d(pixel)/d(camera-frame point) at x_cam (z > 0), through the camera's distortion.
Eigen::Matrix<double, 2, 3> ImgFromCamJacobian(const Camera& camera, const Eigen::Vector3d& x_cam);

}  // namespace markerbench
