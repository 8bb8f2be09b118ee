#!/usr/bin/env python3
"""The README's figure tables, generated from the committed results so that they cannot drift.

Each table sits in README.md (the circle accuracy table also in results/circle_accuracy.md,
the paper sweeps' times in results/speed.md) between
    <!-- readme_figures.py: NAME -->   and   <!-- end NAME -->
and is computed from results/ (summary.csv of results/circle_accuracy and results/paper,
results/paper/breakdowns.csv, results/paper/report.md, results/speed.md, results/sequences/sequence_summary.csv,
results/sequences/recede_pairs.csv,
results/independent/*/summary.csv).

The README's prose cites some of the same figures; each such phrase is listed in PHRASES with
its numbers written {} and computed from results/ as well, and is checked and rewritten with
the tables (its words and line breaks kept, only its numbers replaced).

    readme_figures.py --check   exit 1 naming each table or phrase unlike results/ (ctest)
    readme_figures.py --write   rewrite the tables and phrases in the documents (DOCUMENTS)
"""
import csv
import functools
import math
import pathlib
import re
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
README = ROOT / "README.md"


@functools.lru_cache(maxsize=None)
def read_summary(path):
    """A summary's rows, read once (the figures look many rows up in the same files)."""
    with open(ROOT / path, newline="") as f:
        return tuple(csv.DictReader(f))


def number(text):
    return float(text) if text not in ("", None) else math.nan


def significant(value, digits=3):
    """3 significant digits, trailing zeros kept (1.41, 2.00, 0.158, 102), whole numbers from
    1000 on; '-' for NaN."""
    if math.isnan(value):
        return "-"
    if abs(float(f"{value:.{digits}g}")) >= 10 ** digits:  # also where rounding reaches it
        return f"{value:.0f}"
    return f"{value:#.{digits}g}".rstrip(".")


# The markers of the paper's comparison (Fig. 6-8); the paper runs also sweep circle_d, e and
# f, which the circle_markers table compares.
COMPARISON_MARKERS = {"circles_a", "apriltag", "artkplus", "runetag", "aruco"}


def read_paper_summary():
    return [r for r in read_summary("results/paper/summary.csv")
            if r["marker"] in COMPARISON_MARKERS]


def cell(rows, scenario, value, tracker=None, marker=None):
    return [r for r in rows if r["scenario"] == scenario and number(r["sweep_value"]) == value
            and r.get("grid", "") == "" and (tracker is None or r["tracker"] == tracker)
            and (marker is None or r["marker"] == marker)]


def summary_row(path, scenario, value, tracker, marker):
    """The one row of a summary for a sweep value, tracker and marker."""
    [row] = cell(read_summary(path), scenario, value, tracker, marker)
    return row


# (scenario, sweep value, condition, target as text, minimum success, maximum median error
# in mm or None, maximum ours / bound or None): the targets of results/circle_accuracy.md; a
# value that misses is bold.
CIRCLE_ACCURACY = [
    ("circle_accuracy_0.6m_noise", 0.0, "0.6 m, no noise or blur", "≤ 0.5 mm, 100 %", 1.0, 0.5,
     None),
    ("circle_accuracy_0.6m_noise", 0.02, "0.6 m, σ² = 0.02", "≤ 3 mm, 100 %", 1.0, 3.0, None),
    ("circle_accuracy_0.6m_noise", 0.3, "0.6 m, σ² = 0.3", "≥ 95 %", 0.95, None, None),
    ("circle_accuracy_1m_blur10", 10.0, "1.0 m, σ² = 0.02, blur σ = 10", "≥ 95 %, ≤ 10 mm", 0.95,
     10.0, None),
    ("circle_accuracy_3.5m", 3.5, "3.5 m, σ² = 0.02", "≥ 95 %", 0.95, None, None),
    ("circle_accuracy_0.6m_low_noise", 6e-5, "0.6 m, σ² = 6e-5 (2 grey levels)", "≤ 1.5× bound",
     1.0, None, 1.5),
    ("circle_accuracy_0.6m_low_noise", 2.5e-4, "0.6 m, σ² = 2.5e-4 (4 levels)", "≤ 1.5× bound",
     1.0, None, 1.5),
    ("circle_accuracy_0.6m_low_noise", 1e-3, "0.6 m, σ² = 1e-3 (8 levels)", "≤ 1.5× bound", 1.0,
     None, 1.5),
    ("circle_accuracy_0.6m_slight_blur", 0.3, "0.6 m, σ² = 2.5e-4, blur σ = 0.3", "≤ 1.5× bound",
     1.0, None, 1.5),
    ("circle_accuracy_0.6m_slight_blur", 0.6, "0.6 m, σ² = 2.5e-4, blur σ = 0.6", "≤ 1.5× bound",
     1.0, None, 1.5),
    ("circle_accuracy_0.6m_slight_blur", 1.0, "0.6 m, σ² = 2.5e-4, blur σ = 1", "≤ 1.5× bound",
     1.0, None, 1.5),
    # A colour camera's JPEG (4:2:0): no target, measured against the same scenario's frames
    # without JPEG (quality 0).
    ("circle_accuracy_0.6m_jpeg", 0.0, "0.6 m, σ² = 2.5e-4, no JPEG", "none", 0.0, None, None),
    ("circle_accuracy_0.6m_jpeg", 95.0, "0.6 m, σ² = 2.5e-4, JPEG quality 95 (4:2:0)", "none",
     0.0, None, None),
    ("circle_accuracy_0.6m_jpeg", 75.0, "0.6 m, σ² = 2.5e-4, JPEG quality 75 (4:2:0)", "none",
     0.0, None, None),
]


