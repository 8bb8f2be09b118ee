#!/usr/bin/env python3
"""Tests of paired_runs.py on small frames.csv files whose pairs, successes and p-values are
known exactly."""
import pathlib
import subprocess
import sys
import tempfile
import unittest

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import paired_runs  # noqa: E402

SCRIPT = pathlib.Path(__file__).resolve().parent / "paired_runs.py"
COLUMNS = "tracker,marker,trial,frame,distance_m,position_error_m"


def frames(rows):
    """frames.csv text from (trial, frame, distance, error) tuples (error None: no pose)."""
    lines = [COLUMNS]
    for trial, frame, distance, error in rows:
        lines.append(f"circle,circle_f,{trial},{frame},{distance},"
                     f"{'' if error is None else error}")
    return "\n".join(lines) + "\n"


class PairedRunsTest(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()
        self.root = pathlib.Path(self.dir.name)

    def tearDown(self):
        self.dir.cleanup()

    def write(self, scenario, rows):
        (self.root / scenario).mkdir()
        (self.root / scenario / "frames.csv").write_text(frames(rows))

    def run_script(self, *args):
        return subprocess.run([sys.executable, str(SCRIPT), str(self.root), *args],
                              capture_output=True, text=True)

    def test_counts_the_discordant_frames_and_videos(self):
        # Three videos of four frames, the first at 1 m (left out by --min-distance 2); A
        # succeeds on every far frame, B fails all of video 0's and one of video 1's (an error of
        # 0.3 m at 3 m is a success, 0.31 is not; no pose is a failure).
        a, b = [], []
        for trial in range(3):
            for frame, distance in enumerate((1.0, 2.0, 3.0, 3.0)):
                a.append((trial, frame, distance, 0.01))
                wrong = trial == 0 or (trial == 1 and frame == 3)
                b.append((trial, frame, distance,
                          (None if frame == 2 else 0.31) if wrong else 0.3 * distance / 3.0))
        b[0] = (0, 0, 1.0, 5.0)  # a near frame: not counted
        self.write("tracked", a)
        self.write("alone", b)
        (row,) = paired_runs.compare(paired_runs.read_frames(self.root / "tracked"),
                                     paired_runs.read_frames(self.root / "alone"), 2.0)
        self.assertEqual(row["frames"], 9)
        self.assertEqual(row["success_a"], 1.0)
        self.assertAlmostEqual(row["success_b"], 5 / 9)
        self.assertEqual((row["only_a"], row["only_b"]), (4, 0))
        self.assertAlmostEqual(row["mcnemar_p"], 2 / 16)  # 4 of 4 discordant: 2 × 1/16
        self.assertEqual((row["videos"], row["videos_a_better"], row["videos_b_better"]),
                         (3, 2, 0))
        self.assertAlmostEqual(row["sign_p"], 0.5)  # 2 of 2 videos: 2 × 1/4
        # The same through the command line, as CSV.
        result = self.run_script("tracked", "alone", "--min-distance", "2")
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(result.stdout.splitlines()[1],
                         "circle,circle_f,9,1,0.5556,4,0,0.125,3,2,0,0.5")

    def test_reads_compressed_frames(self):
        # `sweep --zstd` leaves frames.csv.zst: read as the plain file.
        rows = [(0, 0, 3.0, 0.01), (0, 1, 3.0, None)]
        self.write("plain", rows)
        self.write("compressed", rows)
        subprocess.run(["zstd", "-q", "--rm", str(self.root / "compressed" / "frames.csv")],
                       check=True)
        self.assertEqual(paired_runs.read_frames(self.root / "compressed"),
                         paired_runs.read_frames(self.root / "plain"))

    def test_runs_of_other_frames_are_refused(self):
        self.write("tracked", [(0, 0, 1.0, 0.01), (0, 1, 2.0, 0.01)])
        self.write("fewer", [(0, 0, 1.0, 0.01)])
        self.write("moved", [(0, 0, 1.0, 0.01), (0, 1, 2.5, 0.01)])
        for other, message in (("fewer", "do not hold the same frames"),
                               ("moved", "not the same frames"),
                               ("missing", "missing/frames.csv: no such file")):
            result = self.run_script("tracked", other)
            self.assertEqual(result.returncode, 2, other)
            self.assertIn(message, result.stderr)


if __name__ == "__main__":
    unittest.main()
