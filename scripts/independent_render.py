#!/usr/bin/env python3
"""A second renderer, written apart from renderer/, and the circle tracker on its frames.

Issue 21 asks that the tracker hold its accuracy on images from a renderer other than ours.
This one re-renders each frame of a dataset that `markerbench render` wrote, from its
ground truth alone, by other means than renderer/: each pixel's ink is the mean of 8x8 point
samples of the marker plane (renderer/ integrates the exact area of each shape), the optics'
blur is OpenCV's GaussianBlur (on the point samples below 3.5 px, where a kernel sampled at
whole pixels would miss the continuous blur by more than half a level), and the noise comes
from numpy's generator (then clipped to [0, 1] and rounded to 8 bits, imnoise's model). Pixel
centres lie at integer coordinates. Markers of disks only (circles_a-c, circle_d); no motion
blur, JPEG or sequences.

  independent_render.py SCENARIO... --out DIR [--datasets DIR] [--markerbench PATH]
                        [--tracker circle]

renders each scenario with markerbench into DATASETS/ours/<name>, re-renders a copy of it
into DATASETS/independent/<name>, runs the tracker (`markerbench track`) on both, scores both
(`markerbench score`) into the run folders OUT/ours and OUT/independent, reports both and
pairs them frame by frame into OUT/check.md (`markerbench check OUT/independent --reference
OUT/ours`: where the tracker does better or worse on the other renderer's frames).

  independent_render.py --compare DATASET

re-renders DATASET's frames without noise and prints, per frame, its number, its blur σ, and
the largest and the mean absolute difference to DATASET's own image in 8-bit levels (the two
renderers' agreement; a test runs it on noise-free frames).
"""
import argparse
import csv
import math
import pathlib
import shutil
import subprocess
import sys

import cv2
import numpy as np
import yaml

SUBSAMPLES = 8  # point samples per pixel along each axis
# Blurs below this σ (px) act on the point samples, as renderer/degradations.h explains.
FINE_BLUR_BELOW_PX = 3.5


def fail(message):
    print(f"independent_render: {message}", file=sys.stderr)
    sys.exit(2)


def read_disks(marker_path):
    """The marker's disks in paint order as (centre x, y, radius, colour), scaled, and its
    background colour."""
    spec = yaml.safe_load(marker_path.read_text())
    known = {"kind", "disks", "center_dot", "feature_dot", "background", "scale", "name"}
    unknown = sorted(set(spec) - known)
    if unknown:
        fail(f"{marker_path}: key '{unknown[0]}': only markers of disks can be re-rendered")
    scale = float(spec.get("scale", 1.0))
    disks = list(spec.get("disks", []))
    disks += [spec[key] for key in ("center_dot", "feature_dot") if key in spec]
    return ([(scale * d["center"][0], scale * d["center"][1], scale * d["radius"],
              np.array(d["color"], dtype=np.float64)) for d in disks],
            np.array(spec["background"], dtype=np.float64))


