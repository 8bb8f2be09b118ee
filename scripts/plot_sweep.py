#!/usr/bin/python3
"""Plots of a markerbench sweep folder, like the paper's Fig. 6-8.

Usage: plot_sweep.py DIR

Reads DIR/summary.csv (written by `markerbench report DIR`) and DIR/manifest.json, and
writes, for every scenario:
  DIR/<scenario>.png           median position error (log axis, p90 dashed) over the
                               physical limit (the median Cramér-Rao bound of the frames,
                               dotted, the unreachable region below it shaded) and, in its
                               own panel, the success rate versus the sweep value; one line
                               per tracker, with 95 % bands;
  DIR/<scenario>_rotation_time.png  median rotation error (band, bound dotted) and median
                               time per frame versus the sweep value;
  DIR/<scenario>_examples.png  trial 0 of every marker at the scenario's example value
                               (DIR/<scenario>/examples/<marker>.png), like panels (a)-(d);
  DIR/<scenario>_heatmap.png   for a grid sweep: success rate and median position error over
                               the grid (the first axis across, the other axes down), one row
                               of two heat maps per tracker and marker.
  DIR/<scenario>_error_time.png  for a sequence scenario (a `trajectory`): each tracker's
                               camera-position error against time in the first sequence of
                               every marker, over the frame's Cramér-Rao bound (dotted), the
                               occlusions shaded and lost frames marked on the axis.
A grid's series (tracker, marker, combination of the other axes) are separate lines.
Needs Debian's python3-matplotlib (run with /usr/bin/python3).
"""
import csv
import json
import math
import os
import string
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402

LABELS = {
    "noise_var": "Gaussian noise variance σ²",
    "blur_sigma_px": "Gaussian blur σ (px)",
    "motion_blur_px": "motion blur length (px)",
    "distance_m": "distance (m)",
    "tilt_deg": "tilt (°)",
    "gain": "gain",
    "gamma": "camera gamma",
    "jpeg_quality": "JPEG quality",
}


def number(text):
    return float(text) if text != "" else float("nan")


def log_scale(ax):
    """A log y axis where the axis shows a positive value; else a linear one that says it
    has none (a scored run without times, a tracker that failed every frame)."""
    if any(math.isfinite(y) and y > 0 for line in ax.get_lines() for y in line.get_ydata()):
        ax.set_yscale("log")
    else:
        ax.text(0.5, 0.5, "no values", transform=ax.transAxes, ha="center", va="center",
                color="grey")


def band(rows, column, scale):
    """A column of summary.csv scaled, NaN where empty or absent (an older summary)."""
    return [scale * number(r.get(column) or "") for r in rows]


def read_summary(path):
    scenarios = {}
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            series = scenarios.setdefault(row["scenario"], {})
            key = (row["tracker"], row["marker"], row.get("grid", ""))
            series.setdefault(key, []).append(row)
    return scenarios


