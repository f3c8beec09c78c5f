#!/usr/bin/env python3
"""Numbers the docs state about the project's own data, checked against that data, so that a
claim cannot drift when the data changes: the mutants in the campaign (and in each round of it),
the Verilated builds CI makes, the runs of the bad-input campaign, the points of the sweeps, the
functional-coverage bins, the builds of the CPG variant matrix, the fair silhouette measurement
(silhouette.md's tables and the figures other pages quote from silhouette/fair.json), and the
load-balancing study's answer, §4 and §12 figures against its records and generated tables, and
§10's buffer table, §11's targets and §13's copies against the commands they quote, and
scenes.md's sizing against docs/results/scenes/study.json.
A count in README.md or docs/
of one of these is either checked here or not stated."""
import argparse
import ast
import csv
import hashlib
import json
import os
import re
import subprocess
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import claims  # noqa: E402  (every number of docs/results/*.md accounted for)

ROOT = Path(__file__).resolve().parents[2]
WORDS = {w: i for i, w in enumerate("zero one two three four five six seven eight nine ten eleven twelve thirteen "
                                    "fourteen fifteen sixteen seventeen eighteen nineteen twenty".split())}


def claim(path: str, pattern: str) -> str:
    text = (ROOT / path).read_text()
    found = re.findall(pattern, text)
    if len(found) != 1:
        raise SystemExit(f"doc_claims_test: {path}: expected one match of {pattern!r}, found {len(found)}")
    return found[0]


def number(text: str) -> int:
    """A count as the docs write it: '1 960', '1,960' or '1960'."""
    return int(re.sub(r"[\s,\u2009\u202f]", "", text))


def section(path: str, heading: str) -> str:
    text = (ROOT / path).read_text()
    start = text.index(heading)
    end = text.find("\n## ", start + len(heading))
    return text[start:end if end >= 0 else len(text)]


def mutant_rounds(check):
    """Each round of the mutation campaign states the campaign's size after it; that size must be
    the number of mutants of mutants.json named up to the end of that paragraph, and every mutant
    must be named."""
    ids = [m["id"] for m in json.loads((ROOT / "scripts/mutants/mutants.json").read_text())["mutants"]]
    text = section("docs/verification.md", "## Mutation campaign")
    named = lambda upto: {i for i in ids if re.search(rf"\b{i}\b", text[:upto])}
    for m in re.finditer(r"\*\*(\d+) mutants:|brought\s+the\s+campaign\s+to\s+(\d+)\s+mutants|campaign\s+holds\s+(\d+)\s+mutants", text):
        stated = int(next(g for g in m.groups() if g))
        end = text.find("\n\n", m.end())  # the paragraph that states the size names the round's own
        check(f"mutants named up to '{' '.join(m.group(0).split())}' (verification.md)", stated,
              len(named(end if end >= 0 else len(text))))
    check("mutants of mutants.json named in verification.md", len(ids), len(named(len(text))))
    listed = set(re.findall(r"^\| ([a-z][a-z0-9]*(?:_[a-z0-9]+)+) \|", text, re.M))
    check("mutants in verification.md's tables that mutants.json lacks", [], sorted(listed - set(ids)))
    check("mutants in the campaign (README.md)",
          int(claim("README.md", r"mutation campaign: (\d+) single-point bugs")), len(ids))


def sweep_points(check):
    """The points of scripts/sweeps/*.json (as sweep.py expands them), their committed results, and
    the counts README.md, load-balancing.md and the specs' descriptions state."""
    sys.path.insert(0, str(ROOT / "scripts"))
    import sweep  # noqa: E402  (the spec expansion sweep.py runs)

    def points(name):
        spec_path = ROOT / "scripts/sweeps" / f"{name}.json"
        spec = json.loads(spec_path.read_text())
        return spec, sweep.expand(spec, spec_path.parent)

    small_spec, small = points("small")
    full_spec, full = points("full")
    _, adaptive = points("adaptive")
    cpg_grids = {"cpg", "cpg_adaptive", "cpg_fast", "cpg_copies", "cpg_copies_adaptive", "cpg_copies_fast", "cpg_budget",
                 "cpg_budget_adaptive"}
    study = [(p, g) for p, g in small if not cpg_grids & set(g)]
    for name, pts, csv_path in (("small", small, "docs/results/results.csv"),
                                ("full", full, "docs/results/full/results.csv"),
                                ("adaptive", adaptive, "docs/results/adaptive/results.csv")):
        with open(ROOT / csv_path, newline="") as f:
            check(f"rows of {csv_path} against the points of {name}.json", len(pts), sum(1 for _ in csv.DictReader(f)))

    readme = "README.md"
    check("small sweep points (README.md)", number(claim(readme, r"the small sweep \(([\d ,]+) points\)")), len(small))
    check("full sweep points (README.md)", number(claim(readme, r"`--full` \(([\d ,]+) points")), len(full))
    check("adaptive sweep points (README.md)", number(claim(readme, r"`--adaptive` \(([\d ,]+) points\)")),
          len(adaptive))

    lb = "docs/results/load-balancing.md"
    check("small set points timed (load-balancing.md)",
          number(claim(lb, r"the ([\d ,]+) points with a built tessim")), len(small))
    total, in_study, in_adaptive, in_cpg = claim(
        lb, r"CI run: ([\d ,]+)\s+points, ([\d ,]+) of them in the grids of §1–§10 \(([\d ,]+) of these adaptive\)"
            r"\s+and ([\d ,]+) in the CPG-variant")
    check("small set points (load-balancing.md)", number(total), len(small))
    check("small set points outside the CPG grids (load-balancing.md)", number(in_study), len(study))
    check("adaptive points among them (load-balancing.md)", number(in_adaptive),
          sum("camera" in p for p, _ in study))
    check("points of the CPG-variant grids (load-balancing.md)", number(in_cpg), len(small) - len(study))
    check("points of grids cpg and cpg_fast (load-balancing.md)",
          number(claim(lb, r"predicts the ([\d ,]+) points of the grids\s+`cpg` and `cpg_fast`")),
          sum(bool({"cpg", "cpg_fast"} & set(g)) for _, g in small))
    check("full set points (load-balancing.md)", number(claim(lb, r"The full set \(([\d ,]+) points\)")), len(full))
    check("full set points, model versus simulation (load-balancing.md)",
          number(claim(lb, r"On the ([\d ,]+) points of the full set")), len(full))
    with open(ROOT / "docs/results/full/results.csv", newline="") as f:
        err = [abs(float(r["analytic.run_cycles"]) - float(r["cycles"])) / float(r["cycles"]) for r in csv.DictReader(f)]
    close, near = claim(lb, r"simulated cycles on ([\d ,]+) points and within 1 % on\s+([\d ,]+)\.")
    check("full set points within 0.1 % of the model (load-balancing.md)", number(close), sum(e <= 1e-3 for e in err))
    check("full set points within 1 % of the model (load-balancing.md)", number(near), sum(e <= 1e-2 for e in err))
    check("full set points beyond 1 % (load-balancing.md)",
          number(claim(lb, r"TE with few contexts and N ≥ 3\*\* \(([\d ,]+) points")), sum(e > 1e-2 for e in err))

    d = small_spec["description"]
    study_n, adaptive_n = re.search(r"([\d,]+) points \(([\d,]+) of them adaptive", d).groups()
    check("small.json description: points outside the CPG grids", number(study_n), len(study))
    check("small.json description: adaptive among them", number(adaptive_n), sum("camera" in p for p, _ in study))
    check("small.json description: CPG-variant points",
          number(re.search(r"([\d,]+) more points", d).group(1)), len(small) - len(study))
    check("small.json description: points", number(re.search(r"\): ([\d,]+) points", d).group(1)), len(small))
    check("full.json description: points",
          number(re.search(r"([\d,]+) points;", full_spec["description"]).group(1)), len(full))