def circle_accuracy():
    rows = read_summary("results/circle_accuracy/summary.csv")
    lines = ["| condition | target | success (95 % interval) | median camera-centre error (95 % interval) "
             "| median bound | ours / bound | success at bound |",
             "|---|---|---|---|---|---|---|"]
    for scenario, value, condition, target, min_success, max_mm, max_ratio in CIRCLE_ACCURACY:
        (r,) = cell(rows, scenario, value, "circle", "circles_a")
        success = number(r["success_rate"])
        median_mm = 1e3 * number(r["position_error_median_m"])
        success_text = (f"{100 * success:.0f} % ({100 * number(r['success_rate_lo']):.0f}–"
                        f"{100 * number(r['success_rate_hi']):.0f})")
        median_text = (f"{significant(median_mm)} mm "
                       f"({significant(1e3 * number(r['position_error_median_lo_m']))}–"
                       f"{significant(1e3 * number(r['position_error_median_hi_m']))})")
        if success < min_success:
            success_text = f"**{success_text}**"
        if max_mm is not None and median_mm > max_mm:
            median_text = f"**{median_text}**"
        bound_text = f"{significant(1e3 * number(r['crlb_position_median_m']))} mm"
        ratio_text = significant(number(r["efficiency"]))
        if max_ratio is not None and number(r["efficiency"]) > max_ratio:
            ratio_text = f"**{ratio_text}**"
        lines.append(f"| {condition} | {target} | {success_text} | {median_text} | {bound_text} "
                     f"| {ratio_text} "
                     f"| {100 * number(r['success_at_bound']):.1f} % |")
    return lines


# (scenario, sweep value, the cell's name in the table)
EFFICIENCY_CELLS = [
    ("fig6_noise", 0.02, "0.6 m, σ² = 0.02"),
    ("fig6_noise", 0.3, "0.6 m, σ² = 0.3"),
    ("fig7_blur", 0.0, "1 m, blur 0"),
    ("fig7_blur", 5.0, "1 m, blur σ = 5"),
    ("fig7_blur", 10.0, "1 m, blur σ = 10"),
    ("fig8_distance", 2.5, "2.5 m, σ² = 0.02"),
]
TRACKERS = ["circle", "apriltag", "apriltag-ippe", "artkplus", "artkplus-improved", "runetag",
            "runetag-improved", "aruco"]


def efficiency():
    rows = read_paper_summary()
    lines = ["| cell | " + " | ".join(f"`{t}`" for t in TRACKERS) + " | median bound |",
             "|---|" + "---|" * (len(TRACKERS) + 1)]
    for scenario, value, name in EFFICIENCY_CELLS:
        values, bounds = [], []
        for tracker in TRACKERS:
            found = cell(rows, scenario, value, tracker)
            ratio = number(found[0]["efficiency"]) if found else math.nan
            values.append(significant(ratio))
            if found and not math.isnan(ratio):
                bounds.append((1e3 * number(found[0]["crlb_position_median_m"]), found[0]["marker"]))
        if len(bounds) == 1:
            bound = f"{significant(bounds[0][0])} mm (`{bounds[0][1]}`)"
        else:
            lo, hi = min(b for b, _ in bounds), max(b for b, _ in bounds)
            bound = f"{significant(lo, 2)}-{significant(hi, 2)} mm"
        lines.append(f"| {name} | " + " | ".join(values) + f" | {bound} |")
    return lines


BREAKDOWN_SWEEPS = [("fig6_noise", "noise σ²"), ("fig7_blur", "blur σ (px)"),
                    ("fig8_distance", "distance (m)")]


def breakdowns():
    """Per tracker of the paper runs: the first sweep value with success below 50 % (the
    report's breakdown), or the last value reached; and the median time per call."""
    rows = read_paper_summary()
    lines = ["| tracker | " + " | ".join(f"breakdown: {label}" for _, label in BREAKDOWN_SWEEPS) +
             " | median ms per call |",
             "|---|" + "---|" * (len(BREAKDOWN_SWEEPS) + 1)]
    for tracker in TRACKERS:
        times = [number(r["time_median_ms"]) for r in rows if r["tracker"] == tracker]
        texts = breakdown_texts(tracker)
        lines.append(f"| `{tracker}` | " + " | ".join(texts) +
                     f" | {significant(min(times), 2)}-{significant(max(times), 2)} |")
    return lines


# The originals, built on the side and run on these scenarios' renders (25 trials per value;
# ../shared/design/baselines.md, "The originals, measured on our renders"): breakdowns of
# noise, blur and distance, then the clean 0.6 m success and median camera-centre error.
ORIGINALS = {
    "artkplus": ("ARToolKitPlus 2.2", ["0.12", "2", "2.25"], "100 %", 7.00),
    "runetag": ("RUNETag (2015)", ["0.01", "0", "0.5"], "56 %", 2.46),
}


def breakdown_texts(tracker, marker=None):
    """Per paper sweep, the report's breakdown (results/paper/breakdowns.csv) of `tracker` on
    `marker` (default: its marker of the paper's comparison), or "none to" the last value."""
    if marker is None:
        (marker,) = {r["marker"] for r in read_paper_summary() if r["tracker"] == tracker}
    rows = read_summary("results/paper/breakdowns.csv")
    texts = []
    for scenario, _ in BREAKDOWN_SWEEPS:
        (r,) = [r for r in rows if r["scenario"] == scenario and r["tracker"] == tracker
                and r["marker"] == marker and r["grid"] == ""]
        texts.append(f"{number(r['breakdown_value']):g}" if r["breakdown_value"]
                     else f"none to {number(r['last_value']):g}")
    return texts