def ink(row, disks, background):
    """The marker seen at the row's pose: the mean of SUBSAMPLES² point samples a pixel, as
    linear RGB in [0, 1] (height x width x 3); the samples blurred first if the row's blur is
    below FINE_BLUR_BELOW_PX."""
    width, height = int(row["width"]), int(row["height"])
    K = np.array([[float(row["fx"]), 0.0, float(row["cx"])],
                  [0.0, float(row["fy"]), float(row["cy"])], [0.0, 0.0, 1.0]])
    R = np.array([[float(row[f"r{i}{j}"]) for j in (1, 2, 3)] for i in (1, 2, 3)])
    t = np.array([float(row[k]) for k in ("tx", "ty", "tz")])
    H = K @ np.column_stack([R[:, 0], R[:, 1], t])  # plane (X, Y, 1) to pixels
    image = np.empty((height, width, 3))
    image[:] = background
    # The disks' reach in the image, with room for the blur.
    reach = 4.0 * float(row["blur_sigma_px"]) + 3.0
    angles = np.linspace(0.0, 2.0 * math.pi, 256, endpoint=False)
    outline = np.concatenate([
        np.stack([x + r * np.cos(angles), y + r * np.sin(angles), np.ones_like(angles)])
        for x, y, r, _ in disks], axis=1)
    projected = H @ outline
    if np.any(projected[2] <= 0.0):
        fail(f"frame {row['frame']}: a disk crosses the horizon")
    u, v = projected[0] / projected[2], projected[1] / projected[2]
    u0, u1 = max(0, int(math.floor(u.min() - reach))), min(width, int(math.ceil(u.max() + reach)) + 1)
    v0, v1 = max(0, int(math.floor(v.min() - reach))), min(height, int(math.ceil(v.max() + reach)) + 1)
    if u0 >= u1 or v0 >= v1:
        return image
    columns, rows = np.meshgrid(np.arange(u0, u1, dtype=np.float64),
                                np.arange(v0, v1, dtype=np.float64))
    plane_from_px = np.linalg.inv(H)
    # Sample (i, j) of pixel (u, v) is (u, v) + offsets[(i, j)], at [v·S + j, u·S + i] of `samples`.
    samples = np.empty(((v1 - v0) * SUBSAMPLES, (u1 - u0) * SUBSAMPLES, 3))
    offsets = (np.arange(SUBSAMPLES) + 0.5) / SUBSAMPLES - 0.5
    for i, du in enumerate(offsets):
        for j, dv in enumerate(offsets):
            pu, pv = columns + du, rows + dv
            h = [plane_from_px[k, 0] * pu + plane_from_px[k, 1] * pv + plane_from_px[k, 2]
                 for k in range(3)]
            x, y = h[0] / h[2], h[1] / h[2]
            sample = np.empty((v1 - v0, u1 - u0, 3))
            sample[:] = background
            for cx, cy, radius, color in disks:
                sample[(x - cx) ** 2 + (y - cy) ** 2 <= radius * radius] = color
            samples[j::SUBSAMPLES, i::SUBSAMPLES] = sample
    sigma = float(row["blur_sigma_px"])
    if 0.0 < sigma < FINE_BLUR_BELOW_PX:
        samples = cv2.GaussianBlur(samples, (0, 0), sigmaX=SUBSAMPLES * sigma,
                                   sigmaY=SUBSAMPLES * sigma, borderType=cv2.BORDER_REPLICATE)
    image[v0:v1, u0:u1] = samples.reshape(v1 - v0, SUBSAMPLES, u1 - u0, SUBSAMPLES, 3).mean(
        axis=(1, 3))
    return image


def degrade(row, linear, with_noise):
    """Blur, lighting, noise, clipping, gamma and 8-bit rounding, as the row asks (RGB or grey)."""
    for key in ("motion_blur_px", "jpeg_quality", "exposure_s"):
        if row[key] and float(row[key]) != 0.0:
            fail(f"frame {row['frame']}: key '{key}' is not re-rendered")
    sigma = float(row["blur_sigma_px"])
    if sigma >= FINE_BLUR_BELOW_PX:  # a sharper blur acted on the point samples (ink)
        linear = cv2.GaussianBlur(linear, (0, 0), sigmaX=sigma, sigmaY=sigma,
                                  borderType=cv2.BORDER_REPLICATE)
    linear = float(row["gain"]) * linear + float(row["offset"])
    if int(row["channels"]) == 1:
        linear = linear @ np.array([0.299, 0.587, 0.114])
    if with_noise and float(row["noise_var"]) > 0.0:
        generator = np.random.default_rng([int(row["seed"]), int(row["frame"])])
        linear = linear + generator.normal(0.0, math.sqrt(float(row["noise_var"])), linear.shape)
    encoded = np.clip(linear, 0.0, 1.0) ** (1.0 / float(row["gamma"]))  # camera response
    return np.rint(255.0 * encoded).astype(np.uint8)


def write_image(path, image):
    if not cv2.imwrite(str(path), image if image.ndim == 2 else image[:, :, ::-1]):
        fail(f"{path}: cannot be written")


def read_image(path):
    image = cv2.imread(str(path), cv2.IMREAD_UNCHANGED)
    if image is None:
        fail(f"{path}: cannot be read")
    return image if image.ndim == 2 else image[:, :, ::-1]


