#!/usr/bin/python3
"""tests/scripts/claims.py on small made-up pages and data: which tokens are numbers and which are
labels, rounding at the written decimals, claims that fail when one data value changes, the
refusals (constant expressions, bad labels, ambiguous quotes), doc_claims_test's recorded
patterns mapped back through collapsed whitespace, and the ratchet of pending sections."""
import json
import re
import sys
import tempfile
import unittest
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import claims  # noqa: E402

PAGE = """# A page

Intro: the unit runs 9 717 633 cycles.

## 1. First

At L = 8 and N = 1…6 (§12) the best is 0.0480 vertices/cycle, 14 % idle, with 3x1 ×4 copies;
see `tessim sim -L 4 --int 3` and [the table](tables2.md). The two numbers 0.5 and
0.5 differ in meaning.

<!-- generated: by a script -->
| a | b |
|---|---|
| 7 | 8 |
<!-- end generated -->

## 2. Second

The best is 0.0480 again, at 61 MHz.
"""


# The first section's sentence and the intro's cycles, against data.json.
BEST_AND_CYCLES = [{"quote": "the best is 0.0480 vertices/cycle, 14 % idle", "section": "## 1.",
                    "values": {"0.0480": "j('d')['best']", "14": "100 * j('d')['idle']"}},
                   {"quote": "runs 9 717 633 cycles", "values": {"9 717 633": "j('d')['cycles']"}}]


class ClaimsTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        root = Path(self.tmp.name)
        (root / "docs/results/claims").mkdir(parents=True)
        (root / "docs/results/page.md").write_text(PAGE)
        self.data = root / "docs/results/data.json"
        self.data.write_text(json.dumps({"cycles": 9717633, "best": 0.04796, "idle": 0.1404, "half": [0.5, 0.46],
                                         "mhz": 61.2}))
        with open(root / "docs/results/rows.csv", "w") as f:
            f.write("N,tput\n1,0.04796\n2,0.0681\n")
        self._saved = claims.ROOT, claims.CLAIMS_DIR, claims.DOCS
        claims.ROOT, claims.CLAIMS_DIR, claims.DOCS = root, root / "docs/results/claims", ["docs/results/page.md"]
        self.root = root

    def tearDown(self):
        claims.ROOT, claims.CLAIMS_DIR, claims.DOCS = self._saved
        self.tmp.cleanup()

    def write_claims(self, items, name="page.json"):
        path = self.root / "docs/results/claims" / name
        path.write_text(json.dumps({"doc": "docs/results/page.md", "data": {"d": "docs/results/data.json"},
                                    "claims": items}))
        return path

    def run_claims(self):
        docs = claims.load_docs()
        return docs, claims.check_claim_files(docs)

    def uncovered_with(self, items):
        """The numbers still uncovered once `items` are the claims; the claims must pass."""
        self.write_claims(items)
        docs, failures = self.run_claims()
        self.assertEqual(failures, [])
        return [t[2] for t in docs["docs/results/page.md"].uncovered()]

    def test_numbers_and_labels(self):
        doc = claims.load_docs()["docs/results/page.md"]
        self.assertEqual([t[2] for t in doc.tokens], ["9 717 633", "0.0480", "14", "0.5", "0.5", "0.0480", "61"])

    def test_a_claim_passes_and_fails_when_its_data_change(self):
        self.assertEqual(self.uncovered_with(BEST_AND_CYCLES), ["0.5", "0.5", "0.0480", "61"])
        changed = json.loads(self.data.read_text())
        changed["best"] = 0.0482  # rounds to 0.0482, not the doc's 0.0480
        self.data.write_text(json.dumps(changed))
        _, failures = self.run_claims()
        self.assertEqual(len(failures), 1)
        self.assertIn("the doc says 0.0480, the data give 0.0482", failures[0])
        self.assertIn("page.md:7", failures[0])

    def test_fix_rewrites_stale_numbers_in_the_doc_and_the_claim(self):
        path = self.write_claims(BEST_AND_CYCLES)
        changed = json.loads(self.data.read_text())
        changed.update(best=0.05126, idle=0.0951, cycles=12345678)
        self.data.write_text(json.dumps(changed))
        docs, stale = claims.load_docs(), []
        self.assertEqual(len(claims.check_claim_files(docs, stale=stale)), 3)
        self.assertEqual(claims.fix_stale(docs, stale), ["docs/results/page.md:3: 9 717 633 -> 12 345 678",
                                                         "docs/results/page.md:7: 0.0480 -> 0.0513",
                                                         "docs/results/page.md:7: 14 -> 10"])
        docs, failures = self.run_claims()
        self.assertEqual(failures, [])
        text = (self.root / "docs/results/page.md").read_text()
        self.assertIn("runs 12 345 678 cycles", text)
        self.assertIn("the best is 0.0513 vertices/cycle, 10 % idle", text)
        self.assertIn("The best is 0.0480 again", text)  # the other 0.0480 is not this claim's
        spec = json.loads(path.read_text())
        self.assertEqual(sorted(spec["claims"][0]["values"]), ["0.0513", "10"])

    def test_rounding_at_the_written_decimals(self):
        self.assertTrue(claims.agrees("0.0480", 0.04796, 0))
        self.assertFalse(claims.agrees("0.0480", 0.04806, 0))
        self.assertTrue(claims.agrees("1 960", 1960.4, 0))
        self.assertFalse(claims.agrees("1 960", 1960.6, 0))
        self.assertTrue(claims.agrees("−2.5", -2.54, 0))
        self.assertTrue(claims.agrees("61", 63.0, 0.05))
        self.assertFalse(claims.agrees("61", 65.0, 0.05))
        self.assertFalse(claims.agrees("61", float("nan"), 0))

    def test_a_csv_row_and_a_table_cell(self):
        (self.root / "docs/results/tables2.md").write_text("### Best\n\n| K | N = 1 | N = 2 |\n|---|---|---|\n"
                                                            "| 8 | 0.04796 | **0.06814** |\n")
        self.write_claims([{"quote": "The best is 0.0480 again", "values": {
            "0.0480": "min(num(r['tput']) for r in rows('docs/results/rows.csv')) + 0 * "
                      "cell('docs/results/tables2.md', 'Best', 8, 'N = 2')"}}])
        _, failures = self.run_claims()
        self.assertEqual(failures, [])

    def test_refusals(self):
        self.write_claims([
            {"quote": "61 MHz", "values": {"61": "61"}},                      # reads no data
            {"quote": "61 MHz", "labels": {"61": "measured: it is"}},         # not a label kind
            {"quote": "best is 0.0480", "values": {"0.0480": "j('d')['best']"}},       # twice in the page
            {"quote": "61 MHz", "values": {"62": "j('d')['mhz']"}}])          # no such number in the quote
        _, failures = self.run_claims()
        self.assertEqual(len(failures), 4)
        self.assertIn("reads no data file", failures[0])
        self.assertIn("not 'KIND: reason'", failures[1])
        self.assertIn("found 2 times", failures[2])
        self.assertIn("no number '62'", failures[3])

    def test_occurrences_and_labels(self):
        left = self.uncovered_with([{"quote": "The two numbers 0.5 and 0.5 differ",
                                     "values": {"0.5#1": "j('d')['half'][0]", "0.5#2": "j('d')['half'][1]"}},
                                    {"quote": "at 61 MHz", "labels": {"61": "input: the clock the example states"}}])
        self.assertEqual(left, ["9 717 633", "0.0480", "14", "0.0480"])
        self.write_claims([{"quote": "The two numbers 0.5 and 0.5 differ", "values": {"0.5": "j('d')['half'][1]"}}])
        _, failures = self.run_claims()
        self.assertEqual(failures, [])  # 0.46 rounds to 0.5 at one decimal: both occurrences agree

    def test_recorded_patterns_cover_through_collapsed_whitespace(self):
        docs = claims.load_docs()
        doc = docs["docs/results/page.md"]
        recorder = claims.Recorder()
        flat = " ".join(doc.text.split())
        recorder.search(r"the best is ([\d.]+) vertices/cycle, (\d+) % idle, with", flat)
        recorder.search(r"See nothing (\d+)", "See nothing 7")  # a string that is not the page's
        recorder.apply(docs)
        self.assertEqual([t[2] for t in doc.uncovered()], ["9 717 633", "0.5", "0.5", "0.0480", "61"])

    def test_the_ratchet(self):
        pending = self.root / "docs/results/claims/pending.json"
        pending.write_text(json.dumps({"pending": {"docs/results/page.md": ["## 1.", "## 2."]}}))
        docs = claims.load_docs()
        problems = claims.ratchet(docs)
        self.assertEqual(len(problems), 1)
        self.assertIn("9 717 633 is neither checked nor labelled", problems[0])
        self.write_claims([{"quote": "runs 9 717 633 cycles", "values": {"9 717 633": "j('d')['cycles']"}},
                           {"quote": "is 0.0480 again, at 61 MHz", "section": "## 2.", "values": {"61": "j('d')['mhz']"}, "labels": {
                               "0.0480": "target: an example"}}])
        docs, failures = self.run_claims()
        self.assertEqual(failures, [])
        problems = claims.ratchet(docs)
        self.assertEqual(len(problems), 1)
        self.assertTrue(re.search(r"'## 2\.' is accounted for; remove it", problems[0]))

    def test_a_pending_quote_holds_its_numbers_only(self):
        pending = self.root / "docs/results/claims/pending.json"
        pending.write_text(json.dumps({"pending": {"docs/results/page.md": [
            {"quote": "runs 9 717 633 cycles", "why": "an example"}, "## 1.", "## 2."]}}))
        self.assertEqual(claims.ratchet(claims.load_docs()), [])
        pending.write_text(json.dumps({"pending": {"docs/results/page.md": [
            {"quote": "runs 9 717 633 cycles"}, {"quote": "0.5 and", "why": "x"}, "## 2."]}}))
        problems = claims.ratchet(claims.load_docs())
        self.assertIn("gives no reason", problems[0])
        left = [p for p in problems if "neither checked nor labelled" in p]
        self.assertEqual([re.search(r"page.md:\d+: (\S+)", p).group(1) for p in left], ["0.0480", "14", "0.5"])


if __name__ == "__main__":
    unittest.main()
