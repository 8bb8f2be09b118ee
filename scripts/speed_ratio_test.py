#!/usr/bin/env python3
"""Tests of speed_ratio.py against fake benchmark programs: each prints Google Benchmark's JSON
with the next of its listed times and logs its invocation, so that the ratios, their interval,
the order of the runs and the errors are known exactly."""
import contextlib
import io
import json
import math
import pathlib
import stat
import sys
import tempfile
import unittest

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import speed_ratio  # noqa: E402

# A benchmark program: answers --benchmark_filter=^NAME$ for its one benchmark with the next
# time of times.json (ms), appending NAME to the shared invocations log.
FAKE = """#!/usr/bin/env python3
import json, pathlib, re, sys
here = pathlib.Path(__file__).parent
config = json.loads((here / (pathlib.Path(__file__).name + ".json")).read_text())
pattern = next(a for a in sys.argv if a.startswith("--benchmark_filter="))
pattern = pattern.split("=", 1)[1]
names = [config["name"]] if re.search(pattern, config["name"]) else []
count_file = here / (pathlib.Path(__file__).name + ".count")
count = int(count_file.read_text()) if count_file.exists() else 0
count_file.write_text(str(count + 1))
with open(here / "invocations.log", "a") as log:
    log.write(config["name"] + "\\n")
run = {"name": config["name"], "run_type": "iteration", "time_unit": "us",
       "real_time": 1e3 * config["times_ms"][count % len(config["times_ms"])]}
if config.get("error"):
    run.update(error_occurred=True, error_message=config["error"])
print(json.dumps({"benchmarks": [run] if names else []}))
"""


class SpeedRatioTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = pathlib.Path(self.tmp.name)

    def tearDown(self):
        self.tmp.cleanup()

    def fake(self, program, name, times_ms, error=None):
        path = self.dir / program
        path.write_text(FAKE)
        path.chmod(path.stat().st_mode | stat.S_IXUSR)
        (self.dir / (program + ".json")).write_text(
            json.dumps({"name": name, "times_ms": times_ms, "error": error}))
        return f"{path}:{name}"

    def run_main(self, *args, cpuinfo="/proc/cpuinfo"):
        out, err = io.StringIO(), io.StringIO()
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            status = speed_ratio.main(list(args), cpuinfo=cpuinfo)
        return status, out.getvalue(), err.getvalue()

    def table_row(self, output, benchmark):
        row = next(line for line in output.splitlines() if line.startswith(f"| `{benchmark}`"))
        return [cell.strip() for cell in row.strip("|").split("|")]

    def test_ratio_of_steady_times_is_exact(self):
        reference = self.fake("ref", "BM_Ref", [4.0])
        measured = self.fake("fast", "BM_Fast/2", [1.0])
        status, out, _ = self.run_main("--reference", reference, "--measure", measured,
                                       "--runs", "8", "--min-time", "0.01")
        self.assertEqual(status, 0)
        self.assertEqual(self.table_row(out, "BM_Fast/2"), ["`BM_Fast/2`", "1.000", "0.250",
                                                            "0.250-0.250"])

    def test_ratios_are_paired_run_by_run(self):
        # The reference and the measured drift together (a VM): paired, the ratio stays 0.5,
        # though the measured time alone ranges over 4x.
        drift = [1.0, 2.0, 4.0, 1.5, 3.0, 2.5, 1.2, 3.5]
        reference = self.fake("ref", "BM_Ref", [2.0 * d for d in drift])
        measured = self.fake("half", "BM_Half", drift)
        # The order rotates, so each program's invocations are its runs in order.
        status, out, _ = self.run_main("--reference", reference, "--measure", measured,
                                       "--runs", "8", "--min-time", "0.01")
        self.assertEqual(status, 0)
        self.assertEqual(self.table_row(out, "BM_Half")[2:], ["0.500", "0.500-0.500"])

    def test_interval_is_the_binomial_order_statistics(self):
        # 20 runs: P(B <= 5) = 0.021 <= 0.025 < P(B <= 6) = 0.058, so the 6th and 15th
        # smallest of the ratios.
        ratios = [0.50 + 0.01 * ((7 * i) % 20) for i in range(20)]
        reference = self.fake("ref", "BM_Ref", [2.0] * 20)
        measured = self.fake("m", "BM_M", [2.0 * r for r in ratios])
        status, out, _ = self.run_main("--reference", reference, "--measure", measured,
                                       "--runs", "20", "--min-time", "0.01")
        self.assertEqual(status, 0)
        ordered = sorted(ratios)
        expected_median = (ordered[9] + ordered[10]) / 2
        self.assertEqual(self.table_row(out, "BM_M")[2:],
                         [f"{expected_median:.3f}", f"{ordered[5]:.3f}-{ordered[14]:.3f}"])
        low_tail = sum(math.comb(20, k) for k in range(6)) / 2**20
        self.assertLessEqual(low_tail, 0.025)
        self.assertGreater(low_tail + math.comb(20, 6) / 2**20, 0.025)

    def test_order_rotates_from_run_to_run(self):
        reference = self.fake("ref", "BM_Ref", [1.0])
        first = self.fake("a", "BM_A", [1.0])
        second = self.fake("b", "BM_B", [1.0])
        status, _, _ = self.run_main("--reference", reference, "--measure", first,
                                     "--measure", second, "--runs", "6", "--min-time", "0.01")
        self.assertEqual(status, 0)
        calls = (self.dir / "invocations.log").read_text().split()
        runs = [calls[i:i + 3] for i in range(0, len(calls), 3)]
        self.assertEqual(runs, [["BM_Ref", "BM_A", "BM_B"], ["BM_A", "BM_B", "BM_Ref"],
                                ["BM_B", "BM_Ref", "BM_A"]] * 2)

    def test_the_table_names_the_machine(self):
        cpuinfo = self.dir / "cpuinfo"
        cpuinfo.write_text("processor\t: 0\nmodel name\t: AMD EPYC\nflags\t: avx2\n\n"
                           "processor\t: 1\nmodel name\t: AMD EPYC\nflags\t: avx2\n")
        reference = self.fake("ref", "BM_Ref", [1.0])
        measured = self.fake("m", "BM_M", [1.0])
        args = ["--reference", reference, "--measure", measured, "--runs", "6",
                "--min-time", "0.01"]
        status, out, _ = self.run_main(*args, cpuinfo=str(cpuinfo))
        self.assertEqual(status, 0)
        self.assertTrue(out.splitlines()[0].endswith("; on AMD EPYC, 2 CPUs"), out)
        # A file that cannot be read, or names no model: said so, not guessed.
        for unreadable in (self.dir / "absent", self.dir / "m.json"):
            status, out, _ = self.run_main(*args, cpuinfo=str(unreadable))
            self.assertEqual(status, 0)
            self.assertTrue(out.splitlines()[0].endswith("; on an unknown CPU"), out)

    def test_bad_input_exits_2_naming_the_program_and_benchmark(self):
        reference = self.fake("ref", "BM_Ref", [1.0])
        cases = [
            (["--measure", f"{self.dir / 'ref'}:BM_Missing"], "BM_Missing"),
            (["--measure", f"{self.dir / 'absent'}:BM_A"], "absent"),
            (["--measure", "no-colon"], "no-colon"),
            (["--measure", self.fake("bad", "BM_Bad", [1.0], error="no frame found")],
             "no frame found"),
            (["--measure", reference, "--runs", "5"], "--runs 5"),
        ]
        for extra, named in cases:
            with self.subTest(extra=extra):
                status, out, err = self.run_main("--reference", reference, "--min-time", "0.01",
                                                 *extra)
                self.assertEqual(status, 2)
                self.assertIn(named, err)
                self.assertEqual(out, "")


if __name__ == "__main__":
    unittest.main()