def coverage_bins(check, tessim):
    """The bins scripts/coverage.sh declares: the campaign run with every random stream cut to one
    triangle (the bins a run declares depend on its configuration only, not on its length)."""
    probe = subprocess.run([tessim, "cosim", "--help"], capture_output=True, text=True)
    if probe.returncode != 0:
        print(f"coverage bins: not checked, this tessim has no co-simulation: {probe.stderr.strip()}")
        return
    with tempfile.TemporaryDirectory() as tmp:
        wrapper = Path(tmp) / "tessim"
        wrapper.write_text(f"#!{sys.executable}\n"
                           "import os, sys\n"
                           "args = sys.argv[1:]\n"
                           "for i, a in enumerate(args[:-1]):\n"
                           "    if a == '--random':\n"
                           "        args[i + 1] = '1'\n"
                           f"os.execv({tessim!r}, [{tessim!r}] + args)\n")
        wrapper.chmod(0o755)
        out = Path(tmp) / "coverage.json"
        subprocess.run(["bash", str(ROOT / "scripts/coverage.sh"), str(out)], check=True, stdout=subprocess.DEVNULL,
                       env=dict(os.environ, TESSIM=str(wrapper)))
        bins = json.loads(out.read_text())["total"]
    covered, total = claim("docs/verification.md", r"\*\*(\d+) of (\d+) bins\*\*")
    check("bins of the coverage campaign (verification.md)", int(total), bins)
    check("bins the coverage campaign hit (verification.md: all)", int(covered), int(total))
    check("bins of the coverage campaign (README.md)", int(claim("README.md", r"hits all (\d+) bins")), bins)


def cpg_matrix_builds(check):
    """The builds scripts/cpg_matrix.py makes by default: edge lanes × digit bits × N."""
    defaults = {}
    for node in ast.walk(ast.parse((ROOT / "scripts/cpg_matrix.py").read_text())):
        if isinstance(node, ast.Call) and getattr(node.func, "attr", "") == "add_argument":
            for k in node.keywords:
                if k.arg == "default" and isinstance(k.value, ast.List):
                    defaults[node.args[0].value] = ast.literal_eval(k.value)
    lanes, digits, blocks = defaults["--lanes"], defaults["--digit-bits"], defaults["--int"]
    variants = len(lanes) * len(digits)
    check("CPG variant × N builds (README.md)", int(claim("README.md", r"\((\d+) RTL builds in a tree of their own\)")),
          variants * len(blocks))
    stated, ec, r = claim("docs/verification.md", r"is (\d+) builds \(Ec ∈ \{([\d, ]+)\} × r ∈ \{([\d, ]+)\} × N = 1\.\.4\)")
    check("CPG variant × N builds (verification.md)", int(stated), variants * len(blocks))
    check("edge lanes of the matrix (verification.md)", [int(x) for x in ec.split(",")], lanes)
    check("digit bits of the matrix (verification.md)", [int(x) for x in r.split(",")], digits)
    check("N of the matrix (verification.md: 1..4)", [1, 2, 3, 4], blocks)
    check("CPG variants at one N (verification.md)",
          int(claim("docs/verification.md", r"r ∈ \{[\d, ]+\}, (\d+) builds\)")), variants)


def stated_close(text: str, actual: float) -> bool:
    """Whether a number as written ('49.6', '0.105', '102') rounds from `actual`."""
    return claims.agrees(text, actual, 0)  # the one rounding rule of the claims


def silhouette_fair(check):
    """docs/results/silhouette.md's fair-measurement tables against silhouette/fair.json, the
    generated silhouette/fair.md against what the script makes of fair.json, and the figures other
    pages quote from it."""
    sys.path.insert(0, str(ROOT / "scripts"))
    import silhouette_fair as fair
    doc = json.loads((ROOT / "docs/results/silhouette/fair.json").read_text())
    with tempfile.TemporaryDirectory() as tmp:
        fair.write_markdown(doc, os.path.join(tmp, "fair.md"))
        check("silhouette/fair.md regenerated from fair.json", True,
              Path(tmp, "fair.md").read_text() == (ROOT / "docs/results/silhouette/fair.md").read_text())
    meshes = {m["mesh"]: m for m in doc["meshes"]}
    order = list(meshes)
    text = section("docs/results/silhouette.md", "### Result").split("### Popping")[0]
    rows = {r[0]: r[1:] for r in (re.split(r"\s*\|\s*", line.strip("| ")) for line in text.splitlines()
                                  if line.startswith("| ") and not line.startswith("| rule"))}
    names = {"screen-adaptive factors": "screen", "silhouette rule, PN patches": "silhouette",
             "contour rule, PN patches": "contour", "contour rule, fractional_odd": "contour-fractional"}
    bad = []
    for label, kind in names.items():
        for name, cell in zip(order, rows[label]):
            m = meshes[name]
            share = re.match(r"\**([\d.]+) %", cell).group(1)
            if not stated_close(share, 100 * m["share_by_rule"][kind]):
                bad.append(f"{label} {name} {share}")
            views = re.search(r"\(([\d]+) / ([\d]+) / ([\d]+)", cell)
            if views:
                pv = m["share_per_view"][kind]
                for got, key in zip(views.groups(), ("min", "median", "max")):
                    if not stated_close(got, 100 * pv[key]):
                        bad.append(f"{label} {name} per-view {key} {got}")
    for label, kind in (("silhouette rule + blend: against PN; against its own limit", "silhouette-blend"),
                        ("contour rule + blend: against PN; against its own limit", "contour-blend")):
        for name, cell in zip(order, rows[label]):
            m = meshes[name]
            against, own = cell.split(";")
            share = m["share_by_rule"][kind]
            if (against.strip() == "never") != (share is None) or (share is not None and
                                                                    not stated_close(against.strip(" %"), 100 * share)):
                bad.append(f"{label} {name} against PN {against}")
            if not stated_close(own.strip(" %"), 100 * m["share_against_own_limit"][kind]):
                bad.append(f"{label} {name} own limit {own}")
    for name, cell in zip(order, rows["uniform L = 8: triangles, mean contour error"]):
        tri, err = re.match(r"([\d ]+), ([\d.]+) px", cell).groups()
        if number(tri) != round(meshes[name]["reference"]["triangles"]) or \
                not stated_close(err, meshes[name]["reference"]["error_px"]):
            bad.append(f"L = 8 reference {name}")
    check("silhouette.md result table against fair.json (cells that disagree)", [], bad)
    text = section("docs/results/silhouette.md", "### Popping")
    rows = {r[0]: r[1:] for r in (re.split(r"\s*\|\s*", line.strip("| ")) for line in text.splitlines()
                                  if line.startswith("| ") and not line.startswith("| rule"))}
    names.update({"silhouette rule + blend": "silhouette-blend", "contour rule + blend": "contour-blend"})
    bad = []
    for label, kind in names.items():
        for name, cell in zip(order, rows[label]):
            frames, jump = re.match(r"\**([\d]+) %\**, ([\d.]+) px", cell).groups()
            p = doc["popping"][name][kind]
            if not stated_close(frames, 100 * p["pop_frames_over_half_px"]) or not stated_close(jump, p["pop_max_px"]):
                bad.append(f"{label} {name}")
    check("silhouette.md popping table against fair.json (cells that disagree)", [], bad)
    # Figures other pages quote.
    w, s_, y = (meshes[n] for n in ("Wuson", "sphereWithHole", "sydney"))
    lb = section("docs/results/load-balancing.md", "## 14.")
    quoted = re.search(r"takes the silhouette rule ([\d.]+) % of L = 8's triangles on Wuson and ([\d.]+) % on\s+"
                       r"sphereWithHole, the contour rule ([\d.]+) % and ([\d.]+) %, and on the figure sydney either "
                       r"rule about all\s+of them \(([\d.]+) % and ([\d.]+) %\)", lb).groups()
    actual = [w["share_by_rule"]["silhouette"], s_["share_by_rule"]["silhouette"], w["share_by_rule"]["contour"],
              s_["share_by_rule"]["contour"], y["share_by_rule"]["silhouette"], y["share_by_rule"]["contour"]]
    check("load-balancing.md §14 shares against fair.json", True,
          all(stated_close(q, 100 * a) for q, a in zip(quoted, actual)))
    tri = number(re.search(r"on Wuson ([\d ]+) triangles over 3 732 patches at T = 1/32 px", lb).group(1))
    check("load-balancing.md §14 rule triangles at T = 1/32 on Wuson", tri,
          round(w["summary"]["silhouette T=0.03125"]["triangles"]["mean"]))
    pv = re.search(r"worst view 240 % of L = 8's triangles, where the\s+per-edge rule needs 447 %",
                   (ROOT / "docs/patterns.md").read_text())
    check("patterns.md sydney worst views against fair.json", True,
          pv is not None and round(100 * y["share_per_view"]["contour"]["max"]) == 240 and
          round(100 * y["share_per_view"]["silhouette"]["max"]) == 447)
    images = (ROOT / "docs/images.md").read_text()
    q = re.search(r"\(([\d.]+) against ([\d.]+) px\), and reaching L = 4's contour error takes the blend (\d+) % of "
                  r"L = 4's\s+triangles on Wuson \((\d+) % on sydney\), the silhouette rule without the blend (\d+) %",
                  images).groups()
    ref4 = lambda m: m["summary"]["uniform L=4"]
    share4 = lambda m, kind: fair.crossing([(c["triangles"]["mean"], c["error_px"]["mean"]) for c in m["summary"].values()
                                            if c["kind"] == kind], ref4(m)["error_px"]["mean"]) / ref4(m)["triangles"]["mean"]
    check("images.md blend against uniform L = 4 (fair.json)", True,
          stated_close(q[0], w["summary"]["silhouette-blend T=0.25"]["error_px"]["mean"]) and
          stated_close(q[1], ref4(w)["error_px"]["mean"]) and stated_close(q[2], 100 * share4(w, "silhouette-blend")) and
          stated_close(q[3], 100 * share4(y, "silhouette-blend")) and stated_close(q[4], 100 * share4(w, "silhouette")))