def groundtruth(dataset):
    path = dataset / "groundtruth.csv"
    if not path.exists():
        fail(f"{dataset}: no groundtruth.csv (not a dataset markerbench render wrote)")
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def rerender(dataset, with_noise=True):
    """Yields (row, the frame re-rendered) for every frame of the dataset."""
    markers = {}
    for row in groundtruth(dataset):
        if row["marker"] not in markers:
            markers[row["marker"]] = read_disks(dataset / "markers" / f"{row['marker']}.yaml")
        disks, background = markers[row["marker"]]
        yield row, degrade(row, ink(row, disks, background), with_noise)


def compare(dataset):
    for row, image in rerender(dataset, with_noise=False):
        ours = read_image(dataset / row["image"]).astype(np.int32)
        difference = np.abs(ours - image.astype(np.int32))
        print(f"{row['frame']} {row['blur_sigma_px']} {difference.max()} {difference.mean():.6f}")


def run(command):
    result = subprocess.run(command, capture_output=True, text=True)
    if result.returncode != 0:
        fail(f"{' '.join(map(str, command))} exited {result.returncode}: {result.stderr.strip()}")
    return result.stdout


def track_and_score(markerbench, tracker, dataset, run_dir):
    """The tracker on every frame, its estimates scored into run_dir/<the scenario>."""
    frame_of, by_marker = {}, {}  # per image path; the image paths per marker
    for row in groundtruth(dataset):
        image = str(dataset / row["image"])
        frame_of[image] = row["frame"]
        by_marker.setdefault(row["marker"], []).append(image)
    estimates = dataset / "estimates.csv"
    with open(estimates, "w", newline="") as out:
        writer = csv.writer(out)
        pose = [f"r{i}{j}" for i in (1, 2, 3) for j in (1, 2, 3)] + ["tx", "ty", "tz"]
        writer.writerow(["frame", "status"] + pose + ["time_ms"])
        for marker, images in by_marker.items():
            tracked = dataset / f"tracked_{marker}.csv"
            run([markerbench, "track", "--tracker", tracker,
                 "--marker", dataset / "markers" / f"{marker}.yaml",
                 "--camera", dataset / "camera.yaml", "--out", tracked] + images)
            with open(tracked, newline="") as f:
                for row in csv.DictReader(f):
                    ok = row["status"] == "ok"
                    writer.writerow([frame_of[row["image"]], row["status"]] +
                                    [row[k] if ok else "" for k in pose] + [row["time_ms"]])
    run([markerbench, "score", dataset, "--poses", estimates, "--tracker", tracker,
         "--out", run_dir])


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("scenarios", nargs="*")
    parser.add_argument("--out", type=pathlib.Path)
    parser.add_argument("--datasets", type=pathlib.Path, default=pathlib.Path("build/independent"))
    parser.add_argument("--markerbench", default="build/bench/markerbench")
    parser.add_argument("--tracker", default="circle")
    parser.add_argument("--compare", type=pathlib.Path, metavar="DATASET")
    args = parser.parse_args()
    if args.compare:
        compare(args.compare)
        return
    if not args.scenarios or not args.out:
        fail("give SCENARIO... and --out DIR, or --compare DATASET")
    renderers = ("ours", "independent")
    for renderer in renderers:
        shutil.rmtree(args.out / renderer, ignore_errors=True)
        shutil.rmtree(args.datasets / renderer, ignore_errors=True)
    for scenario in args.scenarios:
        name = yaml.safe_load(pathlib.Path(scenario).read_text())["name"]
        ours = args.datasets / "ours" / name
        run([args.markerbench, "render", scenario, "--out", ours])
        independent = args.datasets / "independent" / name
        shutil.copytree(ours, independent)
        for row, image in rerender(independent):
            write_image(independent / row["image"], image)
        for renderer, dataset in zip(renderers, (ours, independent)):
            track_and_score(args.markerbench, args.tracker, dataset, args.out / renderer)
    for renderer in renderers:
        run([args.markerbench, "report", args.out / renderer])
    check = subprocess.run([args.markerbench, "check", args.out / "independent",
                            "--reference", args.out / "ours",
                            "--markdown", args.out / "check.md"], capture_output=True, text=True)
    print(check.stdout.splitlines()[0] if check.stdout else check.stderr.strip())

if __name__ == "__main__":
    main()
