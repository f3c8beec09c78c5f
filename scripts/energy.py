#!/usr/bin/python3
"""Energy of a configuration of the unit on the OSU 0.18 um cells, from the switching activity of
real workloads (docs/silicon.md, Energy).

    energy.py --tessim BIN [--variant NAME] [--name NAME] [--jobs J] [--work DIR]

BIN must be a tessim whose RTL build NAME (default n2, rtl/builds.json) was Verilated with toggle
coverage (`cmake -DTESSIM_RTL_COVERAGE=ON -DTESSIM_RTL_VARIANTS=NAME`); the configuration is that
build's. For each workload of WORKLOADS the RTL runs in lock-step with the cycle
model (`tessim cosim`), which counts every register and port bit's toggles in every instance, and
the cycle model's statistics give the run's action counts (INT operations, CPG cycles, patches,
vertices). Each record of the configuration (scripts/silicon.py) is mapped onto the library,
the activity of its registers and ports (toggles per cycle, instance by instance) is propagated
through its cells and priced from the library's tables (scripts/gate_activity.py): leakage, the
clock's energy per cycle (flip-flops clocked, nothing else switching) and the data's energy per
cycle. The probability of each source bit being 1 comes from a window of the run's waveform.

The records are grouped into the blocks a user reads (BLOCKS), and each block's data energy is
divided by its action count in the calibrating workload of each pattern class (uniform, Direct3D
11): an energy per action (Accelergy's model: energy = actions x energy per action). The checking
workloads test that model: their own propagated activity against their actions times the
calibrated energies per action.

Writes docs/results/silicon/energy/NAME.json, which `tessim power` reads (embedded at build time).
"""

import argparse
import collections
import json
import os
import re
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import cost_records  # noqa: E402
import gate_activity  # noqa: E402
import silicon  # noqa: E402
import yosys_cost  # noqa: E402

REPO = Path(__file__).resolve().parent.parent
OUT = REPO / "docs" / "results" / "silicon" / "energy"
GATE_CHECKS = REPO / "docs" / "results" / "silicon" / "gate_check"
SCHEMA = 1
WUSON = "/usr/share/assimp/models/PLY/Wuson.ply"
CAMERA = "eye=2.6,1.3,-2.9,target=0,0.6,-0.2"
FAR_CAMERA = "eye=5.2,2.0,-5.6,target=0,0.6,-0.2"
ADAPTIVE = ["--adaptive", "screen", "--pixels-per-segment", "6", "--partitioning", "integer"]
COMMON = ["--normals", "quadratic", "--gpe-cycles", "8"]
# The workloads: name -> (arguments, pattern class, role). The energy per action of a block is
# calibrated per pattern class (the uniform pattern or Direct3D 11's) on the class's calibrating
# workload and checked on the other: Wuson at L = 8 and at L = 4, and two adaptive views of it
# (the adaptive study's middle and far cameras), quadratic normals, K = 8.
WORKLOADS = {
    "wuson_l8": ([WUSON, "-L", "8", *COMMON], "uniform", "calibrates"),
    "wuson_adaptive": ([WUSON, *ADAPTIVE, "--camera", CAMERA, *COMMON], "d3d11", "calibrates"),
    "wuson_l4": ([WUSON, "-L", "4", *COMMON], "uniform", "checks"),
    "wuson_adaptive_far": ([WUSON, *ADAPTIVE, "--camera", FAR_CAMERA, *COMMON], "d3d11", "checks"),
}
CLASSES = ("uniform", "d3d11")


def pattern_class(stats):
    """A run's pattern class from its statistics: the uniform pattern or Direct3D 11's."""
    return "uniform" if stats["workload"]["pattern"] == "uniform" else "d3d11"