def plot_errors(directory, scenario, series):
    parameter = next(iter(series.values()))[0]["sweep_parameter"]
    trackers_with_many_markers = {
        t for t, m, _ in series if len({u for v, u, _ in series if v == t}) > 1
    }
    fig, (err_ax, ok_ax) = plt.subplots(
        2, 1, sharex=True, figsize=(9.5, 6), gridspec_kw={"height_ratios": [3, 2]}
    )
    floors = []
    for (tracker, marker, grid), rows in series.items():
        x = [number(r["sweep_value"]) for r in rows]
        label = f"{tracker} ({marker})" if tracker in trackers_with_many_markers else tracker
        label += f", {grid}" if grid else ""
        median = [1e3 * number(r["position_error_median_m"]) for r in rows]
        p90 = [1e3 * number(r["position_error_p90_m"]) for r in rows]
        success = [100 * number(r["success_rate"]) for r in rows]
        bound = [1e3 * number(r.get("crlb_position_median_m", "")) for r in rows]
        (line,) = err_ax.plot(x, median, "o-", label=label, markersize=4)
        err_ax.plot(x, p90, "--", color=line.get_color(), linewidth=0.8)
        # 95 % intervals of summary.csv: the median's (order statistics), the rate's (Wilson).
        err_ax.fill_between(x, band(rows, "position_error_median_lo_m", 1e3),
                            band(rows, "position_error_median_hi_m", 1e3),
                            color=line.get_color(), alpha=0.18, linewidth=0)
        ok_ax.fill_between(x, band(rows, "success_rate_lo", 100), band(rows, "success_rate_hi", 100),
                           color=line.get_color(), alpha=0.18, linewidth=0)
        if any(math.isfinite(b) for b in bound):
            err_ax.plot(x, bound, ":", color=line.get_color(), linewidth=1.0)
            floors.append((x, bound, line.get_color()))
        ok_ax.plot(x, success, "o-", color=line.get_color(), label=label, markersize=4)
        at_bound = band(rows, "success_at_bound", 100)
        if any(math.isfinite(s) for s in at_bound):
            ok_ax.plot(x, at_bound, ":", color=line.get_color(), linewidth=1.0)
    log_scale(err_ax)
    if floors:
        bottom = err_ax.get_ylim()[0]
        for x, bound, color in floors:
            err_ax.fill_between(x, bottom, bound, color=color, alpha=0.06, linewidth=0)
        err_ax.set_ylim(bottom=bottom)
        err_ax.plot([], [], ":", color="grey", label="physical limit (Cramér-Rao)")
    err_ax.set_ylabel("camera-centre error (mm)\nmedian (95% band), p90 dashed, bound dotted")
    err_ax.grid(True, which="both", alpha=0.3)
    # Beside the axes, never over the data.
    err_ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0)
    err_ax.set_title(f"{scenario}: localization error versus {LABELS.get(parameter, parameter)}")
    ok_ax.axhline(50, color="grey", linewidth=0.8, linestyle=":")
    ok_ax.set_ylim(-5, 105)
    ok_ax.set_ylabel("success rate (%)\n95% Wilson band,\nat the bound dotted")
    ok_ax.set_xlabel(LABELS.get(parameter, parameter))
    ok_ax.grid(True, alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(directory, f"{scenario}.png"), dpi=110)
    plt.close(fig)


def plot_rotation_and_time(directory, scenario, series):
    """<scenario>_rotation_time.png: median rotation error (with its 95 % band and bound) and
    median time per frame, per tracker."""
    parameter = next(iter(series.values()))[0]["sweep_parameter"]
    fig, (rot_ax, time_ax) = plt.subplots(2, 1, sharex=True, figsize=(9.5, 5.5))
    for (tracker, marker, grid), rows in series.items():
        x = [number(r["sweep_value"]) for r in rows]
        label = f"{tracker} ({marker})" + (f", {grid}" if grid else "")
        (line,) = rot_ax.plot(x, band(rows, "rotation_error_median_deg", 1), "o-", label=label,
                              markersize=4)
        rot_ax.fill_between(x, band(rows, "rotation_error_median_lo_deg", 1),
                            band(rows, "rotation_error_median_hi_deg", 1),
                            color=line.get_color(), alpha=0.18, linewidth=0)
        rot_ax.plot(x, band(rows, "crlb_rotation_median_deg", 1), ":", color=line.get_color(),
                    linewidth=1.0)
        time_ax.plot(x, band(rows, "time_median_ms", 1), "o-", color=line.get_color(),
                     markersize=4)
    log_scale(rot_ax)
    rot_ax.set_ylabel("rotation error (°)\nmedian (95% band), bound dotted")
    rot_ax.grid(True, which="both", alpha=0.3)
    rot_ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0)
    rot_ax.set_title(f"{scenario}: rotation error and time per frame versus "
                     f"{LABELS.get(parameter, parameter)}")
    log_scale(time_ax)
    time_ax.set_ylabel("time per frame (ms)\nmedian")
    time_ax.set_xlabel(LABELS.get(parameter, parameter))
    time_ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(directory, f"{scenario}_rotation_time.png"), dpi=110)
    plt.close(fig)


def grid_rows(grids):
    """Tick labels and axis label for the heat maps' rows: the value alone when every
    combination is one parameter's, else the combinations themselves."""
    pairs = [g.split(";") for g in grids]
    names = {p.split("=")[0] for pair in pairs for p in pair}
    if all(len(pair) == 1 for pair in pairs) and len(names) == 1:
        name = names.pop()
        return [pair[0].split("=", 1)[1] for pair in pairs], LABELS.get(name, name)
    return grids, "grid"