def baselines():
    """The faithful baselines beside the originals they re-implement, and the improved ones."""
    rows = read_paper_summary()
    lines = ["| system | " + " | ".join(f"breakdown: {label}" for _, label in BREAKDOWN_SWEEPS) +
             " | clean 0.6 m: success | clean 0.6 m: median error, mm |",
             "|---|" + "---|" * (len(BREAKDOWN_SWEEPS) + 2)]
    for tracker, (name, original, found, median_mm) in ORIGINALS.items():
        lines.append(f"| {name}, original (measured) | " + " | ".join(original) +
                     f" | {found} | {significant(median_mm)} |")
        for ours in (tracker, tracker + "-improved"):
            (r,) = cell(rows, "fig6_noise", 0.0, ours)
            lines.append(f"| `{ours}` | " + " | ".join(breakdown_texts(ours)) +
                         f" | {100 * number(r['success_rate']):.0f} % | "
                         f"{significant(1e3 * number(r['position_error_median_m']))} |")
    return lines


def clean_accuracy():
    """Every tracker on the clean frames of Fig. 6 (0.6 m, σ² = 0, tilt 0-40°)."""
    rows = read_paper_summary()
    lines = ["| tracker | success (95 % interval) | median camera-centre error, mm (95 % interval) "
             "| p90, mm | median rotation error, ° |",
             "|---|---|---|---|---|"]
    for tracker in TRACKERS:
        (r,) = cell(rows, "fig6_noise", 0.0, tracker)
        lines.append(
            f"| `{tracker}` | {100 * number(r['success_rate']):.0f} % "
            f"({100 * number(r['success_rate_lo']):.0f}–{100 * number(r['success_rate_hi']):.0f}) | "
            f"{significant(1e3 * number(r['position_error_median_m']))} "
            f"({significant(1e3 * number(r['position_error_median_lo_m']))}–"
            f"{significant(1e3 * number(r['position_error_median_hi_m']))}) | "
            f"{significant(1e3 * number(r['position_error_p90_m']))} | "
            f"{significant(number(r['rotation_error_median_deg']))} |")
    return lines


# (what, a pattern of results/speed.md whose group 1 is the median): each must match once.
SPEED = [
    ("render a grey tag36h11 frame (blur σ = 2, noise)",
     r"\(`BM_RenderTag36h11Grey`\) \| [^|]* \| ([^|]+?) \|"),
    ("render an RGB `circles_a` frame", r"\(`BM_RenderCirclesAColour`\) \| [^|]* \| ([^|]+?) \|"),
    ("`circle`, full detection, analytic pose and refinement on the pixels",
     r"\(`BM_CircleFullDetection`\) \| [^|]* \| ([0-9.]+ ms)"),
    ("`circle`, the same on the edge points alone (`photometric: false`)",
     r"\(`BM_CircleFullDetectionEdgesOnly`\) \| [^|]* \| ([0-9.]+ ms)"),
    ("`circle`, tracking mode (the next frame of a hand-held video)",
     r"\(`BM_CircleTrackingMode`\) \| [^|]* \| ([0-9.]+ ms)"),
    ("`circle`, tracking mode on a steady glide (fitted straight from the prediction)",
     r"\(`BM_CircleTrackingModeSteady`\) \|[^|]*\| ([0-9.]+ ms)"),
    ("`apriltag` (the same frames, run alongside `circle`)",
     r"\| `apriltag` on the same poses[^|]*\|[^|]*\| *([^|]+?) *\|"),
    ("`apriltag-ippe` (the same frames)", r"\| `apriltag-ippe` \| +\| ([^|]+?) \|"),
    ("`artkplus`", r"`BM_ArtkPlusRobustPlanarPose`\) \| ([^|]+?) \|"),
    ("`runetag-improved`", r"\*\*([0-9.]+ ms) per frame\*\*"),
    ("`aruco`", r"\| `aruco` \(OpenCV[^|]*\| ([^|]+?) \|"),
]


def speed():
    text = (ROOT / "results/speed.md").read_text()
    lines = ["| one thread, 640x480, 0.6 m, σ² = 0.02 | median per frame |", "|---|---|"]
    for what, pattern in SPEED:
        found = re.findall(pattern, text)
        if len(found) != 1:
            raise SystemExit(f"readme_figures: results/speed.md: {len(found)} matches for {what}")
        lines.append(f"| {what} | {found[0].strip()} |")
    return lines


PAPER_SCENARIOS = ["fig6_noise", "fig7_blur", "fig8_distance"]


def paper_sweep_times():
    """Wall time per paper sweep (the "Ran ..." line of results/paper/report.md), then each
    tracker's median time per call: the smallest and largest over the sweep's values."""
    report = (ROOT / "results/paper/report.md").read_text()
    lines = ["| scenario | frames | wall time | frames/s |", "|---|---|---|---|"]
    for scenario in PAPER_SCENARIOS:
        found = re.findall(rf"`scenarios/paper/{scenario}\.yaml`.*? Ran (\d+) frames in ([^ ]+) "
                           rf"\(([0-9.]+) frames/s", report)
        if len(found) != 1:
            raise SystemExit(f"readme_figures: results/paper/report.md: no run line for {scenario}")
        frames, wall, rate = found[0]
        lines.append(f"| `{scenario}` | {int(frames):,} | {wall} | {rate} |")
    rows = read_paper_summary()
    lines += ["", "| tracker (median ms per call) | " + " | ".join(PAPER_SCENARIOS) + " |",
              "|---" * (len(PAPER_SCENARIOS) + 1) + "|"]
    trackers = list(dict.fromkeys(r["tracker"] for r in rows))
    for tracker in trackers:
        ranges = []
        for scenario in PAPER_SCENARIOS:
            times = [number(r["time_median_ms"]) for r in rows
                     if r["scenario"] == scenario and r["tracker"] == tracker]
            low, high = significant(min(times), 2), significant(max(times), 2)
            ranges.append(low if low == high else f"{low}-{high}")
        lines.append(f"| `{tracker}` | " + " | ".join(ranges) + " |")
    return lines


