#!/usr/bin/python3
"""Properties of the per-module cost records (scripts/yosys_cost.py, docs/rtl.md Cost method):

1. A record's key depends on its module alone: a comment added to tess_fifo.sv changes no key;
   a real edit of tess_fifo.sv changes the keys of the FIFO records and of nothing else; another
   N or CPG variant shares every record it does not change.
2. The boundary paths of a synthesized record reproduce Yosys's own `ltp -noff` depth.
3. The longest path through the hierarchy joins a parent's paths to its children's at their ports,
   keeps output ports per bit, and finds the path the records imply.
4. Whole-unit figures are the records' figures times their instance counts.
5. scripts/yosys_stat.py, the one reader of Yosys's `stat`, `stat -tech cmos` and `ltp` reports,
   reads their figures (and the command-line form the shell scripts read) from Yosys 0.23's text.
"""

import json
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "scripts"))
import yosys_cost  # noqa: E402
import yosys_stat  # noqa: E402

failures = []


def check(what, ok, detail=""):
    print(f"{'ok  ' if ok else 'FAIL'} {what}{': ' + detail if detail and not ok else ''}")
    if not ok:
        failures.append(what)


def keys_of(rtl_dir, work):
    modules = yosys_cost.elaborate(rtl_dir, {}, work)
    top = yosys_cost.top_name(modules)
    counts = yosys_cost.instance_counts(modules, top)
    return {name: (modules[name].base, yosys_cost.record_key(yosys_cost.record_text(modules, name)[0], "v", True))
            for name in counts}


def test_keys(tmp):
    base = keys_of(ROOT / "rtl", tmp)
    commented = Path(tmp) / "commented"
    shutil.copytree(ROOT / "rtl", commented)
    fifo = commented / "tess_fifo.sv"
    fifo.write_text("// a comment that moves every line of the file\n\n" + fifo.read_text())
    check("a comment in tess_fifo.sv changes no record key", keys_of(commented, tmp) == base)

    edited = Path(tmp) / "edited"
    shutil.copytree(ROOT / "rtl", edited)
    fifo = edited / "tess_fifo.sv"
    text = fifo.read_text()
    # Rename one of the FIFO's registers and add logic: a real change of the elaborated module,
    # which also shifts Yosys's global counter for the automatic names of every module elaborated
    # after it (the TE's for-loop declarations carry that counter in their public names).
    register = re.search(r"\b(\w+_q)\b", text).group(1)
    text = re.sub(rf"\b{register}\b", register + "_renamed", text)
    extra = "  logic unused_extra;\n  assign unused_extra = ^{data_i + 1'b1, data_i - 1'b1, data_i * 3};\n"
    fifo.write_text(text.replace("endmodule", extra + "endmodule"))
    after = keys_of(edited, tmp)
    changed = {base[n][0] for n in base if base[n] != after.get(n)}
    check("an edit of tess_fifo.sv changes the FIFO records' keys and no other",
          changed == {"tess_fifo"}, f"changed: {sorted(changed)}")
    fifo_records = sum(1 for n in base if base[n][0] == "tess_fifo")
    check("the unit has two FIFO records (TRI and VTX widths differ)", fifo_records == 2, str(fifo_records))


def test_records_shared_between_configurations(tmp):
    base = keys_of(ROOT / "rtl", tmp)

    def keys_with(params):
        modules = yosys_cost.elaborate(ROOT / "rtl", params, tmp)
        counts = yosys_cost.instance_counts(modules, yosys_cost.top_name(modules))
        return {(modules[n].base, yosys_cost.record_key(yosys_cost.record_text(modules, n)[0], "v", True))
                for n in counts}

    def differing(params):
        other = keys_with(params)
        return sorted({module for module, key in set(base.values()) ^ other})

    # What Yosys elaborated before a module must not change its record.
    check("another CPG variant changes only the CPG's records, the copies' array that passes it on, and the top",
          differing({"CpgDigitBits": 2}) == ["tess_cpg", "tess_cpg_array", "tess_cpg_edge", "tess_div", "tess_isqrt",
                                             "tess_unit"],
          str(differing({"CpgDigitBits": 2})))
    check("another N changes only the TE's record and the top",
          differing({"IntBlocks": 3}) == ["tess_te", "tess_unit"], str(differing({"IntBlocks": 3})))