def plot_heatmap(directory, scenario, series):
    """<scenario>_heatmap.png: success rate and median position error over a grid sweep."""
    from matplotlib.colors import LogNorm

    pairs, grids, values = [], [], []
    for (tracker, marker, grid), rows in series.items():
        if (tracker, marker) not in pairs:
            pairs.append((tracker, marker))
        if grid not in grids:
            grids.append(grid)
        for r in rows:
            if number(r["sweep_value"]) not in values:
                values.append(number(r["sweep_value"]))
    parameter = next(iter(series.values()))[0]["sweep_parameter"]
    y_ticks, y_label = grid_rows(grids)
    fig, axes = plt.subplots(len(pairs), 2, squeeze=False,
                             figsize=(5.5 + 0.5 * len(values), 1.2 + (1.0 + 0.35 * len(grids)) * len(pairs)))
    for (tracker, marker), (ok_ax, err_ax) in zip(pairs, axes):
        success = [[math.nan] * len(values) for _ in grids]
        error = [[math.nan] * len(values) for _ in grids]
        for i, grid in enumerate(grids):
            for r in series.get((tracker, marker, grid), []):
                j = values.index(number(r["sweep_value"]))
                success[i][j] = 100 * number(r["success_rate"])
                error[i][j] = 1e3 * number(r["position_error_median_m"])
        finite = [e for row in error for e in row if math.isfinite(e) and e > 0]
        panels = [(ok_ax, success, dict(cmap="RdYlGn", vmin=0, vmax=100), "success (%)", "{:.0f}")]
        if finite:
            panels.append((err_ax, error, dict(cmap="viridis_r", norm=LogNorm(min(finite), max(finite))),
                           "median error (mm)", "{:.3g}"))
        else:
            err_ax.axis("off")
        for ax, data, style, title, text in panels:
            image = ax.imshow(data, aspect="auto", **style)
            for i, row in enumerate(data):
                for j, v in enumerate(row):
                    if math.isfinite(v):
                        r, g, b, _ = image.cmap(image.norm(v))
                        dark = 0.299 * r + 0.587 * g + 0.114 * b < 0.45
                        ax.text(j, i, text.format(v), ha="center", va="center", fontsize=7,
                                color="white" if dark else "black")
            ax.set_xticks(range(len(values)), [f"{v:g}" for v in values], fontsize=8)
            ax.set_yticks(range(len(grids)), y_ticks, fontsize=8)
            ax.set_xlabel(LABELS.get(parameter, parameter), fontsize=8)
            ax.set_ylabel(y_label, fontsize=8)
            ax.set_title(f"{tracker} ({marker}): {title}", fontsize=9)
            fig.colorbar(image, ax=ax)
    fig.suptitle(f"{scenario}: success rate and median camera-centre error over the grid")
    fig.tight_layout()
    fig.savefig(os.path.join(directory, f"{scenario}_heatmap.png"), dpi=100)
    plt.close(fig)


def plot_examples(directory, scenario, entry):
    folder = os.path.join(directory, scenario, "examples")
    markers = entry.get("markers") or sorted(
        os.path.splitext(name)[0] for name in os.listdir(folder) if name.endswith(".png")
    )
    images = [(m, os.path.join(folder, m + ".png")) for m in markers]
    images = [(m, path) for m, path in images if os.path.exists(path)]
    if not images:
        return
    columns = min(len(images), 3)
    rows = (len(images) + columns - 1) // columns
    fig, axes = plt.subplots(rows, columns, figsize=(4 * columns, 3.3 * rows), squeeze=False)
    for ax in axes.flat:
        ax.axis("off")
    for ax, letter, (marker, path) in zip(axes.flat, string.ascii_lowercase, images):
        image = mpimg.imread(path)
        ax.imshow(image, cmap="gray" if image.ndim == 2 else None, vmin=0, vmax=1)
        ax.set_title(f"({letter}) {marker}", fontsize=10)
    sweep = entry.get("sweep", {})
    parameter = sweep.get("parameter", "")
    fig.suptitle(
        f"{scenario}: trial 0 at {LABELS.get(parameter, parameter)} = {sweep.get('example_value', '?')}"
    )
    fig.tight_layout()
    fig.savefig(os.path.join(directory, f"{scenario}_examples.png"), dpi=90)
    plt.close(fig)


