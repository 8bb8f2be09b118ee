#!/usr/bin/python3
"""An external markerbench tracker speaking protocol 1 (README, "Benchmark your own tracker"):
AprilTag 36h11 found by OpenCV's ArUco module (its AprilTag dictionary, AprilTag corner
refinement) and its pose by cv2.solvePnP with IPPE_SQUARE. Needs Debian's python3-opencv and
python3-yaml. Reads JSON lines on standard input, writes one JSON line per request on standard
output (flushed), and logs to standard error.
"""
import json
import sys
import time

import cv2
import numpy as np
import yaml


def log(*words):
    print("apriltag_opencv:", *words, file=sys.stderr, flush=True)


def reply(**fields):
    print(json.dumps(fields), flush=True)


def load_marker(path, cache={}):
    """(id, corners in the marker frame) of an apriltag marker file, with its scale."""
    if path not in cache:
        with open(path) as f:
            marker = yaml.safe_load(f)
        if marker.get("kind") != "apriltag" or marker.get("family") != "tag36h11":
            raise ValueError("only tag36h11 apriltag markers, not %s" % path)
        half = 0.5 * float(marker["size_m"]) * float(marker.get("scale", 1.0))
        # markerbench's corner order: top-left, top-right, bottom-right, bottom-left, in the
        # marker frame (x right, y up, z out of the page), which is also OpenCV's order.
        corners = np.array([[-half, half, 0], [half, half, 0], [half, -half, 0], [-half, -half, 0]],
                           dtype=np.float64)
        cache[path] = (int(marker["id"]), corners)
    return cache[path]


def track(request, dictionary, parameters):
    marker_id, object_points = load_marker(request["marker"])
    image = cv2.imread(request["image"], cv2.IMREAD_GRAYSCALE)
    if image is None:
        return {"status": "error", "message": "cannot read " + request["image"]}
    corners, ids, _ = cv2.aruco.detectMarkers(image, dictionary, parameters=parameters)
    if ids is None or len(ids) == 0:
        return {"status": "not_detected"}
    matches = [i for i, found in enumerate(ids.flatten()) if found == marker_id]
    if not matches:
        return {"status": "wrong_id", "message": "found ids %s" % ids.flatten().tolist()}
    camera = request["camera"]
    matrix = np.array([[camera["fx"], 0, camera["cx"]], [0, camera["fy"], camera["cy"]], [0, 0, 1]])
    # OpenCV's AprilTag dictionary starts at the opposite corner from libapriltag and
    # markerbench (a half turn of the bit pattern), so its corner k is markerbench's k + 2.
    # Its AprilTag refinement reports corners with libapriltag's pixel centres at +0.5, and
    # markerbench's are at 0 (baselines.md): half a pixel back.
    image_points = np.roll(corners[matches[0]].reshape(4, 2), 2, axis=0).astype(np.float64) - 0.5
    found, rvec, tvec = cv2.solvePnP(object_points, image_points, matrix,
                                     np.array(camera["dist"], dtype=np.float64),
                                     flags=cv2.SOLVEPNP_IPPE_SQUARE)
    if not found:
        return {"status": "pose_failed"}
    rotation, _ = cv2.Rodrigues(rvec)
    return {"status": "ok",
            "poses": [{"R": rotation.flatten().tolist(), "t": tvec.flatten().tolist()}]}


def main():
    hello = json.loads(sys.stdin.readline())
    if hello.get("protocol") != 1:
        log("unsupported protocol", hello)
        return 2
    dictionary = cv2.aruco.getPredefinedDictionary(cv2.aruco.DICT_APRILTAG_36h11)
    parameters = cv2.aruco.DetectorParameters_create()
    parameters.cornerRefinementMethod = cv2.aruco.CORNER_REFINE_APRILTAG
    reply(protocol=1, ready=True)
    for line in sys.stdin:
        request = json.loads(line)
        start = time.perf_counter()
        try:
            result = track(request, dictionary, parameters)
        except Exception as error:  # a bad frame is an error row, never a dead tracker
            result = {"status": "error", "message": repr(error)}
        result["time_ms"] = 1000.0 * (time.perf_counter() - start)
        reply(**result)
    return 0


if __name__ == "__main__":
    sys.exit(main())