def test_paths_match_ltp(tmp):
    modules = yosys_cost.elaborate(ROOT / "rtl", {}, tmp)
    name = next(n for n, m in modules.items() if m.base == "tess_div")
    text, boxes = yosys_cost.record_text(modules, name)
    check("tess_div has no submodule records", boxes == [])
    result = yosys_cost.synthesize_record(name, text, boxes, False, tmp)
    deepest = max(g for _, _, g in result["paths"])
    check("a record's deepest boundary path is Yosys's ltp depth", deepest == result["depth"],
          f"paths {deepest}, ltp {result['depth']}")
    kinds = {src.split(":")[0] for src, _, _ in result["paths"]}
    check("its paths start at inputs and flip-flops", kinds == {"in", "reg"}, str(kinds))

    def pairs(paths):
        return {(a, b, g) for s, t, g in paths for a in yosys_cost.bits_of(s) for b in yosys_cost.bits_of(t)}
    stored = yosys_cost.compress_paths(result["paths"])
    check("stored paths (bit runs as ranges) stand for exactly the measured ones",
          pairs(stored) == pairs(result["paths"]) and len(stored) < len(result["paths"]),
          f"{len(result['paths'])} -> {len(stored)}")
    record = Path(tmp) / "record.json"
    yosys_cost.write_record(record, {"module": "tess_div", "result": result})
    check("a record reads back as written", yosys_cost.read_record(record)["paths"] == stored)


class FakeModule:
    def __init__(self, base, instances):
        self.base = base
        self.instances = instances


def test_composed_depth():
    # parent: input a -> 3 gates -> child c1 port x; child output y bit 0 (5 gates deep from x) and
    # bit 1 (40 gates deep from x); the parent reads y[0] into 7 gates to a register and y[1]
    # into 1 gate to its output. Longest: 3 + 40 + 1 = 44, not 3 + 40 + 7 (y[0] is shallow).
    modules = {"P": FakeModule("parent", {"c1": "C"}), "C": FakeModule("child", {})}
    records = {
        "P": {"paths": [["in:a", "box:c1.x", 3], ["box:c1.y[0]", "reg", 7], ["box:c1.y[1]", "out:o[0]", 1],
                        ["reg", "reg", 20]]},
        "C": {"paths": [["in:x", "out:y[0]", 5], ["in:x", "out:y[1]", 40], ["reg", "out:y[0]", 2]]},
    }
    depth, path = yosys_cost.composed_depth(modules, records, "P")
    check("composed depth follows the bits a parent reads", depth == 44, f"{depth}")
    check("the critical path names the child's ports",
          [p for p, _ in path] == [" in:a", "/c1 in:x", "/c1 out:y[1]", " out:o[0]"], str(path))
    # A second instance of the child deepens nothing, and its paths are its own.
    modules["P"].instances["c2"] = "C"
    records["P"]["paths"] += [["box:c1.y[0]", "box:c2.x", 30], ["box:c2.y[1]", "out:o[1]", 0]]
    depth, _ = yosys_cost.composed_depth(modules, records, "P")
    check("paths chain through two instances", depth == 3 + 5 + 30 + 40, f"{depth}")


def test_compose_sums():
    records = {"A": {"cells": 10, "flops": 2, "transistors": 100, "transistors_exact": True, "depth": 4,
                     "xilinx": {"lut": 5, "ff": 2}},
               "B": {"cells": 3, "flops": 0, "transistors": 30, "transistors_exact": True, "depth": 9,
                     "xilinx": {"lut": 1, "ff": 0}}}
    total = yosys_cost.compose(records, {"A": 1, "B": 4})
    check("figures add over instances", (total["cells"], total["flops"], total["transistors"]) == (22, 2, 220),
          str(total))
    check("Xilinx cells add over instances", total["xilinx"] == {"lut": 9, "ff": 2}, str(total["xilinx"]))