CIRCLE_MARKERS = ["circles_a", "circle_d", "circle_e", "circle_f"]
CIRCLE_MARKER_CELLS = [
    ("fig6_noise", 0.02, "0.6 m, σ² = 0.02"),
    ("fig6_noise", 0.2, "0.6 m, σ² = 0.2"),
    ("fig7_blur", 0.0, "1 m, no blur"),
    ("fig7_blur", 2.0, "1 m, blur σ = 2"),
    ("fig8_distance", 1.5, "1.5 m, σ² = 0.02"),
    ("fig8_distance", 2.5, "2.5 m, σ² = 0.02"),
]


def circle_marker_series():
    """The circle tracker's rows of the paper runs per marker, keyed by (scenario, value), and
    the cells where circle_d is found in 95 % of the frames."""
    rows = [r for r in read_summary("results/paper/summary.csv") if r["tracker"] == "circle"]
    series = {m: {(r["scenario"], number(r["sweep_value"])): r for r in rows if r["marker"] == m}
              for m in CIRCLE_MARKERS}
    good = [k for k, r in series["circle_d"].items() if number(r["success_rate"]) >= 0.95]
    return series, good


def over_circle_d(series, good, marker):
    """In the cells `good`: how many find `marker` in 95 % of the frames, and its median error
    over circle_d's per cell."""
    kept = sum(number(series[marker][k]["success_rate"]) >= 0.95 for k in good)
    ratios = {k: number(series[marker][k]["position_error_median_m"]) /
              number(series["circle_d"][k]["position_error_median_m"]) for k in good}
    return kept, ratios


def median(values):
    ordered = sorted(values)
    middle = len(ordered) // 2
    return ordered[middle] if len(ordered) % 2 else 0.5 * (ordered[middle - 1] + ordered[middle])


def circle_markers():
    """The circle tracker on markers a, d, e and f of the paper runs (issue 22): breakdowns,
    the cells where d is found in 95 % of frames and how e and f do there, and some cells."""
    series, good = circle_marker_series()
    lines = ["| marker | " + " | ".join(f"breakdown: {label}" for _, label in BREAKDOWN_SWEEPS) +
             f" | success ≥ 95 % where `circle_d`'s is ({len(good)} cells) "
             "| median error over `circle_d`'s there: median, largest |",
             "|---|" + "---|" * (len(BREAKDOWN_SWEEPS) + 2)]
    for marker in CIRCLE_MARKERS:
        texts = breakdown_texts("circle", marker)
        kept, ratios = over_circle_d(series, good, marker)
        lines.append(f"| `{marker}` | " + " | ".join(texts) + f" | {kept} | "
                     f"{significant(median(ratios.values()))}, "
                     f"{significant(max(ratios.values()))} |")
    lines += ["", "| cell | " + " | ".join(f"`{m}`: success, median mm, ours / bound"
                                           for m in CIRCLE_MARKERS) + " |",
              "|---|" + "---|" * len(CIRCLE_MARKERS)]
    for scenario, value, name in CIRCLE_MARKER_CELLS:
        texts = []
        for marker in CIRCLE_MARKERS:
            r = series[marker][(scenario, value)]
            texts.append(f"{100 * number(r['success_rate']):.0f} %, "
                         f"{significant(1e3 * number(r['position_error_median_m']))}, "
                         f"{significant(number(r['efficiency']))}")
        lines.append(f"| {name} | " + " | ".join(texts) + " |")
    return lines


def median_interval(row, figure, unit, scale=1.0):
    """" (lo–hi)": the 95 % interval of a median in a summary row (columns FIGURE_lo_UNIT and
    FIGURE_hi_UNIT), times `scale`; nothing where it has none."""
    lo, hi = row[f"{figure}_lo_{unit}"], row[f"{figure}_hi_{unit}"]
    return f" ({significant(scale * number(lo))}–{significant(scale * number(hi))})" if lo else ""


def sequences():
    """Tracking over time (issue 22): per sequence scenario, sweep value, marker and tracker of
    results/sequences/sequence_summary.csv."""
    lines = ["| video | marker: tracker | lost (95 % interval) | ATE, mm: median (95 % interval) "
             "| RPE over 1 s, mm | jitter, mm | re-acquire, s (never) "
             "| ms tracking / detection: median (95 % interval) |",
             "|---|---|---|---|---|---|---|---|"]
    for r in read_summary("results/sequences/sequence_summary.csv"):
        visible = int(r["visible"])
        lost = 100 * int(r["lost"]) / visible if visible else math.nan
        reacquire = (f"{significant(number(r['reacquire_median_s']))} ({r['never_reacquired']})"
                     if int(r["occlusions"]) else "-")
        video = f"{r['scenario']}, {r['sweep_parameter']} {r['sweep_value']}"
        lines.append(
            f"| {video} | `{r['marker']}`: `{r['tracker']}` | {lost:.1f} % "
            f"({100 * number(r['lost_rate_lo']):.1f}–{100 * number(r['lost_rate_hi']):.1f}) | "
            f"{significant(1e3 * number(r['ate_median_m']))}"
            f"{median_interval(r, 'ate_median', 'm', 1e3)} | "
            f"{significant(1e3 * number(r['rpe_median_m']))} | "
            f"{significant(1e3 * number(r['jitter_median_m']))} | {reacquire} | "
            f"{significant(number(r['tracking_median_ms']))}"
            f"{median_interval(r, 'tracking_median', 'ms')} / "
            f"{significant(number(r['detection_median_ms']))}"
            f"{median_interval(r, 'detection_median', 'ms')} |")
    return lines


