#!/usr/bin/env python3
"""Numbers the docs state about the project's own data, checked against that data, so that a
claim cannot drift when the data changes: the mutants in the campaign, the Verilated builds CI
makes, the runs of the bad-input campaign."""
import argparse
import json
import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
WORDS = {w: i for i, w in enumerate("zero one two three four five six seven eight nine ten eleven twelve thirteen "
                                    "fourteen fifteen sixteen seventeen eighteen nineteen twenty".split())}


def claim(path: str, pattern: str) -> str:
    text = (ROOT / path).read_text()
    found = re.findall(pattern, text)
    if len(found) != 1:
        raise SystemExit(f"doc_claims_test: {path}: expected one match of {pattern!r}, found {len(found)}")
    return found[0]


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--tessim", required=True)
    a = ap.parse_args()
    failures = []

    def check(what, stated, actual):
        print(f"{what}: docs say {stated}, data has {actual}")
        if stated != actual:
            failures.append(what)

    mutants = json.loads((ROOT / "scripts/mutants/mutants.json").read_text())["mutants"]
    check("mutants in the campaign", int(claim("docs/verification.md", r"The campaign holds (\d+) mutants")),
          len(mutants))
    builds = json.loads((ROOT / "rtl/builds.json").read_text())["builds"]
    check("Verilated models CI builds", WORDS[claim("docs/verification.md", r"\((\w+) Verilated models\)")],
          len(builds))
    runs = subprocess.run([sys.executable, str(ROOT / "scripts/bad_input_campaign.py"), "--tessim", a.tessim,
                           "--count"], capture_output=True, text=True, check=True).stdout.strip()
    check("runs of the bad-input campaign", int(claim("docs/verification.md", r"runs `tessim` (\d+) times")),
          int(runs))
    if failures:
        print("doc_claims_test: stale: " + ", ".join(failures), file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
