#!/usr/bin/env python3
"""Writes the fuzz targets' seed corpora (committed; re-run after a format change).

bench/fuzz_corpus/loaders_fuzz: a selector byte (0 camera, 1 marker, 2 scenario, 3 POSES.csv,
4 frames.csv, 5 frames.csv.zst) and a shipped file (frames.csv: the first rows of the CI
gate's reference run, plain and compressed with the zstd command). trackers/fuzz_corpus/track_fuzz: for each tracker, a 64x48 image in the
target's input format with a marker-like shape (a black square, or a red and a blue disk).
trackers/fuzz_regressions/track_fuzz: inputs fuzzing found slow or failing, which every fuzz
run replays once (scripts/fuzz.sh) but does not mutate: slow seeds would slow the fuzzing.
"""
import pathlib
import subprocess

root = pathlib.Path(__file__).resolve().parent.parent


def write(path, data):
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_bytes(data)


loaders = root / "bench/fuzz_corpus/loaders_fuzz"
write(loaders / "camera", b"\x00" + (root / "scenarios/cameras/default.yaml").read_bytes())
for marker in sorted((root / "scenarios/markers").glob("*.yaml")):
    write(loaders / ("marker_" + marker.stem), b"\x01" + marker.read_bytes())
write(loaders / "scenario", b"\x02" + (root / "scenarios/smoke.yaml").read_bytes())
write(loaders / "poses", b"\x03r11,r12,r13,r21,r22,r23,r31,r32,r33,tx,ty,tz\n"
      b"1,0,0,0,-1,0,0,0,-1,0,0,0.5\n0.9,0,0.43,0,-1,0,0.43,0,-0.9,0.01,0,0.8\n")
frames = (root / "results/reference/ci_noise/frames.csv").read_bytes().split(b"\n")
frames = b"\n".join(frames[:6]) + b"\n"
write(loaders / "frames", b"\x04" + frames)
zstd = subprocess.run(["zstd", "-q", "-c"], input=frames, capture_output=True, check=True).stdout
write(loaders / "frames_zst", b"\x05" + zstd)

width, height = 64, 48
# The tracker byte indexes TrackerNames() (trackers/tracker_factory.cc): keep this its order.
trackers = ["apriltag", "apriltag-ippe", "artkplus", "artkplus-improved", "aruco", "circle",
            "runetag", "runetag-improved"]
for index, name in enumerate(trackers):
    colour = name == "circle"
    pixels = bytearray()
    for y in range(height):
        for x in range(width):
            if colour:
                red = (x - 20) ** 2 + (y - 24) ** 2 < 64
                blue = (x - 44) ** 2 + (y - 24) ** 2 < 64
                pixels += bytes([40, 40, 220] if blue else [220, 40, 40] if red else [240, 240, 240])
            else:
                inside = 16 <= x < 48 and 8 <= y < 40
                pixels.append(20 if inside else 235)
    header = bytes([index, width - 1, height - 1, 3 if colour else 1])
    write(root / "trackers/fuzz_corpus/track_fuzz" / name, header + bytes(pixels))

# A 136x138 RGB texture of tiny quads: OpenCV's ArUco took 1.6 s on it (3.5 s with ASan)
# before the aruco adapter's min_pixels_per_cell.
regressions = root / "trackers/fuzz_regressions/track_fuzz"
write(regressions / "aruco_fine_texture",
      bytes.fromhex("a487890d9f890d9f31f431f4f2"))
# A 256x256 RGB texture of some 5000 dots for runetag-improved: the RANSAC stop's iteration
# count overflowed an int (UBSan), and the search took 1.1 s under the sanitizers.
write(regressions / "runetag_few_inliers",
      bytes.fromhex("ffffff3fa1ffffa1853fa1ffffa1d2d2d2d2d2d2d2d2d2d2d2d2d2d2d2d2"
                    "d2d2d2d2d2d2d2d2d2d2d28573"))
