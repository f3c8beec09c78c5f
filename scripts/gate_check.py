#!/usr/bin/python3
"""Cross-check of the energy flow's activity model on one record instance (docs/silicon.md, Energy):
a gate-level, zero-delay simulation of the mapped netlist driven cycle by cycle from an RTL
waveform, against the propagation scripts/energy.py uses, both priced from the library's tables.

    gate_check.py --tessim BIN --instance PATH [--window START:END] [--json OUT]

BIN co-simulates Wuson at L = 8 (quadratic normals, K = 8) on its default RTL build and writes the
window of cycles as a VCD (`tessim cosim --wave`). The record instance PATH (e.g.
u_te/g_int[0].u_int) is mapped as in scripts/energy.py. Its sources (input ports and flip-flop
outputs) take their RTL values in every cycle of the window; every combinational cell is then
evaluated over all cycles at once (numpy, one truth-table lookup per cell), which counts each net's
changes between consecutive cycles exactly, with the inputs' real correlations and reconvergent
fan-out but no glitches. The propagation gets each source's probability of 1 and change rate and
treats cell inputs as independent; the difference of the two data energies is what independence
costs. A third figure gives every source probability 1/2, as toggle counts alone would.
"""

import argparse
import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import cost_records  # noqa: E402
import energy  # noqa: E402
import gate_activity  # noqa: E402
import silicon  # noqa: E402

WORKLOAD = energy.WORKLOADS["wuson_l8"][0]


def read_vcd(path, prefix, clock):
    """{signal name relative to the scope `prefix` ("a_i", "g_stage_mid[2].q", "g_div[0].u_div.res_o"):
    ([values, one int per cycle], width)} of every variable in `prefix` and its sub-scopes, sampled
    in each cycle (the values before each rising edge of `clock`)."""
    scope = []
    ids = {}      # id code -> (name, width) of the variables under prefix
    clock_id = None
    with open(path, encoding="latin-1") as f:
        for line in f:
            if line.startswith("$enddefinitions"):
                break
            parts = line.split()
            if not parts:
                continue
            if parts[0] == "$scope":
                scope.append(parts[2])
            elif parts[0] == "$upscope":
                scope.pop()
            elif parts[0] == "$var":
                width, code, name = int(parts[2]), parts[3], parts[4]
                full = ".".join(scope + [name])
                if full == clock:
                    clock_id = code
                if full.startswith(prefix + ".") and parts[1] != "parameter":
                    ids.setdefault(code, []).append((full[len(prefix) + 1:], width))
        if clock_id is None:
            raise SystemExit(f"gate_check.py: error: no clock {clock} in {path}")
        value = {code: 0 for code in ids}
        samples = {code: [] for code in ids}
        clk = 0
        block = []

        def flush():
            nonlocal clk
            rises = any(code == clock_id and v == "1" for code, v in block)
            if rises and clk == 0:
                for code in ids:
                    samples[code].append(value[code])
            for code, v in block:
                if code == clock_id:
                    clk = 1 if v == "1" else 0
                elif code in value:
                    value[code] = int(v.replace("x", "0").replace("z", "0"), 2)
            block.clear()

        for line in f:
            c = line[0]
            if c == "#":
                flush()
            elif c == "b":
                v, code = line[1:].split()
                if code in value or code == clock_id:
                    block.append((code, v))
            elif c in "01xz":
                code = line[1:].strip()
                if code in value or code == clock_id:
                    block.append((code, c))
        flush()
    out = {}
    for code, names in ids.items():
        for name, width in names:
            out[name] = (samples[code], width)
    return out


def bit_arrays(signals):
    """{netlist bit name ("a_i[3]", "valid_i"): uint8 array over cycles} from sampled signals."""
    out = {}
    for name, (values, width) in signals.items():
        arr = np.array(values, dtype=object)
        if width == 1:
            out[name] = np.array([int(v) & 1 for v in values], dtype=np.uint8)
            out[name + "[0]"] = out[name]
            continue
        for b in range(width):
            out[f"{name}[{b}]"] = np.array([(int(v) >> b) & 1 for v in arr], dtype=np.uint8)
    return out


