#!/usr/bin/env python3
"""The mutation campaign reaches every class of parameter value of the shipped builds
(docs/verification.md, Mutation campaign): a bug visible only at, say, three CPG copies or a
16-bit alpha must be reachable by some stimulus of scripts/mutants.py. Fails naming each class no
stimulus reaches and the shipped build that has it, and each mutant whose text no longer occurs
exactly once in its file (the campaign would stop there). The check itself can fail: dropping the
stimuli of each campaign build in turn must leave the classes only that build has uncovered."""
import json
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "scripts"))
import mutants  # noqa: E402
import rtl_builds  # noqa: E402
import yosys_cost  # noqa: E402


def main():
    failures = []
    stimuli = mutants.stimulus()
    shipped = json.loads((ROOT / "rtl/builds.json").read_text())["builds"]
    by_name = {b["name"]: b for b in shipped}
    defaults = yosys_cost.package_defaults(ROOT / "rtl")

    reached = mutants.reached_builds(stimuli)
    for name in reached:
        if name not in by_name:
            failures.append(f"a stimulus runs on '{name}', which rtl/builds.json does not have")
    if set(reached) != set(mutants.RTL_BUILDS):
        failures.append(f"the campaign builds {mutants.RTL_BUILDS} but its stimuli run on {reached}")
    missing = mutants.uncovered(stimuli)
    for param, cls, build in missing:
        failures.append(f"no stimulus reaches {param} {cls} (shipped build {build})")
    print(f"{len(stimuli)} stimuli on {len(reached)} builds reach every class of "
          f"{len([b for b in shipped if not dict(b['parameters']).get('InjectBug')])} shipped builds"
          if not missing else f"{len(missing)} classes unreached")

    # Every mutant applies to the tree as it stands: its text occurs exactly once in its file (a
    # rewrite of the line would otherwise stop the campaign at that mutant).
    table = json.loads((ROOT / "scripts/mutants/mutants.json").read_text())["mutants"]
    for m in table:
        text = (ROOT / m["file"]).read_text()
        for edit in [m] + m.get("also", []):
            count = text.count(edit["find"])
            if count != 1:
                failures.append(f"mutant {m['id']}: its text occurs {count} times in {m['file']}, not once")
    print(f"{len(table)} mutants apply to the tree")

    # Negative control: a build whose classes no other campaign build has is necessary; without its
    # stimuli the check must name those classes.
    necessary = 0
    for name in mutants.RTL_BUILDS:
        others = [by_name[n] for n in mutants.RTL_BUILDS if n != name]
        own = rtl_builds.parameter_classes(by_name[name]["parameters"], defaults) - set().union(
            *(rtl_builds.parameter_classes(b["parameters"], defaults) for b in others))
        without = [s for s in stimuli if s.get("build") != name and name not in s.get("builds", [])]
        got = {(p, c) for p, c, _ in mutants.uncovered(without)}
        if own:
            necessary += 1
            if not own <= got:
                failures.append(f"without the stimuli on {name} the check misses {sorted(own - got)}")
        print(f"  without {name}: {len(got)} classes unreached" + (f" ({sorted(own)})" if own else ""))
    if necessary == 0:
        failures.append("no campaign build is necessary: the negative control tests nothing")
    # A class that only a non-power-of-two count has: with the three- and five-copy builds removed
    # from the shipped list's coverage the check names the copy counts.
    cut = [s for s in stimuli if s.get("build") not in ("n1_r4", "n4_l3r24")
           and not {"n1_r4", "n4_l3r24"} & set(s.get("builds", []))]
    copies = sorted(c for p, c, _ in mutants.uncovered(cut) if p == "CpgCopies")
    if copies != ["3", "5"]:
        failures.append(f"without n1_r4 and n4_l3r24 the unreached copy counts should be 3 and 5, got {copies}")
    for f in failures:
        print("mutant_classes_test: " + f, file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