def plot_error_time(directory, scenario, entry):
    """Error against time in trial 0 at the first sweep value, one panel per marker."""
    trajectory = entry["trajectory"]
    path = os.path.join(directory, scenario, "frames.csv")
    if not os.path.exists(path):
        return  # compressed (sweep --zstd): no plot
    fps = trajectory["fps"]
    truth_delay = 0.5 * (trajectory["exposure_s"] + trajectory["readout_s"])  # TruthTime
    sequences = {}  # marker -> tracker -> [(time, error or None)], and the bound per frame
    with open(path, newline="") as f:
        first_value = None
        for row in csv.DictReader(f):
            if first_value is None:
                first_value = (row["sweep_value"], row["grid"])
            if row["trial"] != "0" or (row["sweep_value"], row["grid"]) != first_value:
                continue
            marker = sequences.setdefault(row["marker"], {"frames": [], "trackers": {}})
            if not marker["frames"] or marker["frames"][-1][0] != row["frame"]:
                marker["frames"].append((row["frame"], number(row["crlb_position_med_m"])))
            k = len(marker["frames"]) - 1
            error = number(row["position_error_m"]) if row["status"] == "ok" else None
            marker["trackers"].setdefault(row["tracker"], []).append((k / fps + truth_delay, error))
    if not sequences:
        return
    fig, axes = plt.subplots(len(sequences), 1, figsize=(9, 2.8 * len(sequences)), squeeze=False)
    for ax, (marker, data) in zip(axes[:, 0], sequences.items()):
        times = [k / fps + truth_delay for k in range(len(data["frames"]))]
        bound = [1e3 * b if math.isfinite(b) else float("nan") for _, b in data["frames"]]
        ax.plot(times, bound, ":", color="black", label="bound (median)")
        for first, last in trajectory["occlusions"]:
            ax.axvspan(first / fps, (last + 1) / fps, color="0.85", zorder=0)
        for tracker, points in data["trackers"].items():
            line = ax.plot(
                [t for t, e in points],
                [1e3 * e if e is not None else float("nan") for t, e in points],
                label=tracker,
            )[0]
            lost = [t for t, e in points if e is None]
            ax.plot(lost, [0] * len(lost), "|", color=line.get_color(), transform=ax.get_xaxis_transform(), markersize=8)
        log_scale(ax)
        ax.set_ylabel("position error (mm)")
        ax.set_title(f"{marker} (trial 0; grey: marker hidden; ticks: no pose)", fontsize=10)
        ax.legend(fontsize=8, loc="upper right")
    axes[-1, 0].set_xlabel("time (s)")
    fig.suptitle(f"{scenario}: {trajectory['kind']} at {fps:g} fps")
    fig.tight_layout()
    fig.savefig(os.path.join(directory, f"{scenario}_error_time.png"), dpi=90)
    plt.close(fig)


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    directory = sys.argv[1]
    manifest_path = os.path.join(directory, "manifest.json")
    manifest = {}
    if os.path.exists(manifest_path):
        with open(manifest_path) as f:
            manifest = json.load(f)
    for scenario, series in read_summary(os.path.join(directory, "summary.csv")).items():
        plot_errors(directory, scenario, series)
        plot_rotation_and_time(directory, scenario, series)
        heatmap = os.path.join(directory, f"{scenario}_heatmap.png")
        if any(grid for _, _, grid in series):
            plot_heatmap(directory, scenario, series)
        elif os.path.exists(heatmap):
            os.remove(heatmap)  # an earlier run of the same name was a grid
        entry = manifest.get("scenarios", {}).get(scenario, {})
        if os.path.isdir(os.path.join(directory, scenario, "examples")):
            plot_examples(directory, scenario, entry)
        if "trajectory" in entry:
            plot_error_time(directory, scenario, entry)


if __name__ == "__main__":
    main()