def table_rows(path: str, heading: str) -> dict:
    """The rows of the first table under `heading` of a generated tables.md, by first cell."""
    text = (ROOT / path).read_text()
    body = text[text.index(heading):]
    rows, started = {}, False
    for line in body.splitlines()[1:]:
        if line.startswith("|"):
            started = True
            cells = [c.strip(" *") for c in line.strip("|").split("|")]
            rows[cells[0]] = cells[1:]
        elif started:
            break
    return rows


def load_balancing_claims(check):
    """Figures of load-balancing.md's answer, §3/§4 and §12 against the study's data: the
    whole-unit records of full/results.csv, the generated full/tables.md and tables.md, and the
    generated stpn_table.md."""
    lb = (ROOT / "docs/results/load-balancing.md").read_text()
    per_mtr = table_rows("docs/results/full/tables.md", "### Throughput per million transistors")
    n1, n2, n3 = (per_mtr["8"][i] for i in range(3))
    quoted = re.search(r"\(([\d.]+) vertices/cycle per\s+million transistors against ([\d.]+) for N = 1 and "
                       r"([\d.]+) for N = 3;", lb).groups()
    check("answer: vertices/cycle per Mtr. at K = 8, N = 2 / 1 / 3 (full/tables.md)", True,
          all(stated_close(q, float(a)) for q, a in zip(quoted, (n2, n1, n3))))
    small = table_rows("docs/results/tables.md", "### Throughput per million transistors")
    q, lower = re.search(r"at N = 4 for K = 4 \(([\d.]+), N = 3\s+([\d.]+) % lower\)", lb).groups()
    check("§4: small set, N = 4 at K = 4 and N = 3 below it (tables.md)", True,
          stated_close(q, float(small["4"][3])) and
          stated_close(lower, 100 * (1 - float(small["4"][2]) / float(small["4"][3]))))
    unit = {}
    with open(ROOT / "docs/results/full/results.csv") as f:
        for r in csv.DictReader(f):
            if r["mesh"].endswith("Wuson.ply") and r["tess_factor"] == "16" and r["int_latency"] == "1" and \
                    r["normals"] == "quadratic" and r["cost_unit_transistors"]:
                unit.setdefault((int(r["int_blocks"]), int(r["te_contexts"])),
                                (int(r["cost_unit_transistors"]) / 1e6, int(r["cost_unit_depth"])))
    v2, v4 = unit[(2, 2)], unit[(2, 4)]
    q = re.search(r"costs ([\d.]+) M\s+instead of ([\d.]+) M transistors \(−([\d.]+) %, logic depth (\d+) instead "
                  r"of (\d+);", lb).groups()
    check("answer: N = 2 with V = 2 against V = 4 (full/results.csv)", True,
          stated_close(q[0], v2[0]) and stated_close(q[1], v4[0]) and stated_close(q[2], 100 * (1 - v2[0] / v4[0]))
          and int(q[3]) == v2[1] and int(q[4]) == v4[1])
    q = re.search(r"which grows from (\d+) at N = 1 to (\d+) at N = 6", lb).groups()
    check("answer: clock depth at N = 1 and N = 6, V = 4 (full/results.csv)", [int(x) for x in q],
          [unit[(1, 4)][1], unit[(6, 4)][1]])
    q = re.search(r"unit is ([\d.]+)–([\d.]+) M\s+transistors cheaper for N = 1…3, and (\d+)–(\d+) levels deep "
                  r"instead of (\d+)–(\d+)", lb).groups()
    saving = [unit[(n, 4)][0] - unit[(n, 2)][0] for n in (1, 2, 3)]
    check("§4: V = 2 against V = 4 for N = 1…3 (full/results.csv)", True,
          stated_close(q[0], min(saving)) and stated_close(q[1], max(saving)) and
          [int(x) for x in q[2:]] == [unit[(1, 2)][1], unit[(3, 2)][1], unit[(1, 4)][1], unit[(3, 4)][1]])
    steps = [unit[(n + 1, 4)][0] - unit[(n, 4)][0] for n in range(2, 6)]
    further = re.findall(r"(?:every further block adds|each added block costs)\s+about ([\d.]+) M", lb)
    check("statements of what a further INT block adds (answer and §4)", 2, len(further))
    for q in further:
        check("answer and §4: what a further INT block adds (full/results.csv)", True,
              all(stated_close(q, x) for x in steps))
    section12 = section("docs/results/load-balancing.md", "## 12.")
    generated = [line for line in (ROOT / "docs/results/stpn_table.md").read_text().splitlines()
                 if line.startswith("| ")]
    check("§12 tables lines missing from the generated stpn_table.md", [],
          [line for line in generated if line not in section12.splitlines()])


SIM_CACHE = None  # a directory for sim_stats' results when listing uncovered numbers (claims.py)


def sim_stats(tessim: str, args: list) -> dict:
    key = None
    if SIM_CACHE:
        binary = Path(tessim).stat()
        key = Path(SIM_CACHE) / (hashlib.sha256(json.dumps([str(binary.st_mtime_ns), binary.st_size] + args)
                                                .encode()).hexdigest() + ".json")
        if key.is_file():
            return json.loads(key.read_text())
    with tempfile.TemporaryDirectory() as tmp:
        stats = os.path.join(tmp, "s.json")
        subprocess.run([tessim, "sim"] + args + ["--stats", stats], check=True, capture_output=True)
        if key:
            key.parent.mkdir(parents=True, exist_ok=True)
            key.write_text(Path(stats).read_text())
        return json.loads(Path(stats).read_text())