# Blocks: (name, the records' module names, what counts one action). A block holds every instance
# of its modules, except the INT blocks, one block each ("int0", "int1", ...).
BLOCKS = [
    ("cpg", ("tess_cpg_array", "tess_cpg", "tess_cpg_edge", "tess_div", "tess_isqrt"), "cpg_busy"),
    ("fsu", ("tess_fsu", "tess_fsu_edge"), "d3d11_triangles"),
    ("cp_buffers", ("tess_cpbuf",), "triangles"),
    ("te", ("tess_te",), "int_ops"),
    ("dpg", ("tess_dpg",), "vertices"),
    ("int", ("tess_int",), "int_busy"),
    ("fifos", ("tess_fifo",), "vertices"),
    ("top", ("tess_unit",), "vertices"),
]
ACTIONS = {
    "cpg_busy": "cycles the CPG computes (statistics cpg.busy)",
    "triangles": "triangles taken in",
    "d3d11_triangles": "triangles taken in with Direct3D 11 factors (the FSU sets their pattern up)",
    "int_ops": "INT operations issued, all blocks (int.busy)",
    "vertices": "vertices out",
    "int_busy": "the INT block's operations (int.blocks[i].busy)",
}


class EnergyError(Exception):
    pass


def run(cmd, env=None):
    proc = subprocess.run(cmd, capture_output=True, text=True, env=env)
    if proc.returncode != 0:
        raise EnergyError(f"{' '.join(cmd)} failed ({proc.returncode}):\n{proc.stderr[-2000:]}")
    return proc


def workload_run(tessim, build, name, args, work):
    """(statistics, toggles) of one workload on an RTL build (tessim schema's entry), kept in WORK
    and reused while the tessim binary is older than them."""
    work = Path(work)
    work.mkdir(parents=True, exist_ok=True)
    stats_path = work / f"{name}.stats.json"
    binary_time = Path(tessim).stat().st_mtime
    if not (stats_path.exists() and stats_path.stat().st_mtime > binary_time and list(work.glob(f"{name}.dat.*"))):
        for old in work.glob(f"{name}.dat.*"):
            old.unlink()
        env = dict(os.environ, TESSIM_RTL_COVERAGE_FILE=str(work / f"{name}.dat"))
        start = time.monotonic()
        run([tessim, "cosim", *args, *build["flags"], "--variant", build["name"]], env)
        run([tessim, "sim", *args, *build["flags"], "--stats", str(stats_path)])
        print(f"  {name}: {time.monotonic() - start:.0f} s", file=sys.stderr, flush=True)
    files = sorted(work.glob(f"{name}.dat.*"))
    if not files:
        raise EnergyError(f"{tessim} wrote no coverage for {name}: is its RTL build Verilated with coverage?")
    stats = json.loads(stats_path.read_text())
    window = window_activity(tessim, build, name, args, work, stats["cycles"])
    return stats, read_toggles(files), window


WINDOW = 4000  # cycles of each workload's waveform, from the middle of the run