def independent_render():
    """The circle tracker on the frames of scenarios/independent/ from both renderers
    (scripts/independent_render.py): success and median error, markerbench's / the other's."""
    ours = read_summary("results/independent/ours/summary.csv")
    other = {(r["scenario"], r["sweep_value"], r["marker"]): r
             for r in read_summary("results/independent/independent/summary.csv")}
    labels = {"noise_var": "σ² = {}, 0.6 m", "blur_sigma_px": "blur σ = {} px, 1 m",
              "distance_m": "{} m, σ² = 0.02"}
    lines = ["| frames | marker | success: markerbench / other renderer | median error, mm: "
             "markerbench / other renderer |", "|---|---|---|---|"]
    for r in ours:
        o = other[(r["scenario"], r["sweep_value"], r["marker"])]
        errors = " / ".join(significant(1e3 * number(x["position_error_median_m"]))
                            if number(x["success_rate"]) > 0 else "-" for x in (r, o))
        lines.append(f"| {labels[r['sweep_parameter']].format(r['sweep_value'])} | "
                     f"`{r['marker']}` | {100 * number(r['success_rate']):.0f} / "
                     f"{100 * number(o['success_rate']):.0f} % | {errors} |")
    return lines


def camera_response_row(scenario, gamma, tracker, marker):
    return summary_row("results/camera_response/summary.csv", scenario, gamma, tracker, marker)


def camera_response():
    """Every tracker of the paper runs on frames written with a gamma (results/camera_response):
    success and median error over the bound, linear frames, gamma 2.2 untold and told."""
    rows = read_summary("results/camera_response/summary.csv")
    def at(scenario, value, tracker, marker):
        row = camera_response_row(scenario, value, tracker, marker)
        return (f"{100 * number(row['success_rate']):.0f} %, "
                f"{significant(number(row['efficiency']))}")
    lines = ["| tracker: marker | linear frames | gamma 2.2, untold | gamma 2.2, told "
             "(`linear_input`) |", "|---|---|---|---|"]
    pairs = dict.fromkeys((r["tracker"], r["marker"]) for r in rows)
    for tracker, marker in pairs:
        lines.append(f"| `{tracker}`: `{marker}` | {at('camera_gamma', 1.0, tracker, marker)} | "
                     f"{at('camera_gamma', 2.2, tracker, marker)} | "
                     f"{at('camera_gamma_linear_input', 2.2, tracker, marker)} |")
    return lines


def percent(rate):
    return f"{100 * rate:.0f}"


def rounded(value, digits):
    """A number of 100 or more to `digits` significant digits, in thousands with commas (280,
    1,350)."""
    return f"{float(f'{value:.{digits}g}'):,.0f}"


def paper_row(scenario, value, tracker, marker):
    return summary_row("results/paper/summary.csv", scenario, value, tracker, marker)


def camera_response_phrases():
    """An untold gamma against linear frames: circles_a's error over the bound, the success of
    artkplus, circle_f, runetag and aruco."""
    def untold(gamma, tracker, marker):
        return camera_response_row("camera_gamma", gamma, tracker, marker)

    def told(gamma, tracker, marker):
        return camera_response_row("camera_gamma_linear_input", gamma, tracker, marker)

    circle = [untold(g, "circle", "circles_a")["efficiency"] for g in (1.0, 2.2)]
    f = [percent(number(untold(g, "circle", "circle_f")["success_rate"])) for g in (1.8, 2.2, 2.6)]
    untold_rates = [percent(number(untold(2.2, t, t)["success_rate"]))
                    for t in ("runetag", "aruco")]
    told_rates = [percent(number(told(2.2, t, t)["success_rate"])) for t in ("runetag", "aruco")]
    # The trackers that locate edges (not the dots of RUNETag, nor ArUco's thresholded squares).
    pairs = dict.fromkeys((r["tracker"], r["marker"])
                          for r in read_summary("results/camera_response/summary.csv")
                          if not r["tracker"].startswith(("runetag", "aruco")))
    growth = [number(untold(2.2, t, m)["efficiency"]) / number(untold(1.0, t, m)["efficiency"])
              for t, m in pairs]
    return [
        ("the errors of the trackers that locate edges grow {}-{} times",
         [f"{min(growth):.1f}", f"{max(growth):.1f}"]),
        ("(`circle` on `circles_a` {} → {}× the bound; `artkplus` finds {} % at 2.2)",
         [f"{number(e):.2f}" for e in circle] +
         [percent(number(untold(2.2, "artkplus", "artkplus")["success_rate"]))]),
        ("f is found untold on {} % at 1.8 and {} % at 2.2", f[:2]),
        ("but on {} % at 2.6, where the detector finds no ellipse", f[2:]),
        ("find more frames untold ({} % and {} % against {} % and {} % told)",
         untold_rates + told_rates),
    ]