def cpg_targets(check, tessim):
    """§11's targets, from the very commands the section quotes (each runs in well under a
    second), on Wuson as quoted and on sphereWithHole with the same flags."""
    text = section("docs/results/load-balancing.md", "## 11.")
    spheres = "/usr/share/assimp/models/STL/sphereWithHole.stl"
    commands = re.findall(r"`tessim sim (/usr/share/assimp/models/PLY/Wuson.ply [^`]+)`", text)
    radix = next(c for c in commands if "--cpg-digit-bits 4" in c).split()
    fast = next(c for c in commands if "--gpe-cycles 1" in c).split()
    sequential = [a for i, a in enumerate(radix) if a != "--cpg-digit-bits" and radix[i - 1] != "--cpg-digit-bits"]
    on_sphere = lambda args: [spheres] + args[1:]
    reflect = lambda args: [a if a != "24" else "8" for a in args] + ["--normals", "reflect"]
    q = re.search(r"runs at ([\d.]+) cycles per vertex on sphereWithHole and ([\d.]+) on Wuson, ([\d.]+) % and\s+"
                  r"([\d.]+) % of the GPE's rate .*?, against ([\d.]+) and ([\d.]+) with\s+the sequential CPG", text,
                  re.S).groups()
    s_r, w_r = sim_stats(tessim, on_sphere(radix)), sim_stats(tessim, radix)
    s_s, w_s = sim_stats(tessim, on_sphere(sequential)), sim_stats(tessim, sequential)
    actual = [s_r["cycles_per_vertex"], w_r["cycles_per_vertex"], 800 / s_r["cycles_per_vertex"],
              800 / w_r["cycles_per_vertex"], s_s["cycles_per_vertex"], w_s["cycles_per_vertex"]]
    check("§11: one lane of 4 bits at L = 4, N = 2, K = 8 (quoted command)", True,
          all(stated_close(a, b) for a, b in zip(q, actual)))
    q = re.search(r"the unit delivers ([\d.]+)\s+vertices per cycle on sphereWithHole and ([\d.]+) on Wuson at L = 4 "
                  r"\(quadratic normals;\s+reflect: three lanes of 8 bits, C = 13, ([\d.]+) and ([\d.]+)\)", text).groups()
    w_f = sim_stats(tessim, fast)
    actual = [sim_stats(tessim, on_sphere(fast))["throughput"], w_f["throughput"],
              sim_stats(tessim, on_sphere(reflect(fast)))["throughput"], sim_stats(tessim, reflect(fast))["throughput"]]
    check("§11: N = 14 with three lanes of 24 (8) bits at K = 1 (quoted command)", True,
          all(stated_close(a, b) for a, b in zip(q, actual)))
    q = re.search(r"then the same flags to `tessim cosim`\): ([\d ]+) cycles, ([\d ]+) vertices", text).groups()
    check("§11: cycles and vertices of the fast configuration on Wuson", [number(x) for x in q],
          [w_f["cycles"], w_f["vertices_out"]])


def buffer_rows(check, tessim):
    """§10's table of control-point buffers (and the N = 2 figures after it), rerun with the
    command the section gives (each run a fraction of a second)."""
    text = section("docs/results/load-balancing.md", "## 10.")
    near, middle = re.search(r"--camera (eye=[\d.,-]+,target=[\d.,-]+)` or\s+`(eye=[\d.,-]+,target=[\d.,-]+)`",
                             text).groups()
    flags = "--pixels-per-segment 6 --partitioning fractional_odd --normals reflect --gpe-cycles 2".split()
    check("§10: the buffer runs' flags as quoted", True, "`--pixels-per-segment 6 --partitioning fractional_odd\n  "
          "--normals reflect --gpe-cycles 2 --int-blocks 4 --cp-buffers Nb --stats s.json`" in text)
    header = re.search(r"\| Nb \| ([\d |]+)\| full-buffer bound \|", text).group(1)
    buffers = [int(x) for x in header.split("|") if x.strip()]
    run = lambda camera, n, blocks: sim_stats(tessim, ["/usr/share/assimp/models/PLY/Wuson.ply", "--adaptive", "screen",
                                                       "--camera", camera] + flags +
                                              ["--int-blocks", str(blocks), "--cp-buffers", str(n)])
    bad = []
    for label, camera in (("nearest view", near), ("middle view", middle)):
        cells = re.search(rf"\| {label}, cycles per vertex \| ([\d. |]+)\|\n", text).group(1).split("|")
        cells = [c.strip() for c in cells if c.strip()]
        stats = [run(camera, n, 4) for n in buffers]
        actual = [st["cycles_per_vertex"] for st in stats] + [stats[0]["analytic"]["varying"]["full_buffer_cycles_per_vertex"]]
        bad += [f"{label} column {i}" for i, (c, a) in enumerate(zip(cells, actual)) if not stated_close(c, a)]
    q = re.search(r"\(N = 2: ([\d.]+)\s+to ([\d.]+) against ([\d.]+)\)", text).groups()
    two, eight = run(middle, 2, 2), run(middle, 8, 2)
    actual = [two["cycles_per_vertex"], eight["cycles_per_vertex"], two["analytic"]["varying"]["full_buffer_cycles_per_vertex"]]
    bad += [f"N = 2 figure {i}" for i, (c, a) in enumerate(zip(q, actual)) if not stated_close(c, a)]
    check("§10: control-point buffer table against its runs (cells that disagree)", [], bad)
    near_cpv = [run(near, n, 4)["cycles_per_vertex"] for n in (1, 2, 8)]
    mid_cpv = [run(middle, n, 4)["cycles_per_vertex"] for n in (1, 2, 8)]
    bound = [run(c, 2, 4)["analytic"]["varying"]["full_buffer_cycles_per_vertex"] for c in (near, middle)]
    closed = [100 * (v[1] - v[2]) / (v[1] - b) for v, b in ((near_cpv, bound[0]), (mid_cpv, bound[1]))]
    one = sorted(100 * (v[0] / v[1] - 1) for v in (near_cpv, mid_cpv))
    q = re.search(r"Eight buffers close (\d+) % of the gap at the nearest view and (\d+) % at the middle one .*? one "
                  r"buffer, which makes the TE drain at every patch boundary, costs\s+([\d.]+)–([\d.]+) %", text, re.S).groups()
    check("§10: the gap eight buffers close, and what one buffer costs (its runs)", True,
          stated_close(q[0], closed[0]) and stated_close(q[1], closed[1]) and stated_close(q[2], one[0]) and
          stated_close(q[3], one[1]))


def copies_rows(check, tessim):
    """§13's table of CPG copies on Wuson's adaptive views and its fast-GE figures, rerun with the
    commands the section gives (about 40 runs of a fraction of a second)."""
    text = section("docs/results/load-balancing.md", "## 13.")
    wuson = "/usr/share/assimp/models/PLY/Wuson.ply"
    target = re.search(r"--camera eye=[\d.,-]+,(target=[\d.,-]+)`", text).group(1)
    views = dict(zip(("nearest", "middle", "farthest"),
                     [f"{e},{target}" for e in re.findall(r"(eye=[\d.-]+,[\d.-]+,[\d.-]+),(?:target|…)", text)[:3]]))
    base = "--pixels-per-segment 6 --partitioning integer --int-blocks 2 --gpe-cycles 8 --cp-buffers 4".split()
    check("§13: the copies runs' flags as quoted", True, " ".join(base[:4]) in " ".join(text.split()))
    copies = [int(x) for x in re.search(r"\| CPG \| Mc = (\d+) \| (\d+) \| (\d+) \| (\d+) \|", text).groups()]
    bad = []
    rows = re.findall(r"\| (\w+) view: (\d)x(\d+)(?: \(sequential\))? \| ([^\n]+) \|\n", text)
    check("§13: rows of the CPG copies table", 7, len(rows))
    for view, lanes, bits, cells in rows:
        stated = [c.strip(" *") for c in cells.split("|")]
        for mc, c in zip(copies, stated):
            st = sim_stats(tessim, [wuson, "--adaptive", "screen", "--camera", views[view]] + base +
                           ["--cpg-lanes", lanes, "--cpg-digit-bits", bits, "--cpg-copies", str(mc)])
            if not stated_close(c, st["cycles_per_vertex"]):
                bad.append(f"{view} {lanes}x{bits} Mc = {mc}: {c} against {st['cycles_per_vertex']:.4f}")
    check("§13: CPG copies table against its runs (cells that disagree)", [], bad)
    fast = lambda L, bits, mc, nb=8: sim_stats(tessim, [wuson, "-L", str(L), "--int-blocks", "14", "--te-contexts", "16",
                                                       "--cp-buffers", str(nb), "--gpe-cycles", "1", "--cpg-lanes", "3",
                                                       "--cpg-digit-bits", str(bits), "--cpg-copies", str(mc)])["throughput"]
    q = re.search(r"delivers on Wuson ([\d.]+), ([\d.]+) and ([\d.]+) vertices\s+per cycle at L = 1, 2 and 3 with five "
                  r"copies of 3x24 .*?\s+([\d.]+) / ([\d.]+) / ([\d.]+) with ten copies of the shallow 3x4", text, re.S).groups()
    actual = [fast(L, 24, 5) for L in (1, 2, 3)] + [fast(L, 4, 10) for L in (1, 2, 3)]
    check("§13: fast GE on Wuson, five copies of 3x24 and ten of 3x4 (quoted command)", True,
          all(stated_close(a, b) for a, b in zip(q, actual)))
    row = next(l for l in (ROOT / "docs/results/load-balancing.md").read_text().splitlines()
               if l.startswith("| a fast GPE (K = 1) and light tessellation"))
    floor = re.search(r"≥ ([\d.]+) vertices per cycle at L = 1–3 on Wuson \(§13\)", row).group(1)
    step = 10 ** -len(floor.split(".")[1])
    check(f"What to pick: the fast-GE row's floor at L = 1–3 (the §13 runs, lowest {min(actual):.4f})", True,
          float(floor) <= min(actual) < float(floor) + step)
    q = re.search(r"two buffers hold Wuson to ([\d.]+) vertices per cycle and three or more give ([\d.]+)", text).groups()
    check("§13: five copies of 3x24 at L = 1 with two and three buffers", True,
          stated_close(q[0], fast(1, 24, 5, 2)) and stated_close(q[1], fast(1, 24, 5, 3)))
    q = re.search(r"four copies of 1x2 give ([\d.]+), ([\d.]+)\s+and ([\d.]+) cycles per vertex with 2, 4 and 8 buffers",
                  text).groups()
    far = lambda nb: sim_stats(tessim, [wuson, "--adaptive", "screen", "--camera", views["farthest"]] + base[:-1] +
                               [str(nb), "--cpg-lanes", "1", "--cpg-digit-bits", "2", "--cpg-copies", "4"])["cycles_per_vertex"]
    check("§13: farthest view, four copies of 1x2 with 2, 4 and 8 buffers", True,
          all(stated_close(a, far(nb)) for a, nb in zip(q, (2, 4, 8))))


