#!/usr/bin/python3
"""Properties of the energy flow (scripts/gate_activity.py, scripts/energy.py, docs/silicon.md):

1. Propagation (zero delay, lag one): the library's functions read as truth tables; an inverter
   passes a density on, an XOR of independent inputs changes when exactly one does, an AND at
   probability 1/2 changes with the closed form; on a small netlist without reconvergent fan-out
   the propagated densities equal a zero-delay simulation's toggle counts.
2. The activity path counts toggles: a netlist whose sources never toggle costs its clock alone
   (data energy exactly 0), and its data energy grows with the sources' densities; a net's
   switching energy is 1/2 C V^2 per change with its pins' and the wire-load model's capacitance.
3. The figures follow the library: a Liberty copy with the flip-flop's clock-pin energy doubled
   doubles the clock energy.
4. The committed characterization is the current one: its RTL sources digest and library are
   today's, its clock and area are the silicon flow's for the same configuration, its blocks'
   areas add up to the unit's, one INT block's area lies within 80-150 % of a plain mapping of
   tess_int (synth, dfflibmap, abc -liberty, no delay target), and the records that have a
   gate-level check (scripts/gate_check.py, of today's RTL) are scaled to it.
"""

import json
import random
import re
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "scripts"))
import cost_records  # noqa: E402
import gate_activity  # noqa: E402
import silicon  # noqa: E402
import yosys_cost  # noqa: E402
import yosys_stat  # noqa: E402

failures = []

NETLIST = """\
module rec(clk_i, a_i, b_i, c_i, d_i, e_i, y_o);
  input clk_i;
  input a_i;
  input b_i;
  input c_i;
  input d_i;
  input e_i;
  output y_o;
  wire n1;
  wire n2;
  wire n3;
  wire q;
  XOR2X1 g1 (.A(a_i), .B(b_i), .Y(n1));
  NAND2X1 g2 (.A(n1), .B(c_i), .Y(n2));
  INVX1 g3 (.A(q), .Y(n3));
  DFFPOSX1 r (.CLK(clk_i), .D(n2), .Q(q));
  AOI21X1 g4 (.A(n3), .B(d_i), .C(e_i), .Y(y_o));
endmodule
"""


FANOUT = """\
module rec(a_i, y0_o, y1_o, y2_o, y3_o);
  input a_i;
  output y0_o;
  output y1_o;
  output y2_o;
  output y3_o;
  wire n;
  INVX1 d (.A(a_i), .Y(n));
  INVX1 l0 (.A(n), .Y(y0_o));
  INVX1 l1 (.A(n), .Y(y1_o));
  INVX1 l2 (.A(n), .Y(y2_o));
  INVX1 l3 (.A(n), .Y(y3_o));
endmodule
"""


def check(what, ok, detail=""):
    print(f"{'ok  ' if ok else 'FAIL'} {what}{': ' + detail if detail and not ok else ''}")
    if not ok:
        failures.append(what)


def simulate(netlist, tables, densities, cycles=200000, seed=7):
    """Zero-delay toggles per cycle of every comb output, the sources independent bits at
    probability 1/2 that change between cycles with the given probabilities."""
    rng = random.Random(seed)
    value = {n: rng.random() < 0.5 for n in densities}
    toggles = {}
    prev = None
    for _ in range(cycles):
        for n, d in densities.items():
            if rng.random() < d:
                value[n] = not value[n]
        v = dict(value)
        for idx in netlist.order:
            ctype, inst, pins = netlist.comb[idx]
            for out, (used, table, _, _) in tables[ctype].items():
                index = 0
                for i in used:
                    index = index * 2 + int(v[pins[i]])
                v[pins[out]] = bool(table[index])
        if prev is not None:
            for n, x in v.items():
                if x != prev.get(n):
                    toggles[n] = toggles.get(n, 0) + 1
        prev = v
    return {n: k / (cycles - 1) for n, k in toggles.items()}