def paper_phrases():
    """The circle tracker at the ends of the paper sweeps, and every tracker without noise,
    against the bound (results/paper/summary.csv)."""
    def circle(scenario, value, marker="circles_a"):
        return paper_row(scenario, value, "circle", marker)

    def noise_free(tracker, marker):
        return number(paper_row("fig6_noise", 0.0, tracker, marker)["efficiency"])

    others = [noise_free(t, m) for t, m in (("apriltag", "apriltag"), ("apriltag-ippe", "apriltag"),
                                            ("runetag", "runetag"), ("aruco", "aruco"))]
    blur5, blur10 = circle("fig7_blur", 5.0), circle("fig7_blur", 10.0)
    far, apriltag_far = circle("fig8_distance", 3.5), paper_row("fig8_distance", 3.5, "apriltag",
                                                               "apriltag")
    # Success with the better of the circle markers' hypotheses (the oracle's).
    best = ("best_success_rate", "best_success_rate_lo", "best_success_rate_hi")
    f_near, f_far = (circle("fig8_distance", d, "circle_f") for d in (2.5, 3.5))
    f_blur = circle("fig7_blur", 4.0, "circle_f")
    e_far, d_far = (circle("fig8_distance", 3.5, m) for m in ("circle_e", "circle_d"))
    return [
        ("(success {} % at σ = 10, {} % at 3.5 m;",
         [percent(number(blur10["success_rate"])), percent(number(far["success_rate"]))]),
        ("the circle tracker is {}× above its bound on `circles_a` and {}× on `circle_d`",
         [f"{noise_free('circle', m):.2f}" for m in ("circles_a", "circle_d")]),
        ("{}× and {}× on e and f (their fits', not the bound's: below), `artkplus-improved` {}×, "
         "`runetag-improved` {}×, the others {}-{}× (`artkplus` {}×)",
         [f"{noise_free('circle', m):.1f}" for m in ("circle_e", "circle_f")] +
         [f"{noise_free('artkplus-improved', 'artkplus'):.0f}",
          f"{noise_free('runetag-improved', 'runetag'):.0f}",
          rounded(min(others), 2), rounded(max(others), 2),
          rounded(noise_free("artkplus", "artkplus"), 3)]),
        ("circle tracker finds {} % at blur σ = 5 and {} % at σ = 10 where the frames allow {} % "
         "and {} %, and {} % at 3.5 m where they allow {} %",
         [percent(number(r["success_rate"])) for r in (blur5, blur10)] +
         [percent(number(r["success_at_bound"])) for r in (blur5, blur10)] +
         [percent(number(far["success_rate"])), percent(number(far["success_at_bound"]))]),
        ("AprilTag reaches {} % at 3.5 m of the same {} %",
         [percent(number(apriltag_far["success_rate"])),
          percent(number(apriltag_far["success_at_bound"]))]),
        ("the right pose is among those returned for f on {} % ({}-{}) of the frames at 2.5 m and "
         "{} % ({}-{}) at 3.5 m, against the first hypothesis's {} % and {} %, and at blur σ 4 on "
         "{} % against {} %; for e at 3.5 m on {} % against {} %, for `circle_d` at 3.5 m on {} % "
         "against {} %",
         [percent(number(f_near[key])) for key in best] +
         [percent(number(f_far[key])) for key in best] +
         [percent(number(r["success_rate"])) for r in (f_near, f_far)] +
         [percent(number(f_blur[key])) for key in ("best_success_rate", "success_rate")] +
         [percent(number(e_far[key])) for key in ("best_success_rate", "success_rate")] +
         [percent(number(d_far[key])) for key in ("best_success_rate", "success_rate")]),
    ]


def circle_accuracy_phrases():
    """What the 1 m blur σ = 10 and 3.5 m rows of results/circle_accuracy allow and leave, and
    what a colour camera's JPEG costs circles_a and circle_d."""
    rows = read_summary("results/circle_accuracy/summary.csv")
    (blur,) = cell(rows, "circle_accuracy_1m_blur10", 10.0, "circle")
    (far,) = cell(rows, "circle_accuracy_3.5m", 3.5, "circle")
    allowed = [100 * number(r["success_at_bound"]) for r in (blur, far)]
    found = [100 * number(r["success_rate"]) for r in (blur, far)]

    def shown(marker, jpeg_quality):
        (r,) = cell(rows, "circle_accuracy_0.6m_jpeg", jpeg_quality, "circle", marker)
        return [significant(1e3 * number(r["position_error_median_m"])),
                f"{number(r['efficiency']):.2f}"]

    return [
        ("what the frames allow one, is {} % and {} %", [f"{a:.0f}" for a in allowed]),
        ("the tracker's {} % and {} % leave {} and {} points to gain",
         [f"{s:.0f}" for s in found] + [f"{a - s:.0f}" for a, s in zip(allowed, found)]),
        ("`circles_a` {} mm ({}× its bound) without JPEG, {} mm ({}×) at quality 95 and {} mm "
         "({}×) at 75; `circle_d` {} mm ({}×), {} mm ({}×) and {} mm ({}×)",
         [x for marker in ("circles_a", "circle_d") for quality in (0.0, 95.0, 75.0)
          for x in shown(marker, quality)]),
    ]


def circle_marker_phrases():
    """Issue 22's goals for e and f where circle_d is found in 95 % of the frames: found as
    often, and the median error within 1.5× circle_d's (the medians of those ratios, and without
    noise)."""
    series, good = circle_marker_series()
    texts = {}
    for marker in ("circle_e", "circle_f"):
        kept, ratios = over_circle_d(series, good, marker)
        within = sum(ratio <= 1.5 for ratio in ratios.values())
        texts[marker] = [kept, within, f"{median(ratios.values()):.2f}",
                         f"{ratios[('fig6_noise', 0.0)]:.2f}"]
    e, f = texts["circle_e"], texts["circle_f"]

    def rates(marker, scenario, values, column="success_rate"):
        return [percent(number(series[marker][(scenario, v)][column])) for v in values]

    def bound_ratios(marker, values):
        return [number(series[marker][("fig8_distance", v)]["efficiency"]) for v in values]

    far = [2.5, 2.75, 3.0, 3.25, 3.5]
    found_far = [number(series["circle_d"][("fig8_distance", v)]["detection_rate"]) for v in far]
    f_far = bound_ratios("circle_f", far)
    noise_free = [number(series[m][("fig6_noise", 0.0)]["efficiency"])
                  for m in ("circle_e", "circle_f", "circle_d")]
    return [
        ("Without noise e and f are {}× and {}× their bounds (d {}×;",
         [f"{noise_free[0]:.1f}", f"{noise_free[1]:.1f}", f"{noise_free[2]:.2f}"]),
        ("d's success there is {}/{}/{} % at σ 4/5/6 against the bound's {}/{}/{} %",
         rates("circle_d", "fig7_blur", [4.0, 5.0, 6.0]) +
         rates("circle_d", "fig7_blur", [4.0, 5.0, 6.0], "success_at_bound")),
        ("at σ 7-10, {}/{}/{}/{} %", rates("circle_d", "fig7_blur", [7.0, 8.0, 9.0, 10.0])),
        ("At σ 7, where d is found on {} % of the frames, its median error is {}× the bound",
         rates("circle_d", "fig7_blur", [7.0], "detection_rate") +
         [f"{number(series['circle_d'][('fig7_blur', 7.0)]['efficiency']):.2f}"]),
        ("d is now found on {}-{} % of the frames at 2.5-3.5 m",
         [percent(min(found_far)), percent(max(found_far))]),
        ("and succeeds on {}/{}/{}/{}/{} % where `success_at_bound` says {}/{}/{}/{}/{} %; e on "
         "{}/{}/{}/{}/{} %",
         rates("circle_d", "fig8_distance", far) +
         rates("circle_d", "fig8_distance", far, "success_at_bound") +
         rates("circle_e", "fig8_distance", far)),
        ("(d at 3.25 and 3.5 m {}× and {}×, e at 3 and 3.5 m {}× and {}×, f from 2.5 m {}-{}×)",
         [f"{x:.2f}" for x in bound_ratios("circle_d", [3.25, 3.5]) +
          bound_ratios("circle_e", [3.0, 3.5]) + [min(f_far), max(f_far)]]),
        ("`circles_a`'s two disks fix its tilt better, and it meets both ({} % and {} %)",
         rates("circles_a", "fig8_distance", [2.5, 3.5])),
        ("`circle_e` meets issue 22's success goal in {} of the {} cells",
         [str(e[0]), str(len(good))]),
        ("its error goal in {} (median error {}× `circle_d`'s, within 1.5× but without noise, {}×",
         [str(e[1]), e[2], e[3]]),
        ("`circle_f` meets the error goal in {} of the {} cells ({}×; without noise {}×) and the "
         "success goal in {}", [str(f[1]), str(len(good)), f[2], f[3], str(f[0])]),
    ]