def latency_picks(check, tessim):
    """§13's "their picks hold at Λ = 3 with registered products": the GE-bound workloads it lists,
    on the sphere of its quoted command, against Λ = 1 (16 runs of a fraction of a second)."""
    text = " ".join(section("docs/results/load-balancing.md", "## 13.").split())
    q = re.search(r"linear normals at K = 6: the same vertices per cycle within ([\d.]+) %, `tessim sim "
                  r"/usr/share/assimp/models/STL/sphereWithHole.stl -L 16 --int-blocks 2 --gpe-cycles 8 --int-latency 3 "
                  r"--cpg-product-reg 1` against `--int-latency 1`", text).group(1)
    sphere = "/usr/share/assimp/models/STL/sphereWithHole.stl"
    # N = 2 at both factors; the others at L = 16, where they are GE-bound (at L = 8, N = 3 and 4 wait
    # for the CPG, whose C grows with the registered products)
    workloads = [(2, v, 8, L, "quadratic") for v in (2, 4) for L in (8, 16)] + \
                [(3, 4, 5, 16, "quadratic"), (4, 4, 4, 16, "quadratic"), (1, 4, 14, 16, "quadratic"),
                 (2, 4, 6, 16, "linear")]
    worst = 0.0
    for n, v, k, L, normals in workloads:
        args = [sphere, "-L", str(L), "--int-blocks", str(n), "--te-contexts", str(v), "--gpe-cycles", str(k),
                "--normals", normals]
        one = sim_stats(tessim, args + ["--int-latency", "1"])["throughput"]
        three = sim_stats(tessim, args + ["--int-latency", "3", "--cpg-product-reg", "1"])["throughput"]
        worst = max(worst, 100 * abs(three / one - 1))
    check(f"§13: Λ = 3 with registered products against Λ = 1 on the GE-bound workloads (worst {worst:.4f} %)", True,
          worst <= float(q) + 0.005)
    row = next(l for l in (ROOT / "docs/results/load-balancing.md").read_text().splitlines()
               if l.startswith("| any workload, ranked per unit of time"))
    stated = re.search(r"Λ = 3 changes no GE-bound pick of the rows above \(within ([\d.]+) %\)", row).group(1)
    check("What to pick: Λ = 3 changes no GE-bound pick (the §13 runs)", True, worst <= float(stated) + 0.005)


def quoted_command_outputs(check, tessim):
    """Figures the pages read off a command's own report: §12's tagged Cinema4D (stpn-import's
    summary) and §15's Nyquist-rule triangles (render's summary line)."""
    text = " ".join(section("docs/results/load-balancing.md", "## 12.").split())
    q = re.search(r"\(Cinema4D: (\d+) crease vertices and (\d+) corners tagged", text).groups()
    with tempfile.TemporaryDirectory() as tmp:
        out = subprocess.run([tessim, "stpn-import", "/usr/share/assimp/models/Collada/Cinema4D.dae", "-o",
                              os.path.join(tmp, "c.ply")], capture_output=True, text=True, check=True).stdout
    tagged = re.search(r"crease vertices\s+\d+: (\d+) tagged", out).group(1)
    corners = re.search(r"corners\s+(\d+) \(theta 1\)", out).group(1)
    check("§12: Cinema4D's tagged crease vertices and corners (stpn-import's summary)", (q[0], q[1]), (tagged, corners))
    text = " ".join(section("docs/results/load-balancing.md", "## 15.").split())
    q = re.search(r"the Nyquist rule's factors \(([\d ]+) triangles, four points per wavelength", text).group(1)
    cmd = re.search(r"`tessim render (Wuson.ply --displace sine [^`]+)` with `-L 2` or `--adaptive nyquist`", text).group(1)
    args = cmd.replace("Wuson.ply", "/usr/share/assimp/models/PLY/Wuson.ply").split() + ["--adaptive", "nyquist"]
    with tempfile.TemporaryDirectory() as tmp:
        out = subprocess.run([tessim, "render"] + args + ["-o", os.path.join(tmp, "a.png")], capture_output=True,
                             text=True, check=True)
    made = re.search(r"(\d+) PN triangles", out.stdout + out.stderr).group(1)
    check("§15: triangles of the Nyquist rule's factors (the quoted render)", number(q), int(made))


