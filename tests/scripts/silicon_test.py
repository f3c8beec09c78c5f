#!/usr/bin/python3
"""Properties of the silicon cost flow (scripts/silicon.py, docs/silicon.md):

1. A record's key changes with the library: a copy of the Liberty file with one cell's area
   changed misses every record; the same library gives the same key.
2. The figures come from the library: mapping the same record (the CPG's divider) on a copy with
   one cell's area changed changes the area by that cell's count times the change, and a copy
   with the flip-flop's clock-to-output delay tripled lengthens the worst register-to-register path.
3. A mapped record's worst register-to-register path is named by registers of the RTL, and the
   boundary paths use the tags the hierarchy composition joins.
4. The committed records compose the default configuration: the unit's area is the records' areas
   times their instance counts, its clock is at least every record's own worst path, the
   critical path is named by registers at both ends, and the stored composed result is what the
   records compose now.
5. OpenSTA's endpoint reports are read as written (a unit of the parser).
"""

import re
import sys
import shutil
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "scripts"))
import silicon  # noqa: E402

failures = []


def check(what, ok, detail=""):
    print(f"{'ok  ' if ok else 'FAIL'} {what}{': ' + detail if detail and not ok else ''}")
    if not ok:
        failures.append(what)


def cell_body(text, cell):
    m = re.search(rf"^\s*cell\s*\(\s*{cell}\s*\)\s*\{{.*?(?=^\s*cell\s*\()", text, re.M | re.S)
    return m.start(), m.end()


def with_area(text, cell, area):
    start, end = cell_body(text, cell)
    body = re.sub(r"^(\s*area\s*:\s*)[\d.]+", lambda m: f"{m.group(1)}{area}", text[start:end], count=1, flags=re.M)
    return text[:start] + body + text[end:]


def with_slower_clock_to_q(text, cell, factor):
    """The cell's cell_rise / cell_fall tables (its clock-to-output delay) times `factor`."""
    start, end = cell_body(text, cell)

    def scale(m):
        numbers = re.sub(r"[\d.]+(?:e[+-]?\d+)?", lambda n: f"{float(n.group(0)) * factor:.6f}", m.group(2))
        return m.group(1) + numbers

    body = re.sub(r"(cell_(?:rise|fall)\s*\(\w+\)\s*\{.*?values\s*\()(.*?)(\))",
                  lambda m: scale(m) + m.group(3), text[start:end], flags=re.S)
    return text[:start] + body + text[end:]


def divider(lib, versions):
    modules, _, counts, jobs = silicon.plan({}, lib, versions)
    name = next(n for n in counts if modules[n].base == "tess_div")
    text, instances, _ = jobs[name]
    return name, text, instances