# Yosys 0.23's reports, as `tee -q -o FILE stat` (generic, then synth_xilinx), `stat -tech cmos`
# and `ltp -noff` write them for a flattened module.
STAT_GENERIC = """
20. Printing statistics.

=== tess_fifo ===

   Number of wires:               1203
   Number of wire bits:           2398
   Number of public wires:          12
   Number of public wire bits:     160
   Number of memories:               0
   Number of memory bits:            0
   Number of processes:              0
   Number of cells:               1290
     $_ANDNOT_                     300
     $_DFFE_PP_                    100
     $_DFF_PN0_                      5
     $_MUX_                        800
     $_SDFFCE_PN0P_                  3
     $_XOR_                         82

"""
STAT_CMOS = """
   Number of cells:               1290
     $_DFF_P_                      108
   Estimated number of transistors:      20476+
"""
STAT_LTP = """
24. Executing LTP pass (find longest path).

Longest topological path in tess_fifo (length=17):
    0: \\rd_ptr_q [0]
"""
STAT_XILINX = """
=== tess_fifo ===

   Number of cells:                 79
     CARRY4                          2
     DSP48E1                         1
     FDCE                           10
     FDRE                            4
     LUT2                            7
     LUT6                           20
     MUXF7                           3
     SRL16E                          5
     IBUF                           27
"""


def test_stat_reports(tmp):
    total, cells = yosys_stat.cell_table(STAT_GENERIC)
    check("stat: the number of cells and the table by type", total == 1290 and cells["$_MUX_"] == 800
          and "Number" not in " ".join(cells), str(cells))
    check("stat: flip-flops are the $_DFF/$_SDFF... cells", yosys_stat.flops(cells) == 108,
          str(yosys_stat.flops(cells)))
    check("stat -tech cmos: a count with cells of unknown cost is inexact",
          yosys_stat.transistors(STAT_CMOS) == (20476, False))
    check("stat -tech cmos: an exact count", yosys_stat.transistors(STAT_CMOS.replace("+", "")) == (20476, True))
    check("ltp: the longest path", yosys_stat.depth(STAT_LTP) == 17)
    check("missing lines read as None", yosys_stat.generic("", "", "") ==
          {"cells": None, "flops": 0, "transistors": None, "transistors_exact": False, "depth": None})
    x = yosys_stat.xilinx(yosys_stat.cell_table(STAT_XILINX)[1])
    check("synth_xilinx cells by kind", x == {"lut": 27, "ff": 14, "dsp": 1, "carry4": 2, "muxf": 3, "srl": 5}, str(x))
    files = []
    for name, text in (("cells", STAT_GENERIC), ("cmos", STAT_CMOS), ("ltp", STAT_LTP), ("xil", STAT_XILINX)):
        files.append(Path(tmp) / f"report.{name}")
        files[-1].write_text(text)
    script = str(ROOT / "scripts" / "yosys_stat.py")
    line = subprocess.run([sys.executable, script, "generic", *map(str, files[:3])], capture_output=True,
                          text=True).stdout
    check("command line: cells flip-flops transistors depth", line == "1290 108 20476+ 17\n", repr(line))
    line = subprocess.run([sys.executable, script, "xilinx", str(files[3])], capture_output=True, text=True).stdout
    check("command line: LUTs flip-flops DSPs CARRY4s MUXFs SRLs", line == "27 14 1 2 3 5\n", repr(line))


def main():
    if not shutil.which("yosys"):
        print("yosys_cost_test: yosys not found", file=sys.stderr)
        return 1
    with tempfile.TemporaryDirectory(prefix="yosys-cost-test-") as tmp:
        test_stat_reports(tmp)
        test_keys(tmp)
        test_records_shared_between_configurations(tmp)
        test_paths_match_ltp(tmp)
    test_composed_depth()
    test_compose_sums()
    if failures:
        print(f"yosys_cost_test: {len(failures)} failed", file=sys.stderr)
        return 1
    print("yosys_cost_test: all passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
