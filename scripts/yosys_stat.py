#!/usr/bin/python3
"""The one reader of Yosys 0.23's reports for the cost scripts: `stat` (cells by type),
`stat -tech cmos` (transistors) and `ltp -noff` (logic depth), as the generic flow writes them
with `tee -q -o FILE` (docs/rtl.md, Synthesis). Read by scripts/yosys_cost.py, scripts/synth.sh,
scripts/block_cost.sh and scripts/ge_lane_cost.sh.

    yosys_stat.py generic CELLS CMOS LTP   prints: cells flip-flops transistors depth
    yosys_stat.py xilinx STAT              prints: LUTs flip-flops DSPs CARRY4s MUXFs SRLs

one line, separated by spaces, for `read` in a shell script; transistors end in + when Yosys
counted some cells as unknown (a lower bound), and a figure missing from its report is -.
"""
import re
import sys
from pathlib import Path

FLOP_CELL = re.compile(r"\$_(S?DFF|DFFE|SDFFE|SDFFCE|ALDFF|DFFSR|DLATCH)")
XILINX_FIGURES = ("lut", "ff", "dsp", "carry4", "muxf", "srl")


def cell_table(text):
    """`stat` report -> (number of cells, {cell type: count}). Flattened designs have one module;
    with several, the count is the last module's and the table the union of all."""
    cells, total = {}, None
    for line in text.splitlines():
        m = re.match(r"\s+Number of cells:\s+(\d+)", line)
        if m:
            total = int(m.group(1))
            continue
        m = re.match(r"\s+(\S+)\s+(\d+)$", line)
        if m and total is not None:
            cells[m.group(1)] = int(m.group(2))
    return total, cells


def flops(cells):
    """Flip-flops and latches among a cell table's generic cells."""
    return sum(v for k, v in cells.items() if FLOP_CELL.match(k))


def transistors(text):
    """`stat -tech cmos` report -> (transistors or None, exact: no cell counted as unknown)."""
    t = re.search(r"Estimated number of transistors:\s+(\d+)(\+?)", text)
    return (int(t.group(1)), t.group(2) == "") if t else (None, False)


def depth(text):
    """`ltp -noff` report -> the longest topological path in gates, or None."""
    m = re.search(r"Longest topological path in .* \(length=(\d+)\)", text)
    return int(m.group(1)) if m else None


def generic(cells_text, cmos_text, ltp_text):
    """The generic flow's figures: cells, flops, transistors, transistors_exact, depth (None when a
    report lacks its line)."""
    total, cells = cell_table(cells_text)
    count, exact = transistors(cmos_text)
    return {"cells": total, "flops": flops(cells), "transistors": count, "transistors_exact": exact,
            "depth": depth(ltp_text)}


def xilinx(cells):
    """`synth_xilinx` cell table -> LUTs, flip-flops, DSP48s, CARRY4s, MUXFs, SRLs."""
    return {
        "lut": sum(v for k, v in cells.items() if re.match(r"LUT\d$", k)),
        "ff": sum(v for k, v in cells.items() if re.match(r"FD[A-Z]*$", k)),
        "dsp": sum(v for k, v in cells.items() if k.startswith("DSP48")),
        "carry4": cells.get("CARRY4", 0),
        "muxf": sum(v for k, v in cells.items() if k.startswith("MUXF")),
        "srl": sum(v for k, v in cells.items() if k.startswith("SRL")),
    }


def main(argv):
    def text(path):
        return Path(path).read_text()

    def shown(x):
        return "-" if x is None else str(x)

    try:
        if len(argv) == 4 and argv[0] == "generic":
            g = generic(text(argv[1]), text(argv[2]), text(argv[3]))
            count = "-" if g["transistors"] is None else f"{g['transistors']}{'' if g['transistors_exact'] else '+'}"
            print(shown(g["cells"]), g["flops"], count, shown(g["depth"]))
            return 0
        if len(argv) == 2 and argv[0] == "xilinx":
            x = xilinx(cell_table(text(argv[1]))[1])
            print(" ".join(str(x[k]) for k in XILINX_FIGURES))
            return 0
    except OSError as e:
        print(f"yosys_stat.py: error: {e}", file=sys.stderr)
        return 1
    print(__doc__.strip(), file=sys.stderr)
    return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