def simulate(netlist, tables, sources):
    """{net: uint8 array over cycles} of every net, the sources given."""
    cycles = len(next(iter(sources.values())))
    val = {"1'h0": np.zeros(cycles, np.uint8), "1'h1": np.ones(cycles, np.uint8)}
    val.update(sources)
    for idx in netlist.order:
        ctype, inst, pins = netlist.comb[idx]
        for out, (used, table, _, _) in tables[ctype].items():
            if out not in pins:
                continue
            index = np.zeros(cycles, np.int64)
            for i in used:
                index = index * 2 + val.get(pins.get(i), val["1'h0"])
            val[pins[out]] = np.asarray(table, np.uint8)[index]
    return val


def main(argv):
    ap = argparse.ArgumentParser(prog="gate_check.py", description=__doc__.split("\n\n")[0])
    ap.add_argument("--tessim", required=True)
    ap.add_argument("--instance", default="u_te/g_int[0].u_int")
    ap.add_argument("--window", default="200000:210000")
    ap.add_argument("--json")
    args = ap.parse_args(argv)
    start = time.monotonic()
    lib = silicon.library()
    versions = silicon.tool_versions()
    modules, top, counts, jobs = silicon.plan({}, lib, versions)
    paths = dict(energy.instance_paths(modules, top))
    if args.instance not in paths:
        raise SystemExit(f"gate_check.py: error: no record instance {args.instance}")
    name = paths[args.instance]
    functions = gate_activity.liberty_functions(lib.text)
    tables = gate_activity.cell_tables(functions)
    with tempfile.TemporaryDirectory(prefix="tessim-gate-check-") as tmp:
        tmp = Path(tmp)
        text, boxes, key = jobs[name]
        silicon.write_mapped(lib, name, text, boxes, tmp)
        rec = energy.RecordPower(lib, tmp / "mapped.v", functions, tables, gate_activity.liberty_power(lib.text))
        vcd = tmp / "w.vcd"
        subprocess.run([args.tessim, "cosim", *WORKLOAD, "--variant", "n2", "--wave", str(vcd), "--wave-window",
                        args.window], check=True, capture_output=True)
        prefix = "tess.tess_unit." + args.instance.replace("/", ".")
        signals = read_vcd(vcd, prefix, "tess.tess_unit.clk_i")
        bits = bit_arrays(signals)
        net = rec.netlist
        sources, missing = {}, []
        for b in [b for b in net.input_bits if b != "clk_i"] + [q for _, q in net.flops]:
            name_in_rtl = b
            box = b.split("[")[0]
            if box in rec.boxes:  # a black box's pin: INST.PIN of the record
                name_in_rtl = rec.boxes[box] + b[len(box):]
            if name_in_rtl in bits:
                sources[net.find(b)] = bits[name_in_rtl]
            else:
                missing.append(name_in_rtl)
        if missing:
            raise SystemExit(f"gate_check.py: error: {len(missing)} sources not in the waveform: {missing[:8]}")
        cycles = len(next(iter(sources.values())))
        val = simulate(net, tables, sources)
        exact = {n: (float(v.mean()), float(np.count_nonzero(v[1:] != v[:-1])) / (cycles - 1)) for n, v in val.items()}
        # The flow's propagation gets each source's probability of 1 and change rate; the variant
        # with every probability at 1/2 shows what the probabilities are worth.
        propagated = gate_activity.propagate(net, tables, lambda n: exact[net.find(n)])
        halves = gate_activity.propagate(net, tables, lambda n: (0.5, exact[net.find(n)][1]))
        priced = {k: sum(rec.price(a)[part] for part in ("internal", "switching"))
                  for k, a in (("gate_level", exact), ("propagated", propagated), ("propagated_p_half", halves))}
    comb = [pins[o] for _, _, pins in net.comb for o in ("Y", "YC", "YS") if o in pins]
    mean = {k: round(float(np.mean([a[n][1] for n in comb])), 5)
            for k, a in (("gate_level", exact), ("propagated", propagated), ("propagated_p_half", halves))}
    result = {"instance": args.instance, "record": name, "sources_digest": cost_records.sources_digest(energy.REPO / "rtl"),
              "workload": "wuson_l8", "window": args.window,
              "cycles": cycles, "cells": len(net.cells), "sources": len(sources),
              "data_pj_per_cycle": {k: round(v, 3) for k, v in priced.items()},
              "difference": {k: round(priced[k] / priced["gate_level"] - 1, 4) if priced["gate_level"] else None
                             for k in ("propagated", "propagated_p_half")},
              "mean_net_activity": mean, "seconds": round(time.monotonic() - start)}
    text = json.dumps(result, indent=1) + "\n"
    if args.json:
        Path(args.json).write_text(text)
    sys.stdout.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