def main():
    versions = silicon.tool_versions()
    original = silicon.LIBERTY.read_text()
    with tempfile.TemporaryDirectory(prefix="silicon-test-") as tmp:
        tmp = Path(tmp)
        lib = silicon.Library(silicon.LIBERTY, tmp / "lib0")
        (tmp / "lib0").mkdir(exist_ok=True)
        nand_area = lib.cells["NAND2X1"]["area"]
        check("a cell the Liberty gives no area takes its LEF footprint (OSU018's LATCH: 5.6 x 10 um)",
              lib.area_from_lef == ["LATCH"] and abs(lib.cells["LATCH"]["area"] - 56.0) < 1e-9,
              str(lib.area_from_lef))
        bigger = tmp / "bigger.lib"
        bigger.write_text(with_area(original, "NAND2X1", nand_area + 8))
        shutil.copy(silicon.LIBERTY.with_suffix(".lef"), bigger.with_suffix(".lef"))
        (tmp / "lib1").mkdir()
        lib_bigger = silicon.Library(bigger, tmp / "lib1")
        check("the changed copy changes NAND2X1's area only",
              lib_bigger.cells["NAND2X1"]["area"] == nand_area + 8
              and all(lib_bigger.cells[c] == v for c, v in lib.cells.items() if c != "NAND2X1"))

        name, text, instances = divider(lib, versions)
        same = silicon.record_key(text, silicon.Library(silicon.LIBERTY, tmp / "lib0"), versions)
        check("the same library gives the same record key", silicon.record_key(text, lib, versions) == same)
        check("a library with one cell's area changed misses the record",
              silicon.record_key(text, lib_bigger, versions) != same)

        results = {}
        for tag, library in (("original", lib), ("bigger", lib_bigger)):
            work = tmp / f"map-{tag}"
            work.mkdir()
            results[tag] = silicon.map_record(library, name, text, instances, work)
        a, b = results["original"], results["bigger"]
        nands = a["cell_counts"].get("NAND2X1", 0)
        area_a = a["area_um2"]["comb"] + a["area_um2"]["seq"]
        area_b = b["area_um2"]["comb"] + b["area_um2"]["seq"]
        check("the divider maps to NAND2X1 cells", nands > 0, str(a["cell_counts"]))
        if b["cell_counts"] == a["cell_counts"]:
            check("one cell's area changed changes the record's area by its count times the change",
                  abs(area_b - area_a - 8 * nands) < 1e-6, f"{area_a} -> {area_b}, {nands} NAND2X1")
        else:  # ABC mapped differently: the area must still be the changed library's cell areas
            expected = sum(n * lib_bigger.cells[c]["area"] for c, n in b["cell_counts"].items())
            check("the record's area is its cells' areas in the changed library", abs(area_b - expected) < 1.0,
                  f"{area_b} against {expected}")
        check("...and the area is larger", area_b > area_a, f"{area_a} -> {area_b}")

        slower = tmp / "slower.lib"
        slower.write_text(with_slower_clock_to_q(original, "DFFPOSX1", 3.0))
        (tmp / "lib2").mkdir()
        lib_slower = silicon.Library(slower, tmp / "lib2")
        work = tmp / "map-slower"
        work.mkdir()
        c = silicon.map_record(lib_slower, name, text, instances, work)
        check("a slower flip-flop lengthens the worst register-to-register path",
              c["worst"]["ns"] > a["worst"]["ns"] + 0.05, f"{a['worst']['ns']} -> {c['worst']['ns']} ns")

        w = a["worst"]
        regs = set(re.findall(r"\b(\w+_q)\b", (ROOT / "rtl" / "tess_div.sv").read_text()))
        named = [x for x in (w["from"], w["to"]) if x and re.sub(r"\[\d+\]$", "", x).split(".")[-1] in regs]
        check("the worst path runs between registers of tess_div.sv, named as in the RTL",
              w["ns"] > 0 and len(named) == 2, str(w))
        tags = {t for p in a["paths"] for t in p[:2]}
        check("boundary paths use the composition's tags",
              tags and all(t == "reg" or t.startswith(("in:", "out:", "box:")) for t in tags), str(sorted(tags)[:6]))
        check("no boundary path starts at the untimed reset", not any(t == "in:rst_ni" for t in tags))

    try:
        result = silicon.cost({}, require_cached=True)
    except silicon.SiliconError as e:
        check("the committed records compose the default configuration", False, str(e))
        result = None
    if result:
        unit = result["blocks"]["tess_unit"]
        records = {r["key"]: r for r in result["records"]}
        summed = sum(r["area_um2"] * r["instances"] for r in records.values())
        check("the unit's area is the records' areas times their instances", abs(summed - unit["area_um2"]) < 1.0,
              f"{summed} against {unit['area_um2']}")
        deepest = max(r["worst_ns"] for r in records.values())
        check("the unit's clock is no shorter than any record's own worst path", unit["clock_ns"] >= deepest,
              f"{unit['clock_ns']} < {deepest}")
        ends = unit["critical_path_ends"]
        check("the critical path is named by registers at both ends",
              ends and "(a register)" not in ends["from"] + ends["to"], str(ends))
        check("clock in MHz is 1000 / clock in ns", abs(result["clock_mhz"] * unit["clock_ns"] - 1000) < 0.1)
        lib = silicon.library()
        fresh = silicon.compose_configuration({}, lib, versions, silicon.CACHE, ROOT / "rtl", 1, True, None)
        check("the stored composed result is what the records compose now",
              (fresh["area_mm2"], fresh["clock_ns"], fresh["blocks"]["tess_unit"]["critical_path_ends"])
              == (result["area_mm2"], result["clock_ns"], unit["critical_path_ends"]),
              f"{fresh['area_mm2']} mm2 {fresh['clock_ns']} ns against {result['area_mm2']} mm2 {result['clock_ns']} ns")

    report = """
Endpoint                                Required  Actual   Slack
------------------------------------------------------------------
res_o[23] (output)                     100.0000    6.5060   93.4940 (MET)
_1234_/D (DFFPOSX1)                     99.8385    0.3389   99.4996 (MET)
"""
    check("OpenSTA's endpoint report is read as period - slack",
          silicon.parse_ends(report) == [("res_o[23]", 6.506), ("_1234_/D", 0.5004)], str(silicon.parse_ends(report)))
    if failures:
        print(f"{len(failures)} failed")
        return 1
    print("all passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