def performance_counts(check, tessim):
    """The deterministic figures of docs/results/performance.md (its speeds are measured, not
    checked): the shader-core runs' cycles and K, the chunk bound of the million-triangle mesh, the
    bytes the write benchmark writes, the cycles of the RTL benchmark's workload and of the
    co-simulation, each from `tessim sim` at the quoted flags (each a fraction of a second)."""
    path = "docs/results/performance.md"
    wuson = "/usr/share/assimp/models/PLY/Wuson.ply"
    text = section(path, "### A shader-core geometry engine")
    flat = " ".join(text.split())
    q = re.search(r"Wuson at L = 16 \(([\d ]+) vertices\), `tessim sim Wuson.ply -L 16 --stats S.json ARGS`", flat)
    rows = re.findall(r"^\| `([^`]+)`(?: \(K = ([\d.]+)\))? \| ([\d ]+) \|", text, re.M)
    check("performance.md: rows of the shader-core table", 4, len(rows))
    runs = {args: sim_stats(tessim, [wuson, "-L", "16"] + args.split()) for args, _, _ in rows}
    check("performance.md: vertices of Wuson at L = 16 (the shader-core runs)", [number(q.group(1))],
          sorted({st["vertices_out"] for st in runs.values()}))
    bad = []
    for args, k, cycles in rows:
        st = runs[args]
        if number(cycles) != st["cycles"]:
            bad.append(f"{args}: {cycles} against {st['cycles']}")
        if k and not stated_close(k, st["ge"]["core"]["cycles_per_vertex"]):
            bad.append(f"{args}: K = {k} against {st['ge']['core']['cycles_per_vertex']}")
    check("performance.md: shader-core table's cycles and K against its runs (cells that disagree)", [], bad)
    q = re.search(r"The four-lane core takes ([\d.]+) % more cycles than a fixed K = 8: its K is ([\d.]+)\.", flat).groups()
    four, eight = runs["--ge-core-lanes 4 --ge-core-mhz 200 --unit-mhz 100"], runs["--gpe-cycles 8"]
    check("performance.md: the four-lane core against K = 8 (its runs)", True,
          stated_close(q[0], 100 * (four["cycles"] / eight["cycles"] - 1)) and
          stated_close(q[1], four["ge"]["core"]["cycles_per_vertex"]))
    # The bound per chunk boundary depends on the configuration alone (statistics.md, Chunked runs:
    # F = (C + 3) + S + Λ + 2 with uniform factors), so Wuson at big.ply's flags gives big.ply's.
    text = " ".join(section(path, "## A million-triangle mesh").split())
    q = re.search(r"cycles, \d+ more than the single run \(bound per boundary: (\d+)\)", text).group(1)
    bound = sim_stats(tessim, [wuson, "-L", "16", "--chunks", "2"])["chunks"]["boundary_bound"]["longer"]
    check("performance.md: the bound per chunk boundary at L = 16 (the same flags on Wuson)", int(q), bound)
    text = " ".join(section(path, "## Float reference, binary PLY output").split())
    q = re.search(r"Wuson, L = (\d+), ([\d.]+) MB into `/dev/shm`", text).groups()
    size = 0
    with subprocess.Popen([tessim, "tessellate", wuson, "-L", q[0], "-o", "-"], stdout=subprocess.PIPE,
                          stderr=subprocess.DEVNULL) as proc:
        while block := proc.stdout.read(1 << 20):
            size += len(block)
    check(f"performance.md: megabytes bench_write.py writes ({size} bytes)", True,
          proc.returncode == 0 and stated_close(q[1], size / 1e6))
    text = " ".join(section(path, "## Verilated RTL versus the cycle model").split())
    q = re.search(r"\(CPG-bound workload: (\d+) k cycles;", text).group(1)
    cycles = [sim_stats(tessim, [wuson, "-L", "4", "--int", str(n)])["cycles"] for n in (1, 2, 4)]
    check(f"performance.md: cycles of rtlbench's workload, N = 1, 2, 4 ({cycles})", True,
          all(stated_close(q, c / 1e3) for c in cycles))
    # the co-simulation agrees with the cycle model cycle by cycle, so `tessim sim` at its flags
    # gives its cycles and vertices (the co-simulation itself takes some 6-12 s)
    q = re.search(r"--stall 0.3 ([\d.]+) M cycles, ([\d ]+) vertices, agreed end to end", text).groups()
    st = sim_stats(tessim, [wuson, "--int-blocks", "2", "-L", "8", "--stall", "0.3"])
    check("performance.md: cycles and vertices of the quoted co-simulation (the cycle model at its flags)", True,
          stated_close(q[0], st["cycles"] / 1e6) and number(q[1]) == st["vertices_out"])


def scene_claims(check):
    """docs/scenes.md's sizing paragraph against docs/results/scenes/study.json."""
    doc = json.loads((ROOT / "docs/results/scenes/study.json").read_text())
    text = " ".join(section("docs/scenes.md", "## How the unit is sized").split())
    pick = {(p["scene"], p["gpe_cycles"]): p for p in doc["picks"]}
    rows = lambda scene, k: [r for r in doc["rows"] if r["scene"] == scene and r["gpe_cycles"] == k]
    herd8, herd4, fig8, fig4 = pick[("herd", 8)], pick[("herd", 4)], pick[("figures", 8)], pick[("figures", 4)]
    q = re.search(r"The herd puts ([\d ]+) tessellated vertices into its first frame and ([\d ]+) into its last.*? gives "
                  r"the worst frame in ([\d.]+) ms, ([\d.]+) frames per second, and 60 would take a (\d+) MHz clock; at "
                  r"K = 4, ([\d.]+) frames per second, and (\d+) MHz", text).groups()
    first = rows("herd", 8)[0]
    check("scenes.md: the herd's vertices and its fastest units (study.json)", True,
          number(q[0]) == first["tessellated_vertices"] and number(q[1]) == first["max_tessellated_vertices"] and
          stated_close(q[2], herd8["worst_ms"]) and stated_close(q[3], herd8["fps"]) and
          stated_close(q[4], herd8["clock_mhz_for_60fps"]) and stated_close(q[5], herd4["fps"]) and
          stated_close(q[6], herd4["clock_mhz_for_60fps"]) and not herd8["meets_60fps"] and not herd4["meets_60fps"])
    q = re.search(r"At K = 8 the geometry engine alone needs ([\d.]+) M cycles for the last", text).group(1)
    check("scenes.md: the geometry engine's cycles for the herd's last frame at K = 8", True,
          stated_close(q, 8 * rows("herd", 8)[0]["max_tessellated_vertices"] / 1e6))
    fastest = next(r for r in rows("herd", 8) if r["config"] == herd8["pick"])
    q = re.search(r"the engine's K cycles for the tessellated vertices are (\d+) % of the fastest unit's first frame and "
                  r"(\d+) % of its last", text).groups()
    check("scenes.md: the geometry engine's share of the fastest unit's herd frames (study.json)", True,
          stated_close(q[0], 800 * fastest["tessellated_vertices"] / fastest["frame_cycles"][0]) and
          stated_close(q[1], 800 * fastest["max_tessellated_vertices"] / fastest["frame_cycles"][-1]))
    default = next(r for r in rows("herd", 8) if r["config"] == "N=2 1x1 Λ=1 Nb=2")
    q = re.search(r"it needs ([\d ]+) cycles for the herd's worst frame, ([\d.]+) frames per second at its ([\d.]+) MHz",
                  text).groups()
    check("scenes.md: the default unit on the herd (study.json)", True,
          number(q[0]) == default["worst_cycles"] and stated_close(q[1], default["fps"]) and
          stated_close(q[2], default["clock_mhz"]))
    q = re.search(r"The figures scene \(([\d ]+) tessellated vertices\) is sustained at 60 frames per second by the cheapest "
                  r"unit with registered CPG products at Λ = 3 \(([\d.]+) mm², ([\d.]+) MHz\), at either K", text).groups()
    check("scenes.md: the figures scene's pick (study.json)", True,
          number(q[0]) == rows("figures", 8)[0]["tessellated_vertices"] and fig8["meets_60fps"] and fig4["meets_60fps"]
          and fig8["pick"] == fig4["pick"] and "reg Λ=3" in fig8["pick"] and stated_close(q[1], fig8["area_mm2"])
          and stated_close(q[2], fig8["clock_mhz"]))
    q = re.search(r"idles in the untessellated draws for at most ([\d.]+) % of the herd's frames", text).group(1)
    check("scenes.md: the unit's idle share on the herd (study.json)", True,
          stated_close(q, 100 * max(r["unit_idle_share"] for r in doc["rows"] if r["scene"] == "herd")))