def window_activity(tessim, build, name, args, work, cycles):
    """{instance path below tess_unit, "/"-free as the waveform names it ("u_te.g_int[0].u_int"):
    {signal bit: (probability of 1, changes per cycle)}} over WINDOW cycles from the middle of the
    run, from its waveform (`tessim cosim --wave`), kept in WORK. The coverage counts give the
    whole run's change rates but not how often a bit is 1; the propagation needs both (a bit that
    is mostly 0 blocks an AND far more often than one at 1/2: on an INT block, probabilities of 1/2
    overstate the data energy 3.4-fold)."""
    out_path = Path(work) / f"{name}.window.json"
    if out_path.exists() and out_path.stat().st_mtime > Path(tessim).stat().st_mtime:
        return {k: {s: tuple(v) for s, v in d.items()} for k, d in json.loads(out_path.read_text()).items()}
    start = max(0, cycles // 2 - WINDOW // 2)
    vcd = Path(work) / f"{name}.vcd"
    run([tessim, "cosim", *args, *build["flags"], "--variant", build["name"], "--wave", str(vcd), "--wave-window",
         f"{start}:{start + WINDOW - 1}"])
    result = read_window(vcd)
    vcd.unlink()
    for gtkw in Path(work).glob(f"{name}.gtkw"):
        gtkw.unlink()
    out_path.write_text(json.dumps(result))
    return result


def read_window(vcd):
    """The probabilities and change rates of every bit of every variable of a VCD, per scope,
    cycles counted by the rising edges of tess_unit's clk_i."""
    scope, vars_of, clock = [], {}, None
    with open(vcd, encoding="latin-1") as f:
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
            elif parts[0] == "$var" and parts[1] != "parameter":
                width, code, vname = int(parts[2]), parts[3], parts[4]
                if scope[:2] == ["tess", "tess_unit"]:
                    if scope == ["tess", "tess_unit"] and vname == "clk_i":
                        clock = code
                    vars_of.setdefault(code, []).append((".".join(scope[2:]), vname, width))
        if clock is None:
            raise EnergyError(f"{vcd}: no tess_unit.clk_i")
        value = {c: 0 for c in vars_of}
        since = {c: 0 for c in vars_of}
        ones = {c: collections.Counter() for c in vars_of}      # bit -> cycles at 1
        changes = {c: collections.Counter() for c in vars_of}   # bit -> changes
        cycle, clk = 0, 0

        def settle(c, new):
            old = value[c]
            held = cycle - since[c]
            if held and old:
                v, b = old, 0
                while v:
                    if v & 1:
                        ones[c][b] += held
                    v >>= 1
                    b += 1
            diff, b = old ^ new, 0
            while diff:
                if diff & 1:
                    changes[c][b] += 1
                diff >>= 1
                b += 1
            value[c], since[c] = new, cycle

        for line in f:
            ch = line[0]
            if ch == "b":
                v, code = line[1:].split()
                if code in value and code != clock:
                    settle(code, int(v.replace("x", "0").replace("z", "0"), 2))
            elif ch in "01xz":
                code = line[1:].strip()
                if code == clock:
                    if ch == "1" and clk == 0:
                        cycle += 1
                    clk = 1 if ch == "1" else 0
                elif code in value:
                    settle(code, 1 if ch == "1" else 0)
        for c in vars_of:
            settle(c, value[c])
    result = {}
    for c, names in vars_of.items():
        for where, vname, width in names:
            table = result.setdefault(where, {})
            for b in range(width):
                entry = [round(ones[c][b] / cycle, 5), round(changes[c][b] / cycle, 5)]
                table[f"{vname}[{b}]"] = entry
                if width == 1:
                    table[vname] = entry
    return result


def rtl_build(tessim, variant):
    builds = json.loads(run([tessim, "schema"]).stdout)["rtl_builds"]
    match = [b for b in builds if b["name"] == variant]
    if not match:
        raise EnergyError(f"{tessim} has no RTL build {variant}")
    return match[0]


def read_toggles(files):
    """Verilator coverage files -> {instance below tess_unit as Verilator names it ("" for the top,
    "u_te.g_int[*].u_int"): {signal bit ("sum_q[3]"): toggles}}, summed over the files. Verilator
    counts both edges of a bit (the clock toggles twice a cycle) and merges the instances of a
    generate loop into one name with [*], whose counts are then the instances' sum."""
    out = collections.defaultdict(lambda: collections.defaultdict(int))
    for path in files:
        for line in open(path, encoding="latin-1"):
            if not line.startswith("C '"):
                continue
            body, count = line[3:].rsplit("' ", 1)
            keys = dict(item.split("\x02", 1) for item in body.split("\x01") if "\x02" in item)
            if not keys.get("page", "").startswith("v_toggle/"):
                continue
            hier = keys.get("h", "")
            inst = hier.split(".", 2)[2] if hier.count(".") >= 2 else ""
            out[inst][keys.get("o", "")] += int(count)
    return out


class Toggles:
    """A run's toggles looked up by instance path ("u_te/g_int[1].u_int") and signal bit as the
    mapped netlist names it: the density (toggles per cycle) of one instance. An instance of a
    merged generate loop gets the loop's mean. Names differ in three ways: a one-bit vector is a
    scalar in the netlist ("rd_ptr_q" for "rd_ptr_q[0]"), an unpacked array is flattened by
    Yosys's mem2reg ("temp_q[55][3]" for "temp_q[13][3][3]" with 4 elements in the inner
    dimension), and registers local to a generate block are not counted by Verilator at all."""

    def __init__(self, counts, cycles, paths, window=None):
        self.counts = counts
        self.cycles = cycles
        self.window = window or {}
        self.paths = [p.replace("/", ".") for p in paths]
        self.patterns = [(k, re.compile(re.escape(k).replace(r"\[\*\]", r"\[\d+\]") + "$")) for k in counts]
        self.resolved = {}
        self.dims = {}

    def instance(self, instance):
        """(coverage key, instances merged into it) of an instance path, or (None, 0)."""
        if instance not in self.resolved:
            key = instance.replace("/", ".")
            found = (None, 0)
            if key in self.counts:
                found = (key, 1)
            else:
                for k, pattern in self.patterns:
                    if pattern.match(key):
                        found = (k, max(1, sum(1 for p in self.paths if pattern.match(p))))
                        break
            self.resolved[instance] = found
        return self.resolved[instance]

    def shape(self, key, base):
        """Sizes of the unpacked dimensions of `base` in instance `key` (the indices before the bit)."""
        if (key, base) not in self.dims:
            sizes = []
            for name in self.counts[key]:
                m = re.fullmatch(re.escape(base) + r"((?:\[\d+\])+)", name)
                if m:
                    idx = [int(x) for x in re.findall(r"\d+", m.group(1))]
                    sizes = [max(a, b + 1) for a, b in zip(sizes + [0] * len(idx), idx)] if sizes else [i + 1 for i in idx]
            self.dims[(key, base)] = sizes
        return self.dims[(key, base)]

    def in_window(self, instance, signal):
        """(probability of 1, changes per cycle) of a bit in the waveform window, or None. The
        window names instances with dots and every instance of a generate loop on its own."""
        table = self.window.get(instance.replace("/", "."))
        if table is None:
            return None
        for name in (signal, signal + "[0]"):
            if name in table:
                return table[name]
        return None

    def density(self, instance, signal):
        key, merged = self.instance(instance)
        if key is None:
            return None
        table = self.counts[key]
        for name in (signal, signal + "[0]"):
            if name in table:
                return table[name] / self.cycles / merged
        m = re.fullmatch(r"(.+?)\[(\d+)\](?:\[(\d+)\])?", signal)
        if m:  # a flattened unpacked array: element i of the netlist is (x, k) of the RTL
            base, i, bit = m.group(1), int(m.group(2)), m.group(3)
            sizes = self.shape(key, base)
            if len(sizes) == 3 and bit is not None:
                inner = sizes[1]
                name = f"{base}[{i // inner}][{i % inner}][{bit}]"
                if name in table:
                    return table[name] / self.cycles / merged
            if len(sizes) == 3 and bit is None:
                inner = sizes[1]
                name = f"{base}[{i // inner}][{i % inner}][0]"
                if name in table:
                    return table[name] / self.cycles / merged
        return None


def map_netlists(params, lib, work_root, jobs):
    """{derived record name: (module base, instances, key, mapped netlist path)} of the
    configuration, each record mapped once into WORK_ROOT/<key> (reused when there). A mapping
    whose area differs from the committed silicon record is an error: the energy would belong to
    another netlist than the area and the clock."""
    versions = silicon.tool_versions()
    modules, top, counts, jobs_of = silicon.plan(params, lib, versions)
    out = {}
    todo = []
    for name in counts:
        text, boxes, key = jobs_of[name]
        work = Path(work_root) / key[:24]
        out[name] = (modules[name].base, counts[name], key, work / "mapped.v", modules)
        if not (work / "mapped.v").exists():
            todo.append((name, text, boxes, work))

    def one(job):
        name, text, boxes, work = job
        work.mkdir(parents=True, exist_ok=True)
        start = time.monotonic()
        silicon.write_mapped(lib, name, text, boxes, work)
        print(f"  mapped {modules[name].base} in {time.monotonic() - start:.0f} s", file=sys.stderr, flush=True)

    with ThreadPoolExecutor(max_workers=max(1, jobs)) as pool:
        list(pool.map(one, sorted(todo, key=lambda j: -len(j[1]))))
    for name, (base, n, key, path, _) in out.items():
        record = silicon.record_path(silicon.CACHE, key)
        if record.exists():
            stored = silicon.read_record(record)["cell_counts"]
            _, cells = silicon.yosys_stat.cell_table(path.with_suffix(".cells").read_text())
            if cells != stored:
                raise EnergyError(f"{base}: the mapping differs from its silicon record {record.name}")
    return modules, top, counts, out


def instance_paths(modules, top):
    """[(instance path below the top, "" for the top, derived record name)] of every record instance."""
    out = []

    def visit(name, path):
        out.append((path, name))
        for inst, child in sorted(modules[name].instances.items()):
            if yosys_cost.is_inline(modules[child]):
                continue
            visit(child, f"{path}/{inst}" if path else inst)

    visit(top, "")
    return out


class RecordPower:
    """One mapped record, priced with the activity of any of its instances."""

    def __init__(self, lib, path, functions, tables, power):
        text, self.boxes = gate_activity.rename_box_ports(Path(path).read_text())
        self.netlist = gate_activity.Netlist(text, functions)
        self.tables = tables
        self.power = power
        self.lib = lib
        self.unmatched = set()

    def source_signal(self, instance, net):
        """(instance path, signal bit) of the RTL that a source net of this record carries."""
        base = net
        if re.fullmatch(r"box\d+(\[\d+\])?", net):
            box, _, bit = net.partition("[")
            original = self.boxes[box]  # INST.PIN of a black box
            inst, pin = original.rsplit(".", 1)
            signal = pin + (f"[{bit}" if bit else "")
            return (f"{instance}/{inst}" if instance else inst), signal
        if "." in base:  # a register of an inlined child: CHILD.SIGNAL
            inst, signal = base.rsplit(".", 1)
            return (f"{instance}/{inst}" if instance else inst), signal
        return instance, base

    def activity(self, instance, toggles):
        """(net activity, sources matched, sources not found, sources with a probability from the
        waveform window) for one instance and one run's Toggles (None: every source still, the
        clock alone). A source's probability of 1 is the window's, 1/2 where the waveform has no
        such bit (the TE's temporaries: Verilator traces no array of more than 32 elements). A register the run did not count
        (local to a generate block) takes the density its D input propagates to, iterated to a
        fixed point from the counted registers' mean (a register's output changes in a cycle
        when its input did in the cycle before); an input not counted takes the counted mean."""
        found = missing = 0
        densities = {}
        netlist = self.netlist
        inputs = [b for b in netlist.input_bits if b != "clk_i"]
        flops = [q for _, q in netlist.flops]
        unknown_flops = []
        if toggles is None:
            act = gate_activity.propagate(netlist, self.tables, lambda net: (0.5, 0.0))
            return act, 0, 0, 0
        probs = {}
        for net in inputs + flops:
            inst, signal = self.source_signal(instance, net)
            d = toggles.density(inst, signal)
            w = toggles.in_window(inst, signal)
            if w is not None:
                probs[net] = w[0]
            if d is None and w is not None:
                d = w[1]  # not counted by the coverage (local to a generate block): the window's rate
            if d is None:
                missing += 1
                self.unmatched.add(signal)
                if net in flops:
                    unknown_flops.append(net)
            else:
                found += 1
                densities[net] = min(d, 1.0)
        mean = sum(densities.values()) / len(densities) if densities else 0.0
        guess = {q: mean for q in unknown_flops}
        d_of = {q: d for q, d in netlist.flop_inputs.items()}
        act = None
        for _ in range(4 if unknown_flops else 1):
            act = gate_activity.propagate(netlist, self.tables,
                                          lambda net: (probs.get(net, 0.5), densities.get(net, guess.get(net, mean))))
            for q in unknown_flops:
                d_net = d_of.get(q)
                guess[q] = min(act.get(d_net, (0.5, mean))[1], 1.0) if d_net else mean
        return act, found, missing, len(probs)

    def price(self, act):
        """Energy per cycle (pJ: internal, switching, clock) of the record with `act`, from the
        library's tables (scripts/gate_activity.py, price); each boundary net is counted once, at
        the record whose input it is."""
        return gate_activity.price(self.netlist, act, self.power, output_load_pf=0.0)

    def leakage_nw(self):
        return sum(self.lib.cells[ctype]["leakage_nw"] for ctype, _, _ in self.netlist.cells)


ICG = """\
module icg(clk_i, en_i, gclk_o);
  input clk_i;
  input en_i;
  output gclk_o;
  wire en_l;
  wire nclk;
  LATCH l (.CLK(nclk), .D(en_i), .Q(en_l));
  INVX1 i (.A(clk_i), .Y(nclk));
  AND2X2 a (.A(clk_i), .B(en_l), .Y(gclk_o));
endmodule
"""
FLOPS_PER_GATE = 32  # flip-flops behind one clock gate (a leaf of the clock tree)


def clock_gate(lib, functions, power):
    """A latch-based clock gate from the library's cells (a LATCH open while the clock is low, an
    AND2X2, an inverter): its area, leakage and energy per cycle with its enable still (the latch's
    clock pin and the inverter on the clock, two transitions a cycle); a gated flip-flop's clock
    pin costs nothing while the gate is shut."""
    netlist = gate_activity.Netlist(ICG, functions)
    act = {netlist.find("clk_i"): (0.5, 2.0), netlist.find("nclk"): (0.5, 2.0)}
    e = gate_activity.price(netlist, act, power, output_load_pf=0.0)
    cells = {"LATCH": 1, "AND2X2": 1, "INVX1": 1}
    return {"cells": cells, "area_um2": sum(lib.cells[c]["area"] * n for c, n in cells.items()),
            "leakage_nw": round(sum(lib.cells[c]["leakage_nw"] * n for c, n in cells.items()), 4),
            "pj_per_cycle": round(e["internal"] + e["switching"] + e["clock"], 6),
            "flops_per_gate": FLOPS_PER_GATE}


def actions(stats):
    """A run's action counts (ACTIONS) from its statistics; the INT blocks' one by one."""
    d3d11 = pattern_class(stats) == "d3d11"
    out = {"cpg_busy": stats["cpg"]["busy"], "triangles": stats["triangles_in"], "int_ops": stats["int"]["busy"],
           "d3d11_triangles": stats["triangles_in"] if d3d11 else 0,
           "vertices": stats["vertices_out"], "cycles": stats["cycles"]}
    for i, b in enumerate(stats["int"]["blocks"]):
        out[f"int_busy{i}"] = b["busy"]
    return out


def block_of(base, path):
    """The user-facing block of a record instance: (block name, action key)."""
    for name, bases, action in BLOCKS:
        if base in bases:
            if name == "int":
                index = int(re.search(r"g_int\[(\d+)\]", path).group(1))
                return f"int{index}", f"int_busy{index}"
            return name, action
    raise EnergyError(f"record {base} belongs to no block of energy.py's BLOCKS")


def characterize(tessim, variant, name, jobs, work_root):
    lib = silicon.library()
    build = rtl_build(tessim, variant)
    params = cost_records.normalized(build["parameters"], REPO / "rtl")
    start = time.monotonic()
    silicon_cost = silicon.cost(params, require_cached=True)
    modules, top, counts, mapped = map_netlists(params, lib, Path(work_root) / "netlists", jobs)
    runs = {}
    for wname, (args, _, _) in WORKLOADS.items():
        runs[wname] = workload_run(tessim, build, wname, args, Path(work_root) / "runs" / variant)
    functions = gate_activity.liberty_functions(lib.text)
    tables = gate_activity.cell_tables(functions)
    power = gate_activity.liberty_power(lib.text)
    records = {}
    for rname, (base, n, key, path, _) in mapped.items():
        records[rname] = RecordPower(lib, path, functions, tables, power)

    all_instances = instance_paths(modules, top)
    paths = [p for p, _ in all_instances]

    def price_instance(item):
        path, rname = item
        rec = records[rname]
        out = {"path": path or "tess_unit", "record": rname, "base": modules[rname].base}
        act, _, _, _ = rec.activity(path, None)
        still = rec.price(act)
        out["clock_pj"] = still["clock"]
        out["leakage_nw"] = rec.leakage_nw()
        out["flops"] = len(rec.netlist.flops)
        out["workloads"] = {}
        for wname, (stats, toggles, window) in runs.items():
            act, found, missing, windowed = rec.activity(path, Toggles(toggles, stats["cycles"], paths, window))
            p = rec.price(act)
            flops = [q for _, q in rec.netlist.flops]
            out["workloads"][wname] = {"data_pj_per_cycle": p["internal"] + p["switching"],
                                       "sources_in_window": windowed,
                                       "flop_activity": (sum(act[q][1] for q in flops) / len(flops)) if flops else 0.0,
                                       "sources_found": found, "sources_missing": missing}
        print(f"  priced {out['path']}: clock {out['clock_pj']:.2f} pJ/cycle, data "
              + ", ".join(f"{w} {v['data_pj_per_cycle']:.2f}" for w, v in out["workloads"].items())
              + f" pJ/cycle, {out['workloads'][next(iter(runs))]['sources_missing']} sources unmatched",
              file=sys.stderr, flush=True)
        return out

    with ThreadPoolExecutor(max_workers=max(1, jobs)) as pool:
        instances = list(pool.map(price_instance, all_instances))
    # Where a gate-level simulation of a record exists (scripts/gate_check.py on this RTL), the
    # propagation's data energy of that record is scaled to it: independence is far off on some
    # datapaths (the CPG's edge lane), close on others (an INT block).
    scales = {}
    for check in sorted(GATE_CHECKS.glob("*.json")):
        g = json.loads(check.read_text())
        if g.get("sources_digest") == cost_records.sources_digest(REPO / "rtl") and g["data_pj_per_cycle"]["propagated"]:
            scales[g["record"]] = g["data_pj_per_cycle"]["gate_level"] / g["data_pj_per_cycle"]["propagated"]
    for inst in instances:
        factor = scales.get(inst["record"])
        if factor is not None:
            inst["gate_level_scale"] = round(factor, 4)
            for v in inst["workloads"].values():
                v["data_pj_per_cycle"] *= factor
    # per block
    area = {r["derived"]: r["area_um2"] for r in silicon_cost["records"]}
    blocks = {}
    for inst in instances:
        bname, action = block_of(inst["base"], inst["path"])
        b = blocks.setdefault(bname, {"name": bname, "action": action, "instances": [], "area_um2": 0.0,
                                      "leakage_nw": 0.0, "clock_pj_per_cycle": 0.0, "flops": 0,
                                      "data_pj": {w: 0.0 for w in WORKLOADS}, "unmatched_sources": 0,
                                      "clock_floor_pj_per_cycle": {w: 0.0 for w in WORKLOADS},
                                      "sources": 0})
        b["instances"].append(inst["path"])
        b["area_um2"] += area[inst["record"]]
        b["leakage_nw"] += inst["leakage_nw"]
        b["clock_pj_per_cycle"] += inst["clock_pj"]
        b["flops"] += inst["flops"]
        for w, v in inst["workloads"].items():
            b["data_pj"][w] += v["data_pj_per_cycle"] * runs[w][0]["cycles"]
            b["clock_floor_pj_per_cycle"][w] += inst["clock_pj"] * v["flop_activity"]
            if w == next(iter(WORKLOADS)):
                b["unmatched_sources"] += v["sources_missing"]
                b["sources"] += v["sources_missing"] + v["sources_found"]
    acts = {w: actions(runs[w][0]) for w in WORKLOADS}
    calibrating = {cls: next(w for w, (_, c, role) in WORKLOADS.items() if c == cls and role == "calibrates")
                   for cls in CLASSES}
    for w, (_, cls, _) in WORKLOADS.items():
        if pattern_class(runs[w][0]) != cls:
            raise EnergyError(f"workload {w} ran the {pattern_class(runs[w][0])} pattern, not {cls}")
    validation = []

    def predicted(b, w):
        return b["pj_per_action"][WORKLOADS[w][1]] * acts[w][b["action"]]

    for b in blocks.values():
        b["pj_per_action"] = {}
        for cls, w in calibrating.items():
            n = acts[w][b["action"]]
            b["pj_per_action"][cls] = b["data_pj"][w] / n if n else 0.0
        for w in WORKLOADS:
            validation.append({"workload": w, "block": b["name"], "role": WORKLOADS[w][2],
                               "direct_pj": round(b["data_pj"][w], 1), "predicted_pj": round(predicted(b, w), 1),
                               "error": round(predicted(b, w) / b["data_pj"][w] - 1, 4) if b["data_pj"][w] else None})
    for w in WORKLOADS:
        direct = sum(b["data_pj"][w] for b in blocks.values())
        model = sum(predicted(b, w) for b in blocks.values())
        validation.append({"workload": w, "block": "unit", "role": WORKLOADS[w][2], "direct_pj": round(direct, 1),
                           "predicted_pj": round(model, 1), "error": round(model / direct - 1, 4)})
    order = [n for n, _, _ in BLOCKS]
    block_list = sorted(blocks.values(), key=lambda b: (order.index(re.sub(r"\d+$", "", b["name"])), b["name"]))
    for b in block_list:
        b["area_um2"] = round(b["area_um2"], 1)
        b["leakage_nw"] = round(b["leakage_nw"], 2)
        b["clock_pj_per_cycle"] = round(b["clock_pj_per_cycle"], 4)
        b["pj_per_action"] = {c: round(v, 4) for c, v in b["pj_per_action"].items()}
        b["data_pj"] = {w: round(v, 1) for w, v in b["data_pj"].items()}
        # The clock if each flip-flop were clocked only in the cycles its value changes: the floor
        # of enable-based gating (each flip-flop's clock energy times its output's activity).
        b["clock_floor_pj_per_cycle"] = {w: round(v, 4) for w, v in b["clock_floor_pj_per_cycle"].items()}
    return {
        "schema": SCHEMA, "name": name, "variant": variant, "params": params,
        "sources_digest": cost_records.sources_digest(REPO / "rtl"), "library": str(lib.source),
        "library_sha256": lib.digest, **silicon.tool_versions(),
        "area_mm2": silicon_cost["area_mm2"], "clock_ns": silicon_cost["clock_ns"],
        "clock_mhz": silicon_cost["clock_mhz"],
        "int_blocks": sum(1 for b in block_list if b["name"].startswith("int")),
        "actions": ACTIONS,
        "pricing": {"reference_slew_ns": gate_activity.REFERENCE_SLEW_NS, "vdd": gate_activity.VDD},
        "clock_gate": clock_gate(lib, functions, power),
        "workloads": {w: {"args": [a.replace("/usr/share/assimp/models/", "") for a in args], "class": cls,
                          "role": role, "counts": acts[w]} for w, (args, cls, role) in WORKLOADS.items()},
        "gate_level_scales": {modules[r].base: round(f, 4) for r, f in scales.items() if r in modules},
        "blocks": block_list, "validation": validation,
        "seconds": round(time.monotonic() - start),
    }


def main(argv):
    ap = argparse.ArgumentParser(prog="energy.py", description=__doc__.split("\n\n")[0])
    ap.add_argument("--tessim", help="a tessim whose RTL build was Verilated with coverage")
    ap.add_argument("--variant", default="n2", help="its RTL build (default n2)")
    ap.add_argument("--name", help="the result's name (default: the build's)")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--work", default=str(REPO / "build-energy"), help="mapped netlists and the workloads' runs")
    ap.add_argument("--refresh-clock-gate", metavar="NAME", action="append",
                    help="recompute only the clock gate's figures of the committed characterization NAME from the "
                         "library (its area, leakage and clock energy depend on the library alone)")
    args = ap.parse_args(argv)
    if args.refresh_clock_gate:
        lib = silicon.library()
        functions, power = gate_activity.liberty_functions(lib.text), gate_activity.liberty_power(lib.text)
        for name in args.refresh_clock_gate:
            path = OUT / f"{name}.json"
            result = json.loads(path.read_text())
            if result["library_sha256"] != lib.digest:
                print(f"energy.py: error: {path}: characterized on another library; rerun it whole", file=sys.stderr)
                return 1
            before, result["clock_gate"] = result["clock_gate"], clock_gate(lib, functions, power)
            path.write_text(json.dumps(result, indent=1) + "\n")
            print(f"{path.relative_to(REPO)}: clock gate {before['area_um2']} -> {result['clock_gate']['area_um2']} um2")
        return 0
    if not args.tessim:
        ap.error("--tessim is required to characterize")
    try:
        result = characterize(args.tessim, args.variant, args.name or args.variant, args.jobs, args.work)
    except (EnergyError, silicon.SiliconError, gate_activity.NetlistError) as e:
        print(f"energy.py: error: {e}", file=sys.stderr)
        return 1
    OUT.mkdir(parents=True, exist_ok=True)
    out = OUT / f"{result['name']}.json"
    partial = out.with_name(out.name + ".tmp")
    partial.write_text(json.dumps(result, indent=1) + "\n")
    partial.replace(out)
    print(f"{out.relative_to(REPO)}: {result['seconds']} s")
    for v in result["validation"]:
        print(f"  {v['workload']:<16} {v['block']:<11} direct {v['direct_pj'] / 1e6:10.4f} uJ"
              f"  predicted {v['predicted_pj'] / 1e6:10.4f} uJ  {100 * v['error'] if v['error'] is not None else 0:+6.1f} %")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
