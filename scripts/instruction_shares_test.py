#!/usr/bin/env python3
"""Tests of instruction_shares.py with a fake valgrind and callgrind_annotate on the PATH: they
log their invocations and print callgrind_annotate's formats with known counts, so that the
shares, the calls and the errors are known exactly."""
import contextlib
import io
import os
import pathlib
import stat
import sys
import tempfile
import unittest

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import instruction_shares  # noqa: E402

FAKE_VALGRIND = """#!/bin/sh
echo "$@" >> "$(dirname "$0")/valgrind.log"
for a in "$@"; do
  case "$a" in --callgrind-out-file=*) echo profile > "${a#--callgrind-out-file=}";; esac
done
exit ${FAKE_STATUS:-0}
"""

# callgrind_annotate's two outputs for a Track (2 calls of 500) that runs Detect (its lambda
# inside it; listed whole and in parts by file, as with debug information), Fit twice over,
# and a helper called from both.
INCLUSIVE = """--------------------------------------------------------------------------------
Ir
--------------------------------------------------------------------------------
2,000 (100.0%)  PROGRAM TOTALS

--------------------------------------------------------------------------------
Ir                 file:function
--------------------------------------------------------------------------------
1,000 (50.00%)  ???:ns::Tracker::Track(ns::Frame const&) [/build/prog]
  600 (30.00%)  ???:ns::Fit(ns::Frame const&, double) [clone .constprop.0] [/build/prog]
  300 (15.00%)  /src/detect.cc:ns::Detect(ns::Frame const&) [/build/prog]
  280 (14.00%)  src/detect.cc:ns::Detect(ns::Frame const&) [/build/prog]
   20 ( 1.00%)  /usr/include/c++/12/bits/stl_vector.h:ns::Detect(ns::Frame const&) [/build/prog]
  120 ( 6.00%)  ???:ns::Detect(ns::Frame const&)::{lambda(int)#1}::operator()(int) const [/build/prog]
   50 ( 2.50%)  ???:std::_Function_handler<void (), ns::Detect(ns::Frame const&)::{lambda()#2}> [/build/prog]
   40 ( 2.00%)  ???:ns::Helper(int) [/lib/libx.so]
"""
TREE = """--------------------------------------------------------------------------------
Ir                 file:function
--------------------------------------------------------------------------------
1,000 (50.00%)  < ???:main (1x) [/build/prog]
1,000 (50.00%)  < ???:ns::Bench(benchmark::State&) (1x) [/build/prog]
   10 ( 0.50%)  *  ???:ns::Tracker::Track(ns::Frame const&) [/build/prog]
  600 (30.00%)  >   ???:ns::Fit(ns::Frame const&, double) [clone .constprop.0] (4x) [/build/prog]

  600 (30.00%)  < ???:ns::Tracker::Track(ns::Frame const&) (4x) [/build/prog]
   20 ( 1.00%)  *  ???:ns::Fit(ns::Frame const&, double) [clone .constprop.0] [/build/prog]
"""
# The same tree from a build with debug information: Track listed once per source file, its
# callers under the entry of its own file's full path, which counts no instruction of its own.
DEBUG_TREE = """--------------------------------------------------------------------------------
Ir                 file:function
--------------------------------------------------------------------------------
1,000 (50.00%)  < ???:ns::Bench(benchmark::State&) (2x) [/build/prog]
1,000 (50.00%)  *  /src/track.cc:ns::Tracker::Track(ns::Frame const&)

1,000 (50.00%)  *  src/track.cc:ns::Tracker::Track(ns::Frame const&) [/build/prog]
  600 (30.00%)  >   ???:ns::Fit(ns::Frame const&, double) [clone .constprop.0] (4x) [/build/prog]

  600 (30.00%)  < src/track.cc:ns::Tracker::Track(ns::Frame const&) (4x) [/build/prog]
  600 (30.00%)  *  ???:ns::Fit(ns::Frame const&, double) [clone .constprop.0] [/build/prog]
"""
# Its tree of self counts (without --inclusive=yes) leaves the entry with Track's callers out.
DEBUG_SELF_TREE = """--------------------------------------------------------------------------------
Ir                 file:function
--------------------------------------------------------------------------------
   20 ( 1.00%)  *  ???:ns::Fit(ns::Frame const&, double) [clone .constprop.0] [/build/prog]

   10 ( 0.50%)  *  src/track.cc:ns::Tracker::Track(ns::Frame const&) [/build/prog]
"""
FAKE_ANNOTATE = """#!/bin/sh
case "$*" in
  *--inclusive=yes*--tree=caller*) cat "$(dirname "$0")/tree.txt";;
  *--tree=caller*) cat "$(dirname "$0")/self_tree.txt";;
  *--inclusive=yes*) cat "$(dirname "$0")/inclusive.txt";;
esac
"""