def core_claims(check):
    """load-balancing.md §17 (its table and prose), its summary paragraph and row, and docs/scenes.md's
    paragraph against docs/results/scenes/cores.json and the configurations' clocks."""
    doc = json.loads((ROOT / "docs/results/scenes/cores.json").read_text())
    with open(ROOT / "docs/results/silicon/configurations.csv") as f:
        clocks = [float(r["clock_mhz"]) for r in csv.DictReader(f)]
    pick = {(p["scene"], p["core"]): p for p in doc["picks"]}
    cores = {c["name"]: c for c in doc["cores"]}
    programs = doc["programs"]
    text = " ".join(section("docs/results/load-balancing.md", "## 17.").split())
    q = re.search(r"own clock \(([\d.]+)–([\d.]+) MHz\)", text).groups()
    check("§17: the configurations' clock range (configurations.csv)", True,
          stated_close(q[0], min(clocks)) and stated_close(q[1], max(clocks)))
    q = re.search(r"own work \(transform, normal, one light, the perspective divide\) is (\d+) issue slots", text)
    check("§17: the GE's own program (cores.json)", int(q.group(1)),
          programs["own work (transform, light)"]["vec4"]["slots"])
    rows = table_rows("docs/results/load-balancing.md", "## 17.")
    rows = {name: cells for name, cells in rows.items() if name.split(" — ")[0] in cores}
    check("§17 table: a row per core", sorted(n.split(" — ")[0] for n in rows), sorted(cores))
    for name, cells in rows.items():
        core = cores[name.split(" — ")[0]]
        lanes = re.match(r"(\d+) × (\d+), (\d+) MHz", cells[0]).groups()
        ks = cells[1].split(" / ")
        lo, hi = cells[2].split("–")
        p = pick[("herd", core["name"])]
        check(f"§17 table: the {core['name']} row (cores.json)", True,
              (int(lanes[0]), int(lanes[1]), int(lanes[2])) == (core["lanes"], core["issue"], core["mhz"]) and
              all(stated_close(k, programs[prog][core["name"]]["k"]) for k, prog in
                  zip(ks, ["own work (transform, light)", "+ sine displacement",
                           "+ evaluation of the patch (evaluation gpe)"])) and
              stated_close(lo, p["k_min"]) and stated_close(hi, p["k_max"]))
    simd = cores["simd32"]
    q = re.search(r"give K = ([\d.]+) at a 100 MHz unit, ([\d.]+)–([\d.]+) at the clocks", text).groups()
    check("§17: simd32's K (cores.json)", True,
          stated_close(q[0], programs["own work (transform, light)"]["simd32"]["k"]) and
          stated_close(q[1], pick[("herd", "simd32")]["k_min"]) and stated_close(q[2], pick[("herd", "simd32")]["k_max"]))
    q = re.search(r"noise displacement \((\d+) slots\) stays at K = ([\d.]+) on simd32. With vec4, K = ([\d.]+) at 100", text)
    check("§17: noise displacement and vec4 at 100 MHz (cores.json)", True,
          int(q.group(1)) == programs["+ noise displacement"]["simd32"]["slots"] and
          stated_close(q.group(2), programs["+ noise displacement"]["simd32"]["k"]) and
          stated_close(q.group(3), programs["own work (transform, light)"]["vec4"]["k"]))
    vec4 = cores["vec4"]
    herd = {c: pick[("herd", c)] for c in cores}
    q = re.search(r"with \*\*vec4, two\*\* on both scenes — the herd is bound by the core \(([\d.]+) Mvertices/s: ([\d.]+) "
                  r"frames per second at best, and ([\d.]+) already with N = 2, three CPG lanes and registered products at "
                  r"([\d.]+) MHz\)", text).groups()
    n2 = next(r for r in doc["rows"] if r["scene"] == "herd" and r["core"] == "vec4" and r["config"] == "N=2 3x1 reg Λ=3 Nb=4")
    check("§17: vec4 on the herd (cores.json)", True,
          all(pick[(s_, "vec4")]["int_blocks_needed"] == 2 for s_ in ("herd", "figures")) and
          stated_close(q[0], vec4["lanes"] * vec4["issue"] / programs["own work (transform, light)"]["vec4"]["slots"]
                       * vec4["mhz"]) and stated_close(q[1], herd["vec4"]["best_fps"]) and stated_close(q[2], n2["fps"])
          and stated_close(q[3], n2["clock_mhz"]))
    q = re.search(r"\*\*simd32 or cu64, four\*\* — .*?\(N = (\d), three CPG lanes of radix 16, ([\d.]+) MHz\) gives ([\d.]+) "
                  r"frames per second, .*? which would take ([\d.]+) Mvertices/s, ([\d.]+) vertices per cycle at ([\d.]+) MHz",
                  text).groups()
    wide = [herd["simd32"], herd["cu64"]]
    check("§17: the wide cores on the herd (cores.json)", True,
          all(p["int_blocks_needed"] == 4 and p["pick_int_blocks"] == int(q[0]) and p["pick"] == "N=4 3x4 Λ=1 Nb=2" and
              stated_close(q[1], p["clock_mhz"]) and stated_close(q[2], p["fps"]) and
              stated_close(q[3], p["mvertices_per_s_for_60fps"]) and stated_close(q[4], p["vertices_per_cycle_for_60fps"])
              and stated_close(q[5], p["clock_mhz"]) for p in wide) and
          all(pick[("figures", c)]["int_blocks_needed"] == 4 for c in ("simd32", "cu64")))
    q = re.search(r"The figures scene is sustained at 60 frames per second by the same ([\d.]+) mm² unit \(N = 2, registered "
                  r"CPG products, Λ = 3, ([\d.]+) MHz\) with any of the three cores", text).groups()
    fig = [pick[("figures", c)] for c in cores]
    check("§17: the figures scene's pick for every core (cores.json)", True,
          all(p["meets_60fps"] and p["pick"] == "N=2 1x1 reg Λ=3 Nb=4" and stated_close(q[0], p["area_mm2"]) and
              stated_close(q[1], p["clock_mhz"]) for p in fig))
    check("§17: the FIFO depth (cores.json)", True, f"The cross-clock FIFO holds {doc['fifo']} vertices" in text)
    summary = " ".join(section("docs/results/load-balancing.md", "## Answer in short").split())
    q = re.search(r"K is ([\d.]+)–([\d.]+) for a four-lane vertex shader at (\d+) MHz .*? K falls below ([\d.]+), .*? "
                  r"still ([\d.]+) frames per second on the herd scene, where 60 would take ([\d.]+) vertices per cycle",
                  summary).groups()
    check("Answer in short: where K comes from (cores.json)", True,
          stated_close(q[0], herd["vec4"]["k_min"]) and stated_close(q[1], herd["vec4"]["k_max"]) and
          int(q[2]) == vec4["mhz"] and max(herd["simd32"]["k_max"], herd["cu64"]["k_max"]) < float(q[3]) and
          stated_close(q[4], herd["simd32"]["fps"]) and stated_close(q[5], herd["simd32"]["vertices_per_cycle_for_60fps"]))
    row = next(l for l in (ROOT / "docs/results/load-balancing.md").read_text().splitlines()
               if l.startswith("| a GE that is a wide shader core"))
    q = re.search(r"K < ([\d.]+) at every unit clock measured.*?four-lane core \(K = ([\d.]+)–([\d.]+)\)", row).groups()
    check("What to pick: the wide-core row (cores.json)", True,
          max(herd["simd32"]["k_max"], herd["cu64"]["k_max"]) < float(q[0]) and stated_close(q[1], herd["vec4"]["k_min"])
          and stated_close(q[2], herd["vec4"]["k_max"]))
    limits = " ".join((ROOT / "docs/silicon.md").read_text().split())
    q = re.search(r"a four-lane core at (\d+) MHz gives K = ([\d.]+)–([\d.]+) in the configurations' cycles, a (\d+)-lane one at "
                  r"(\d+) MHz K = ([\d.]+)–([\d.]+);", limits).groups()
    check("silicon.md: the GE on its own clock (cores.json)", True,
          int(q[0]) == vec4["mhz"] and stated_close(q[1], herd["vec4"]["k_min"]) and stated_close(q[2], herd["vec4"]["k_max"])
          and int(q[3]) == simd["lanes"] and int(q[4]) == simd["mhz"] and stated_close(q[5], herd["simd32"]["k_min"])
          and stated_close(q[6], herd["simd32"]["k_max"]))
    scenes = " ".join(section("docs/scenes.md", "## How the unit is sized").split())
    q = re.search(r"\(four lanes at (\d+) MHz; (\d+) lanes at (\d+) MHz; (\d+) lanes at (\d+) MHz\).*?The four-lane core is the "
                  r"herd's limit \(([\d.]+) frames per second at best\) and two INT blocks are enough; with 32 or 64 lanes K "
                  r"is below ([\d.]+), .*? four blocks are needed, and the best herd frame gives ([\d.]+) frames", scenes).groups()
    check("scenes.md: K from a shader core (cores.json)", True,
          [int(x) for x in q[:5]] == [vec4["mhz"], simd["lanes"], simd["mhz"], cores["cu64"]["lanes"], cores["cu64"]["mhz"]]
          and stated_close(q[5], herd["vec4"]["best_fps"]) and max(herd["simd32"]["k_max"], herd["cu64"]["k_max"]) < float(q[6])
          and stated_close(q[7], herd["simd32"]["best_fps"]))