def sequence_phrases():
    """What the videos show (results/sequences/sequence_summary.csv): the circle tracker's ATE
    against AprilTag's and ARToolKitPlus's, its tracking mode's time, the rolling shutter, and
    the frames ARToolKitPlus and ArUco lose."""
    rows = {(r["scenario"], number(r["sweep_value"]), r["tracker"]): r
            for r in read_summary("results/sequences/sequence_summary.csv")
            if not r["scenario"].startswith("recede")}  # the circle markers alone: below

    def figure(scenario, value, tracker, column):
        return number(rows[(scenario, value, tracker)][column])

    def lost(scenario, value, tracker):
        return percent(figure(scenario, value, tracker, "lost") /
                       figure(scenario, value, tracker, "visible"))

    noisy = [("orbit", 0.02), ("orbit", 0.1), ("handheld", 0.02)]

    def ate_over_circle(tracker, videos):
        return [figure(s, v, tracker, "ate_median_m") / figure(s, v, "circle", "ate_median_m")
                for s, v in videos]

    apriltag, artkplus = ate_over_circle("apriltag", noisy), ate_over_circle("artkplus", noisy)
    still = [ate_over_circle(t, [("orbit", 0.0)])[0] for t in ("apriltag", "artkplus")]
    saved = [1.0 - figure(s, v, "circle", "tracking_median_ms") /
             figure(s, v, "circle", "detection_median_ms")
             for s, v in {(r[0], r[1]) for r in rows}]
    shake = [1.0 - figure(s, 0.02, "circle", "tracking_median_ms") /
             figure(s, 0.02, "circle", "detection_median_ms")
             for s in ("handheld", "handheld_rolling_shutter")]

    def ms(scenario, value, column):
        return f"{figure(scenario, value, 'circle', column):.2f}"

    def ate_mm(scenario, tracker):
        return significant(1e3 * figure(scenario, 0.02, tracker, "ate_median_m"))

    return [
        ("({}-{}× below AprilTag's and {}-{}× below ARToolKitPlus's under noise; without noise, "
         "on the orbit, {}× and {}×)",
         [f"{min(apriltag):.1f}", f"{max(apriltag):.1f}", f"{min(artkplus):.1f}",
          significant(max(artkplus), 2), rounded(still[0], 2), rounded(still[1], 2)]),
        ("takes {}-{} % less time than full detection", [percent(min(saved)), percent(max(saved))]),
        ("({} against {} ms on the orbit at σ² 0.02, {} against {} on the approach",
         [ms("orbit", 0.02, "tracking_median_ms"), ms("orbit", 0.02, "detection_median_ms"),
          ms("approach", 0.02, "tracking_median_ms"), ms("approach", 0.02, "detection_median_ms")]),
        ("{}-{} % on the hand-held shake", [f"{100 * min(shake):.1f}", f"{100 * max(shake):.1f}"]),
        ("tracker (from {} to {} mm), AprilTag ({} to {}) and ARToolKitPlus ({} to {})",
         [ate_mm(s, t) for t in ("circle", "apriltag", "artkplus")
          for s in ("handheld", "handheld_rolling_shutter")]),
        ("ARToolKitPlus loses {} % of the approach's frames", [lost("approach", 0.02, "artkplus")]),
        ("loses none of the orbit's frames without noise but {} % at σ² 0.02 and {} % at 0.1",
         [lost("orbit", 0.02, "aruco"), lost("orbit", 0.1, "aruco")]),
    ] + recede_phrases()


def recede_phrases():
    """The circle markers receding, tracked against each frame alone, beyond 2.5 m
    (results/sequences/recede_pairs.csv)."""
    pairs = {r["marker"]: r for r in read_summary("results/sequences/recede_pairs.csv")}
    markers = ("circle_f", "circle_e", "circle_d", "circles_a")
    worst_p = max(number(pairs[m]["mcnemar_p"]) for m in markers)
    return [
        ("its first hypothesis succeeds on {} % of f's frames against {} % each frame alone, on "
         "{} % against {} % of e's, {} % against {} % of `circle_d`'s and {} % against {} % of "
         "`circles_a`'s (McNemar on the frames: p below 1e-{} for each",
         [percent(number(pairs[m][c])) for m in markers for c in ("success_a", "success_b")] +
         [str(-math.ceil(math.log10(worst_p)))]),
        ("tracking mode is better on {}, {}, {} and {} of the {} videos and worse on {}, {}, {} "
         "and {}",
         [pairs[m]["videos_a_better"] for m in markers] + [pairs[markers[0]]["videos"]] +
         [pairs[m]["videos_b_better"] for m in markers]),
    ]