def main():
    lib = silicon.library()
    functions = gate_activity.liberty_functions(lib.text)
    tables = gate_activity.cell_tables(functions)
    check("every combinational cell of the library has a truth table",
          all(c in tables for c, f in functions.items() if not f["sequential"]))
    _, d_inv = gate_activity.propagate_cell(tables["INVX1"]["Y"], [0.5], [0.3])
    _, d_xor = gate_activity.propagate_cell(tables["XOR2X1"]["Y"], [0.5, 0.5], [0.1, 0.2])
    p_and, d_and = gate_activity.propagate_cell(tables["AND2X1"]["Y"], [0.5, 0.5], [0.1, 0.2])
    check("an inverter passes its density on", abs(d_inv - 0.3) < 1e-12, str(d_inv))
    check("an XOR changes when exactly one input does", abs(d_xor - (0.1 * 0.8 + 0.2 * 0.9)) < 1e-12, str(d_xor))
    # AND at p = 1/2: P(before 1) = P(both 1) = (0.5 - d1/2)(0.5 - d2/2) + ... closed form by cases
    before_after = {(a, b): (0.5 - 0.05 if a == b else 0.05) for a in (0, 1) for b in (0, 1)}
    before_after2 = {(a, b): (0.5 - 0.1 if a == b else 0.1) for a in (0, 1) for b in (0, 1)}
    exact = sum(before_after[(a1, b1)] * before_after2[(a2, b2)]
                for a1 in (0, 1) for b1 in (0, 1) for a2 in (0, 1) for b2 in (0, 1) if (a1 & a2) != (b1 & b2))
    check("an AND's change probability is the enumeration's", abs(d_and - exact) < 1e-12 and abs(p_and - 0.25) < 1e-12,
          f"{d_and} against {exact}")
    mux = tables["MUX2X1"]["Y"]
    check("MUX2X1 reads as !(S A + !S B)", mux[0] == ["A", "B", "S"] and mux[1] == [1, 1, 0, 1, 1, 0, 0, 0], str(mux[:2]))

    net = gate_activity.Netlist(NETLIST, functions)
    sources = {"a_i": 0.3, "b_i": 0.1, "c_i": 0.2, "d_i": 0.4, "e_i": 0.15, "q": 0.25}
    act = gate_activity.propagate(net, tables, lambda n: (0.5, sources[n]))
    print("     densities:", {n: round(act[n][1], 4) for n in ("n1", "n2", "n3", "y_o")})
    sim = simulate(net, tables, sources)
    worst = max(abs(act[n][1] - sim.get(n, 0.0)) for n in ("n1", "n2", "n3", "y_o"))
    check("propagated densities match a zero-delay simulation", worst < 0.01,
          ", ".join(f"{n} {act[n][1]:.4f}/{sim.get(n, 0):.4f}" for n in ("n1", "n2", "n3", "y_o")))

    power = gate_activity.liberty_power(lib.text)
    with tempfile.TemporaryDirectory(prefix="energy-test-") as tmp:
        tmp = Path(tmp)
        still = gate_activity.price(net, gate_activity.propagate(net, tables, lambda n: (0.5, 0.0)), power)
        busy = gate_activity.price(net, act, power)
        double = gate_activity.price(net, gate_activity.propagate(net, tables, lambda n: (0.5, min(1.0, 2 * sources[n]))),
                                     power)
        data1 = busy["internal"] + busy["switching"]
        data2 = double["internal"] + double["switching"]
        check("still sources: the clock alone", still["internal"] == 0.0 and still["switching"] == 0.0
              and still["clock"] > 0, str(still))
        check("the clock is the flip-flop's clock pin up and down, whatever the data", busy["clock"] == still["clock"])
        check("toggling sources add data energy", data1 > 0, f"{data1}")
        check("more toggling costs more data energy", data2 > data1 * 1.2, f"{data1} -> {data2}")
        # A net's switching energy is 1/2 C V^2 per change: an inverter driving four inverters,
        # C = four input pins and the wire-load model's 100 um for fan-out 4.
        fan = gate_activity.Netlist(FANOUT, functions)
        e = gate_activity.price(fan, {fan.find("a_i"): (0.5, 0.0), fan.find("n"): (0.5, 0.5)}, power)
        c = 4 * power["INVX1"]["caps"]["A"] + 0.0002 * 100
        check("a net's switching energy is 1/2 C V^2 per change", abs(e["switching"] - 0.5 * 0.5 * c * 1.8 ** 2) < 1e-9,
              f"{e['switching']} against {0.5 * 0.5 * c * 1.8 ** 2}")

        text = silicon.LIBERTY.read_text()
        m = re.search(r"(cell \(DFFPOSX1\).*?pin\(CLK\).*?internal_power\(\) \{)(.*?)(\n    \}\n)", text, re.S)
        scaled = re.sub(r"values \(\"([^\"]*)\"\)",
                        lambda v: 'values ("' + ", ".join(f"{2 * float(x):.6f}" for x in v.group(1).split(",")) + '")',
                        m.group(2))
        (tmp / "clk2.lib").write_text(text[:m.start(2)] + scaled + text[m.end(2):])
        (tmp / "lib2").mkdir()
        lib2 = silicon.Library(tmp / "clk2.lib", tmp / "lib2")
        still2 = gate_activity.price(net, gate_activity.propagate(net, tables, lambda n: (0.5, 0.0)),
                                     gate_activity.liberty_power(lib2.text))
        check("a library with the flip-flop's clock-pin energy doubled doubles the clock energy",
              abs(still2["clock"] - 2 * still["clock"]) < 1e-9, f"{still['clock']} -> {still2['clock']}")
        check("...and changes the library's digest (another key)", lib2.digest != lib.digest)

        files = sorted((ROOT / "docs" / "results" / "silicon" / "energy").glob("*.json"))
        check("a characterization is committed", bool(files))
        for path in files:
            c = json.loads(path.read_text())
            name = path.name
            check(f"{name}: of today's RTL", c["sources_digest"] == cost_records.sources_digest(ROOT / "rtl"))
            check(f"{name}: of today's library", c["library_sha256"] == lib.digest)
            s = silicon.cost(c["params"], require_cached=True)
            check(f"{name}: the silicon flow's clock", abs(s["clock_ns"] - c["clock_ns"]) < 1e-9,
                  f"{c['clock_ns']} against {s['clock_ns']}")
            total = sum(b["area_um2"] for b in c["blocks"])
            check(f"{name}: the blocks' areas add up to the unit's", abs(total / 1e6 - s["area_mm2"]) < 1e-4,
                  f"{total / 1e6} against {s['area_mm2']}")
            ints = [b for b in c["blocks"] if re.fullmatch(r"int\d+", b["name"])]
            check(f"{name}: one INT block per INT block of the configuration",
                  len(ints) == c["params"].get("IntBlocks", 2))
            if ints:
                plain = plain_int_area(lib, c["params"], tmp)
                ratio = ints[0]["area_um2"] / plain
                print(f"     INT block {ints[0]['area_um2'] / 1e6:.4f} mm2, plain mapping {plain / 1e6:.4f} mm2 "
                      f"({100 * ratio:.1f} %)")
                check(f"{name}: an INT block's area is 80-150 % of a plain mapping of tess_int", 0.8 <= ratio <= 1.5,
                      f"{ratio:.3f}")
            checks = [json.loads(g.read_text()) for g in sorted((ROOT / "docs" / "results" / "silicon" / "gate_check").glob("*.json"))]
            for g in checks:
                check(f"gate check of {g['instance']}: of today's RTL", g["sources_digest"] == c["sources_digest"])
            scales = {re.sub(r"^.*\\", "", g["record"]): g["data_pj_per_cycle"]["gate_level"] / g["data_pj_per_cycle"]["propagated"]
                      for g in checks}
            check(f"{name}: the records with a gate-level check are scaled to it",
                  set(c.get("gate_level_scales", {})) == set(scales)
                  and all(abs(c["gate_level_scales"][k] - v) < 1e-3 for k, v in scales.items()),
                  f"{c.get('gate_level_scales')} against {scales}")
            for v in c["validation"]:
                check(f"{name}: {v['workload']} {v['block']} has a direct and a predicted energy",
                      v["direct_pj"] >= 0 and v["predicted_pj"] >= 0)
    print("FAILED:" if failures else "all passed", *failures, sep="\n  " if failures else "")
    return 1 if failures else 0


def plain_int_area(lib, params, tmp):
    """tess_int of the configuration mapped with no delay target and no load constraint."""
    versions = silicon.tool_versions()
    modules, _, counts, jobs = silicon.plan(params, lib, versions)
    name = next(n for n in counts if modules[n].base == "tess_int")
    work = tmp / "plain"
    work.mkdir(exist_ok=True)
    (work / "job.il").write_text(jobs[name][0])
    (work / "map.ys").write_text(f"read_rtlil {work / 'job.il'}\nhierarchy -top {name}\nflatten\nsynth -top {name}\n"
                                 f"dfflibmap -liberty {lib.path}\nabc -liberty {lib.path}\nopt_clean\n"
                                 f"tee -q -o {work / 'cells'} stat -liberty {lib.path}\n")
    yosys_cost.run_yosys(work / "map.ys", work / "map.log", work)
    _, cells = yosys_stat.cell_table((work / "cells").read_text())
    return sum(n * lib.cells[c]["area"] for c, n in cells.items())


if __name__ == "__main__":
    sys.exit(main())