def ge_fair_claims(check):
    """load-balancing.md §15's shader-core lanes, its summary and its row against
    docs/results/ge_lane/costs.json and docs/results/ge/verdict.json."""
    costs = json.loads((ROOT / "docs/results/ge_lane/costs.json").read_text())
    verdict = json.loads((ROOT / "docs/results/ge/verdict.json").read_text())
    lane, issue, fma = costs["ge_shader_lane"], costs["ge_simd_issue"], costs["ge_fma_lane"]
    text = " ".join(section("docs/results/load-balancing.md", "## 15.").split())
    q = re.search(r"\(16 registers per wave, 4 waves\).*?a lane costs ([\d ]+) transistors \(([\d ]+) flip-flops, ([\d ]+) of "
                  r"them the registers\) and the issue logic ([\d ]+), so a lane of a (\d+)-lane SIMD costs ([\d ]+), ([\d.]+) "
                  r"times the bare lane", text).groups()
    core_lane = verdict["core_lane_transistors"]
    check("§15: the shader-core lane's cost (costs.json)", True,
          (lane["regs"], lane["waves"]) == (16, 4) and number(q[0]) == lane["transistors"] and
          number(q[1]) == lane["flip_flops"] and number(q[2]) == lane["register_bits"] and
          number(q[3]) == issue["transistors"] and int(q[4]) == verdict["core_simd"] and
          number(q[5]) == round(core_lane) and stated_close(q[6], core_lane / fma["transistors"]))
    pts = verdict["points"]

    def tally(key, displaced):
        r = [v[key] / v["a"] for v in pts if v["displaced"] == displaced]
        return sum(x < 1 for x in r), len(r), min(r), max(r)

    at = {(v["K"], v["workload"], v["displaced"]): v for v in pts}
    q = re.search(r"on (\d+) of (\d+) points against lanes that run the shader \(lanes / unit ([\d.]+)–([\d.]+)\); and if the "
                  r"GE's own work ran on the lanes too \(the model\), the lanes' lead falls from (\d+)–(\d+) times to "
                  r"([\d.]+)–([\d.]+), and the unit wins (\d+) of (\d+) points \(K = 8, L = 8: ([\d.]+) against ([\d.]+)\)",
                  text).groups()
    s1, c2, s2 = tally("s1", False), tally("c2", False), tally("s2", False)
    k8 = at[(8, "L=8", False)]
    check("§15: the verdict without displacement, shader-core lanes (verdict.json)", True,
          int(q[0]) == s1[0] and int(q[1]) == s1[1] and stated_close(q[2], s1[2]) and stated_close(q[3], s1[3]) and
          stated_close(q[4], c2[2]) and stated_close(q[5], c2[3]) and stated_close(q[6], s2[2]) and
          stated_close(q[7], s2[3]) and int(q[8]) == s2[0] and int(q[9]) == s2[1] and stated_close(q[10], k8["s2"])
          and stated_close(q[11], k8["a"]))
    q = re.search(r"With the sine the lanes still win everywhere\*\*, by ([\d.]+)–([\d.]+) times instead of ([\d.]+)–([\d.]+) "
                  r"\(K = 8, L = 8: ([\d.]+) against ([\d.]+) with (\d+) lanes\)", text).groups()
    s1d, c1d = tally("s1", True), tally("c1", True)
    k8d = at[(8, "L=8", True)]
    check("§15: the verdict with the sine, shader-core lanes (verdict.json)", True,
          s1d[0] == 0 and stated_close(q[0], s1d[2]) and stated_close(q[1], s1d[3]) and stated_close(q[2], c1d[2]) and
          stated_close(q[3], c1d[3]) and stated_close(q[4], k8d["s1"]) and stated_close(q[5], k8d["a"]) and
          int(q[6]) == k8d["core_lanes"])
    q = re.search(r"LUT RAM \((\d+) flip-flops, ([\d ]+) LUTs against the bare lane's ([\d ]+)\)", text).groups()
    check("§15: the lanes on Xilinx (costs.json)", True,
          int(q[0]) == lane["xilinx"]["flip_flops"] and number(q[1]) == lane["xilinx"]["luts"] and
          number(q[2]) == fma["xilinx"]["luts"])
    summary = " ".join(section("docs/results/load-balancing.md", "## Answer in short").split())
    q = re.search(r"operand network and share of the issue logic: ([\d.]+) times a bare lane\), the lanes' lead with displacement "
                  r"shrinks to ([\d.]+)–([\d.]+) times, and without it the unit wins (\d+) of (\d+) points", summary).groups()
    check("Answer in short: shader-core lanes (verdict.json)", True,
          stated_close(q[0], core_lane / fma["transistors"]) and stated_close(q[1], s1d[2]) and
          stated_close(q[2], s1d[3]) and int(q[3]) == s1[0] and int(q[4]) == s1[1])
    row = next(l for l in (ROOT / "docs/results/load-balancing.md").read_text().splitlines()
               if l.startswith("| a GE that displaces"))
    q = re.search(r"lanes costed as a shader core's, ([\d.]+)–([\d.]+) times \(([\d.]+) against ([\d.]+)\)", row).groups()
    check("What to pick: a GE that displaces, shader-core lanes (verdict.json)", True,
          stated_close(q[0], s1d[2]) and stated_close(q[1], s1d[3]) and stated_close(q[2], k8d["s1"]) and
          stated_close(q[3], k8d["a"]))


def run_checks(tessim: str, check, cached: bool = False):
    """Every check of this file; `cached` keeps the simulated runs' statistics between calls (in
    the build's temporary directory) for claims.py's listing."""
    global SIM_CACHE
    if cached:
        SIM_CACHE = Path(tempfile.gettempdir()) / "tessim-doc-claims-cache"
    mutants = json.loads((ROOT / "scripts/mutants/mutants.json").read_text())["mutants"]
    check("mutants in the campaign", int(claim("docs/verification.md", r"The campaign holds (\d+) mutants")),
          len(mutants))
    builds = json.loads((ROOT / "rtl/builds.json").read_text())["builds"]
    check("Verilated models CI builds", WORDS[claim("docs/verification.md", r"\((\w+) Verilated models\)")],
          len(builds))
    runs = subprocess.run([sys.executable, str(ROOT / "scripts/bad_input_campaign.py"), "--tessim", tessim,
                           "--count"], capture_output=True, text=True, check=True).stdout.strip()
    check("runs of the bad-input campaign", int(claim("docs/verification.md", r"runs `tessim` (\d+) times")),
          int(runs))
    mutant_rounds(check)
    sweep_points(check)
    coverage_bins(check, tessim)
    cpg_matrix_builds(check)
    silhouette_fair(check)
    load_balancing_claims(check)
    cpg_targets(check, tessim)
    buffer_rows(check, tessim)
    copies_rows(check, tessim)
    latency_picks(check, tessim)
    quoted_command_outputs(check, tessim)
    performance_counts(check, tessim)
    scene_claims(check)
    core_claims(check)
    ge_fair_claims(check)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--tessim", required=True)
    a = ap.parse_args()
    failures = []

    def check(what, stated, actual):
        print(f"{what}: docs say {stated}, data has {actual}")
        if stated != actual:
            failures.append(what)

    global re
    recorder = claims.Recorder()
    re = recorder
    run_checks(os.path.abspath(a.tessim), check)
    docs = claims.load_docs()
    claim_failures = claims.check_claim_files(docs)
    recorder.apply(docs)
    for f in claim_failures:
        print(f"claims: {f}", file=sys.stderr)
    print(claims.summary(docs))
    problems = claims.ratchet(docs)
    for problem in problems:
        print(f"claims: {problem}", file=sys.stderr)
    if failures:
        print("doc_claims_test: stale: " + ", ".join(failures), file=sys.stderr)
    if claim_failures:
        print(f"doc_claims_test: {len(claim_failures)} claims disagree with their data", file=sys.stderr)
    if problems:
        print(f"doc_claims_test: {len(problems)} numbers outside docs/results/claims/pending.json are neither checked "
              "nor labelled (list them: /usr/bin/python3 tests/scripts/claims.py --uncovered)", file=sys.stderr)
    return 1 if failures or claim_failures or problems else 0

if __name__ == "__main__":
    sys.exit(main())