# results/speed.md's latest ratios of the circle tracker to apriltag: the table after this line.
SPEED_RATIOS_FROM = "The latest paired times beside `apriltag`"


def speed_phrases():
    """The circle tracker's time over apriltag's in the same runs (the median and its interval,
    the latest table of results/speed.md), and the fit's share of full detection's
    instructions (the last table of shares; a change outside full detection's path adds none)."""
    text = (ROOT / "results/speed.md").read_text()
    if text.count(SPEED_RATIOS_FROM) != 1:
        raise SystemExit(f"readme_figures: results/speed.md: '{SPEED_RATIOS_FROM}' not once")
    after = text[text.index(SPEED_RATIOS_FROM):]
    figures = []
    for benchmark in ("BM_CircleFullDetection", "BM_CircleTrackingMode",
                      "BM_CircleTrackingModeHandheld", "BM_CircleTrackingModeSteady"):
        found = re.search(rf"\| `{benchmark}` \| [0-9.]+ \| ([0-9.]+) \| ([0-9.]+)-([0-9.]+) \|",
                          after)
        if not found:
            raise SystemExit(f"readme_figures: results/speed.md: no ratio of {benchmark}")
        figures += [f"{float(x):.2f}" for x in found.groups()]
    share = re.findall(r"\| the fit on the pixels \| [0-9.]+ \| ([0-9.]+) %", text)
    if not share:
        raise SystemExit("readme_figures: results/speed.md: no table of the fit's share")
    return [
        ("full detection {}× `apriltag`'s time ({}-{}), tracking mode {}× ({}-{}) after a frame "
         "with no history and {}× ({}-{}) in a hand-held shake, and {}× ({}-{}) on a steady glide",
         figures),
        ("the fit on the pixels is {} % of full detection's", [f"{float(share[-1]):.0f}"]),
    ]


PHRASES = {"speed": speed_phrases, "circle_accuracy": circle_accuracy_phrases,
           "camera_response": camera_response_phrases, "paper": paper_phrases,
           "circle_markers": circle_marker_phrases, "sequences": sequence_phrases}
# A number in a phrase: digits, with separators inside (1,350 and 0.125, not a sentence's end).
PHRASE_NUMBER = r"([0-9]+(?:[.,][0-9]+)*)"


def phrase_pattern(phrase):
    """A phrase's regular expression: its numbers captured, any run of its spaces matching any
    run of white space (a line break in the README)."""
    return re.compile(PHRASE_NUMBER.join(
        r"\s+".join(re.escape(word) for word in re.split(r"\s+", piece))
        for piece in phrase.split("{}")))


def phrase_count():
    return sum(len(phrases()) for phrases in PHRASES.values())


def check_phrases(text, problems, phrases=None):
    """Each phrase of `phrases` (PHRASES') found once in `text` with its numbers from results/:
    the text with the numbers rewritten, and what differed added to `problems`."""
    for name, listed in (phrases or PHRASES).items():
        for phrase, values in listed():
            matches = list(phrase_pattern(phrase).finditer(text))
            if len(matches) != 1:
                problems.append(f"README.md: phrase '{phrase}' ({name}) found {len(matches)} "
                                f"times, not once")
                continue
            match = matches[0]
            shown = list(match.groups())
            if shown != values:
                problems.append(f"README.md: phrase '{phrase}' ({name}) shows {shown}, results/ "
                                f"give {values}")
                for k in reversed(range(len(values))):
                    text = text[:match.start(k + 1)] + values[k] + text[match.end(k + 1):]
    return text


TABLES = {"circle_accuracy": circle_accuracy, "circle_markers": circle_markers, "efficiency": efficiency,
          "breakdowns": breakdowns, "baselines": baselines, "clean_accuracy": clean_accuracy,
          "speed": speed, "paper_sweep_times": paper_sweep_times, "sequences": sequences,
          "independent_render": independent_render, "camera_response": camera_response}
# The documents and the tables each holds.
DOCUMENTS = {"README.md": [t for t in TABLES if t != "paper_sweep_times"],
             "results/circle_accuracy.md": ["circle_accuracy"],
             "results/speed.md": ["paper_sweep_times"]}


def main():
    if len(sys.argv) != 2 or sys.argv[1] not in ("--check", "--write"):
        sys.exit(__doc__)
    problems = []
    count = 0
    for document, names in DOCUMENTS.items():
        path = ROOT / document
        text = path.read_text()
        if document == "README.md":
            text = check_phrases(text, problems)
        for name in names:
            count += 1
            pattern = re.compile(
                rf"(<!-- readme_figures.py: {name} -->\n)(.*?)(<!-- end {name} -->)", re.S)
            match = pattern.search(text)
            if not match:
                problems.append(f"{document}: no table '{name}' (<!-- readme_figures.py: {name} -->)")
                continue
            table = "\n".join(TABLES[name]()) + "\n"
            if match.group(2) != table:
                problems.append(f"{document}: table '{name}' differs from results/:\n{table}")
                text = text[:match.start(2)] + table + text[match.end(2):]
        if sys.argv[1] == "--write":
            path.write_text(text)
    if sys.argv[1] == "--write":
        print(f"readme_figures: wrote {count} tables and {phrase_count()} phrases")
        return
    if problems:
        sys.exit("\n".join(problems) + "\nRun scripts/readme_figures.py --write after new results.")
    print(f"readme_figures: {count} tables and {phrase_count()} phrases match results/")


if __name__ == "__main__":
    main()
