#!/usr/bin/env python3
"""Tests of readme_figures.py's phrases: a phrase in the prose is found across line breaks, its
numbers compared with results/ and rewritten in place; a phrase not found once is named; and
every phrase of the README is wired to its results (a number changed in the README is caught)."""
import pathlib
import re
import sys
import unittest

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import readme_figures  # noqa: E402

PHRASE = "finds {} % at blur σ = 5 and {} % at σ = 10"
TEXT = "The tracker\nfinds 98 % at blur σ = 5 and\n91 % at σ = 10. Then 1,350 more.\n"


def check(text, values, phrase=PHRASE):
    problems = []
    rewritten = readme_figures.check_phrases(text, problems,
                                             {"test": lambda: [(phrase, values)]})
    return rewritten, problems


class PhraseTest(unittest.TestCase):
    def test_a_phrase_across_line_breaks_with_its_numbers_matches(self):
        rewritten, problems = check(TEXT, ["98", "91"])
        self.assertEqual(problems, [])
        self.assertEqual(rewritten, TEXT)

    def test_a_changed_number_is_named_and_rewritten_in_place(self):
        rewritten, problems = check(TEXT, ["97", "91"])
        self.assertEqual(len(problems), 1)
        self.assertIn("shows ['98', '91']", problems[0])
        self.assertIn("give ['97', '91']", problems[0])
        self.assertEqual(rewritten, TEXT.replace("98 %", "97 %"))

    def test_a_sentences_full_stop_and_thousands_separators(self):
        rewritten, problems = check(TEXT, ["92", "1,351"], "{} % at σ = 10. Then {} more")
        self.assertIn("shows ['91', '1,350']", problems[0])
        self.assertEqual(rewritten, TEXT.replace("91 %", "92 %").replace("1,350", "1,351"))

    def test_a_phrase_not_found_once_is_named(self):
        _, missing = check(TEXT, ["98"], "finds {} % at blur σ = 6")
        self.assertEqual(len(missing), 1)
        self.assertIn("found 0 times", missing[0])
        _, twice = check(TEXT + TEXT, ["98", "91"])
        self.assertIn("found 2 times", twice[0])

    def test_every_phrase_of_the_readme_is_its_results(self):
        text = readme_figures.README.read_text()
        problems = []
        self.assertEqual(readme_figures.check_phrases(text, problems), text)
        self.assertEqual(problems, [])
        # One number of a phrase changed in the README: caught, and only that phrase.
        found = re.search(r"`circles_a` ([0-9.]+) → ([0-9.]+)× the bound", text)
        self.assertIsNotNone(found)
        first, second = found.groups()
        altered = f"{float(first) + 0.01:.2f}"
        changed = text.replace(found.group(0), f"`circles_a` {altered} → {second}× the bound")
        self.assertNotEqual(changed, text)
        problems = []
        self.assertEqual(readme_figures.check_phrases(changed, problems), text)
        self.assertEqual(len(problems), 1)
        self.assertIn(f"(camera_response) shows ['{altered}', '{second}', ", problems[0])


if __name__ == "__main__":
    unittest.main()