TRACK = "ns::Tracker::Track(ns::Frame const&)"


class InstructionSharesTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = pathlib.Path(self.tmp.name)
        for name, text in [("valgrind", FAKE_VALGRIND), ("callgrind_annotate", FAKE_ANNOTATE),
                           ("prog", "#!/bin/sh\n")]:
            path = self.dir / name
            path.write_text(text)
            path.chmod(path.stat().st_mode | stat.S_IXUSR)
        (self.dir / "inclusive.txt").write_text(INCLUSIVE)
        (self.dir / "tree.txt").write_text(TREE)
        (self.dir / "self_tree.txt").write_text(DEBUG_SELF_TREE)
        self.path = os.environ["PATH"]
        os.environ["PATH"] = f"{self.dir}{os.pathsep}{self.path}"

    def tearDown(self):
        os.environ["PATH"] = self.path
        os.environ.pop("FAKE_STATUS", None)
        self.tmp.cleanup()

    def run_main(self, *stages, per=TRACK, command=None):
        args = ["--per", per]
        for stage in stages:
            args += ["--stage", stage]
        if command is None:
            command = [str(self.dir / "prog"), "--benchmark_filter=^BM_Track/2$",
                       "--benchmark_min_time=0.5"]
        out, err = io.StringIO(), io.StringIO()
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            status = instruction_shares.main(args + ["--"] + command)
        return status, out.getvalue(), err.getvalue()

    def test_shares_of_the_calls(self):
        status, out, err = self.run_main("fit=ns::Fit(", "detect=ns::Detect(", "helper=Helper")
        self.assertEqual(status, 0, err)
        # Track: 1,000 over its 2 calls (its callers' 1 + 1).
        self.assertIn(f"2 calls of `{TRACK}`, 0.001 M instructions a call", out)
        self.assertIn("| fit | `ns::Fit(ns::Frame const&, double) [clone .constprop.0]` | "
                      "0.000 | 60.0% |", out)
        # Detect's whole count, not a part's, nor its lambda's (defined inside it) nor a
        # handler of one's.
        self.assertIn("| detect | `ns::Detect(ns::Frame const&)` | 0.000 | 30.0% |", out)
        self.assertIn("| helper | `ns::Helper(int)` | 0.000 | 4.0% |", out)

    def test_counts_the_calls_of_a_build_with_debug_information(self):
        (self.dir / "tree.txt").write_text(DEBUG_TREE)
        status, out, err = self.run_main("fit=ns::Fit(")
        self.assertEqual(status, 0, err)
        self.assertIn(f"2 calls of `{TRACK}`, 0.001 M instructions a call", out)

    def test_runs_the_command_under_callgrind(self):
        self.run_main("fit=ns::Fit(")
        logged = (self.dir / "valgrind.log").read_text()
        self.assertIn("--tool=callgrind", logged)
        self.assertTrue(logged.rstrip().endswith(
            f"{self.dir / 'prog'} --benchmark_filter=^BM_Track/2$ --benchmark_min_time=0.5"))

    def test_bad_input_exits_2_naming_it(self):
        cases = [
            (("fit=ns::Nothing(",), {}, "--stage 'fit': 'ns::Nothing(': no function"),
            (("any=ns::",), {}, "--stage 'any': 'ns::': 4 functions"),
            (("fit",), {}, "--stage 'fit': expected LABEL=PATTERN"),
            (("fit=ns::Fit(",), {"per": "ns::Track("}, "--per 'ns::Track(': not called"),
            (("fit=ns::Fit(",), {"command": ["/no/such/prog"]}, "/no/such/prog: no such executable"),
            (("fit=ns::Fit(",), {"command": []}, "no command: give it after --"),
        ]
        for stages, keywords, message in cases:
            with self.subTest(message=message):
                status, out, err = self.run_main(*stages, **keywords)
                self.assertEqual(status, 2)
                self.assertIn(message, err)
                self.assertEqual(out, "")

    def test_a_failing_run_exits_2(self):
        os.environ["FAKE_STATUS"] = "3"
        status, _, err = self.run_main("fit=ns::Fit(")
        self.assertEqual(status, 2)
        self.assertIn("--benchmark_min_time=0.5 under callgrind: exit status 3", err)

    def test_without_valgrind_exits_2_saying_where_it_comes_from(self):
        (self.dir / "valgrind").unlink()
        os.environ["PATH"] = str(self.dir)
        status, _, err = self.run_main("fit=ns::Fit(")
        self.assertEqual(status, 2)
        self.assertIn("valgrind: not installed", err)


if __name__ == "__main__":
    unittest.main()
