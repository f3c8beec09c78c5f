#!/usr/bin/python3
"""Hardware cost of a configuration of the unit, composed from per-module Yosys records.

    yosys_cost.py [-chparam NAME VALUE]... [--cache DIR] [--jobs J] [--no-xilinx]
                  [--require-cached] [--json FILE] [--rtl DIR] [--compare-flat]

The unit is elaborated with its parameters (Yosys 0.23: read the sources of rtl/tess.f, chparam,
hierarchy, proc; about a second), which gives every module as it is instantiated: one derived
module per distinct parameter set. Each derived module is a *record*, costed on its own with its
submodules as black boxes (docs/rtl.md, Cost method): generic `synth` cells and flip-flops,
`stat -tech cmos` transistors after flip-flop legalisation, `ltp -noff` logic depth, and
`synth_xilinx` LUT/FF/DSP/CARRY4. The small leaf modules in INLINE are synthesized inside their
parents instead (a saturation is a few gates; a boundary around it would hide the constants its
parent feeds it).

A record is stored under the SHA-256 of exactly what Yosys reads for it: the module's elaborated
RTLIL with source locations dropped and automatic names renumbered, its inlined submodules, the
ports of its black-box submodules, and the synthesis commands. Editing one module's source
therefore re-synthesizes only the records of that module (and of a parent it is inlined into);
a comment or an edit elsewhere in the same file changes nothing.

The unit's figures are the sums over its module instances (cells, flip-flops, transistors and
Xilinx cells); its logic depth is the deepest record's, which holds where module boundaries are
registered and is compared with flattened syntheses in docs/rtl.md. Blocks reported: tess_unit,
tess_cpg (its subtree times its Mc copies), tess_int (one INT block), and every record with its
instance count.
"""

import argparse
import hashlib
import json
import re
import subprocess
import sys
import tempfile
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import rtl_sources as rtl_sources_list
import yosys_stat

REPO = Path(__file__).resolve().parent.parent
RECORD_SCHEMA = 2
# Leaf modules synthesized inside their parents rather than as records of their own.
INLINE = ("tess_sat",)
TOP = "tess_unit"
# Reported as blocks: the module and its subtree, once or times its instances (the CPG's copies
# together; one INT block, whose count N the study multiplies itself).
BLOCKS = {"tess_unit": False, "tess_cpg": True, "tess_int": False}
# The depth budget (docs/rtl.md, Depth budget): the logic depth in generic gate levels (`ltp -noff`)
# every register-to-register path of the unit must fit in to run at the budget's clock. 48 is what
# one INT block needs, 45 levels for the W x (B + 2) products and the rounded three-way sum, the one
# operation the architecture does in a single cycle, and three levels for its operand select. A
# configuration whose deepest path is longer runs at a clock of that many levels instead.
DEPTH_BUDGET = 48


def clock_levels(depth, budget=DEPTH_BUDGET):
    """Cycle time of a configuration in gate levels: the budget, or its deepest path if longer."""
    return max(budget, depth)


def over_budget(result, budget=DEPTH_BUDGET):
    """The records of a cost() result deeper than the budget: (module, depth), deepest first."""
    deep = {(r["module"], r["depth"]) for r in result["records"] if r["depth"] > budget}
    return sorted(deep, key=lambda md: (-md[1], md[0]))

GENERIC_SCRIPT = """\
read_rtlil {job}
hierarchy -top {top}
flatten
synth -top {top}
tee -q -o {out}.cells stat
async2sync
dfflegalize -cell $_DFF_P_ 01
write_json {out}.json
{delete}tee -q -o {out}.cmos stat -tech cmos
tee -q -o {out}.ltp ltp -noff
"""
XILINX_SCRIPT = """\
read_rtlil {job}
hierarchy -top {top}
flatten
synth_xilinx -top {top}
{delete}tee -q -o {out}.xil stat
"""


class CostError(Exception):
    pass


def rtl_sources(rtl_dir):
    """The sources of rtl/tess.f (package first), as paths."""
    return rtl_sources_list.read(Path(rtl_dir) / "tess.f")


def yosys_version():
    try:
        return subprocess.run(["yosys", "-V"], capture_output=True, text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError) as e:
        raise CostError(f"yosys not available: {e}")


def package_defaults(rtl_dir):
    """tess_pkg's `localparam int unsigned Name = value;` defaults."""
    text = (Path(rtl_dir) / "tess_pkg.sv").read_text()
    return {m.group(1): int(m.group(2))
            for m in re.finditer(r"^\s*localparam\s+int\s+unsigned\s+(\w+)\s*=\s*(\d+)\s*;", text, re.M)}


def run_yosys(script, log, cwd):
    proc = subprocess.run(["yosys", "-q", "-l", str(log), "-s", str(script)], capture_output=True, text=True,
                          cwd=cwd)
    if proc.returncode != 0:
        tail = "\n".join(Path(log).read_text().splitlines()[-15:]) if Path(log).exists() else proc.stderr
        raise CostError(f"yosys {script.name} failed:\n{tail}")


class Module:
    def __init__(self, name, attributes):
        self.name = name
        self.base = name
        for a in attributes:
            m = re.match(r'attribute \\hdlname "\\\\(\S+)"', a)
            if m:
                self.base = m.group(1)
        if self.base.startswith("\\"):
            self.base = self.base[1:]
        self.attributes = [a for a in attributes if not a.startswith("attribute \\src ")]
        self.body = []    # lines between `module` and its `end`, source locations dropped
        self.ports = []   # the port `wire` lines
        self.cells = []     # (type, name) of every cell
        self.children = []  # cell types that are modules of the design, one entry per instance
        self.instances = {}  # cell name -> module, for those cells


AUTO_NAME = re.compile(r"(?<!\S)\$(?!paramod)[^\s$]*\$\S*")  # $add$file:line$N_Y, $procmux$N, ...
SOURCE_IN_NAME = re.compile(r"\$/[^$\s]*")  # the file:line part of an automatic name
COUNTER = re.compile(r"\$(\d+)")  # Yosys's global counter in an automatic name
# A public name with an automatic part: Yosys names a block-local declaration of a for loop
# \g_ctx[0].$fordecl_block$1080.a, with the global counter in it.
ESCAPED_AUTO = re.compile(r"(?<!\S)\\\S*\$[A-Za-z_]+\$\d+\S*")


def parse_rtlil(text):
    """Modules of an elaborated, proc'd RTLIL dump: module -> Module (cells reference modules by name)."""
    modules = {}
    pending = []
    current = None
    depth = 0
    for raw in text.splitlines():
        line = raw.strip()
        if current is None:
            if line.startswith("attribute "):
                pending.append(line)
            elif line.startswith("module "):
                current = Module(line.split(None, 1)[1], pending)
                pending = []
                depth = 0
            continue
        if line == "end":
            if depth == 0:
                modules[current.name] = current
                current = None
                continue
            depth -= 1
        elif line.startswith("cell "):
            depth += 1
            _, cell_type, cell_name = line.split()[:3]
            current.cells.append((cell_type, cell_name))
        elif line.startswith("wire ") and re.search(r"\b(input|output|inout) \d+\b", line):
            current.ports.append(line)
        if line.startswith("attribute \\src "):
            continue
        current.body.append(line)
    for m in modules.values():
        m.instances = {name[1:] if name.startswith("\\") else name: t for t, name in m.cells if t in modules}
        m.children = list(m.instances.values())
    return modules


def normalized(module):
    """The module's text as it depends on the module alone: automatic names lose their file:line
    and their global counter becomes its rank within the module (the counter's offset depends on
    what Yosys elaborated before), and declarations are sorted (the dump's order follows the
    original names)."""
    tokens = {t for line in module.body for pattern in (AUTO_NAME, ESCAPED_AUTO) for t in pattern.findall(line)}
    counters = sorted({int(n) for t in tokens for n in COUNTER.findall(SOURCE_IN_NAME.sub("", t))})
    rank = {n: i for i, n in enumerate(counters)}

    def rename(match):
        name = SOURCE_IN_NAME.sub("$", match.group(0))
        return COUNTER.sub(lambda m: f"${rank[int(m.group(1))]}", name)

    entities = []  # (kind, sort key, lines): attributes stay with what they describe
    pending = []
    cell, cell_key = None, None
    for raw in module.body:
        line = ESCAPED_AUTO.sub(rename, AUTO_NAME.sub(rename, raw))
        if cell is not None:
            cell.append(line)
            if line == "end":
                entities.append((3, cell_key, cell))
                cell = None
            continue
        if line.startswith("attribute "):
            pending.append(line)
            continue
        kind = {"parameter": 0, "wire": 1, "memory": 2, "cell": 3, "connect": 4}.get(line.split(" ", 1)[0], 5)
        if kind == 3:
            cell = pending + [line]
            cell_key = line
            pending = []
            continue
        entities.append((kind, line, pending + [line]))
        pending = []
    entities.sort(key=lambda e: (e[0], e[1]))
    lines = module.attributes + [f"module {module.name}"]
    for _, _, entity in entities:
        lines += entity
    lines += pending + ["end"]
    return "\n".join(lines) + "\n"


def stub(module):
    return "\n".join(["attribute \\blackbox 1", f"module {module.name}", *module.ports, "end"]) + "\n"


def is_inline(module):
    return module.base in INLINE


def record_text(modules, name):
    """What Yosys reads to cost record `name`: the module, its inlined submodules (recursively) and
    black-box stubs of its other submodules. Returns (text, black-box module names)."""
    parts = [normalized(modules[name])]
    boxes = []
    seen = {name}
    stack = list(modules[name].children)
    while stack:
        child = stack.pop(0)
        if child in seen:
            continue
        seen.add(child)
        if is_inline(modules[child]):
            parts.append(normalized(modules[child]))
            stack.extend(modules[child].children)
        else:
            parts.append(stub(modules[child]))
            boxes.append(child)
    return "".join(parts), sorted(boxes)


def instance_counts(modules, top):
    """Record -> instances under `top` (inlined modules count as part of their parents)."""
    counts = {}

    def visit(name, times):
        counts[name] = counts.get(name, 0) + times
        for child in modules[name].children:
            if is_inline(modules[child]):
                continue
            visit(child, times)

    visit(top, 1)
    return counts


_ELABORATED = {}


def elaborate(rtl_dir, params, work):
    """Elaborates tess_unit with `params` (name -> value, defaults dropped) into RTLIL. Memoized
    per process on the parameters and the sources' content."""
    sources = rtl_sources(rtl_dir)
    memo = (tuple(sorted(params.items())), tuple(p.read_bytes() for p in sources))
    if memo not in _ELABORATED:
        _ELABORATED[memo] = _elaborate(sources, params, work)
    return _ELABORATED[memo]


def elaborate_all(param_sets, rtl_dir=REPO / "rtl", jobs=2):
    """Elaborates several configurations, `jobs` Yosys processes at a time, into the memo: the
    elaboration is most of what composing a configuration from recorded records costs."""
    defaults = package_defaults(rtl_dir)

    def one(params):
        params = {k: int(v) for k, v in params.items() if int(v) != defaults.get(k)}
        with tempfile.TemporaryDirectory(prefix="tessim-elaborate-") as tmp:
            elaborate(rtl_dir, params, tmp)

    with ThreadPoolExecutor(max_workers=max(1, jobs)) as pool:
        list(pool.map(one, param_sets))


def _elaborate(sources, params, work):
    sources = " ".join(str(p) for p in sources)
    chparam = "".join(f"chparam -set {k} {v} {TOP}\n" for k, v in params.items())
    script = Path(work) / "elaborate.ys"
    script.write_text(f"read_verilog -sv {sources}\n{chparam}hierarchy -check -top {TOP}\nproc\n"
                      f"write_rtlil {work}/design.il\n")
    run_yosys(script, Path(work) / "elaborate.log", work)
    return parse_rtlil((Path(work) / "design.il").read_text())


def top_name(modules):
    return next(n for n, m in modules.items() if m.base == TOP)


def record_key(text, yosys, xilinx):
    h = hashlib.sha256()
    ident = {"schema": RECORD_SCHEMA, "yosys": yosys, "xilinx": xilinx, "generic": GENERIC_SCRIPT,
             "xilinx_script": XILINX_SCRIPT if xilinx else ""}
    h.update(json.dumps(ident, sort_keys=True).encode())
    h.update(text.encode())
    return h.hexdigest()


def synthesize_record(name, text, boxes, xilinx, work):
    """Costs one record with Yosys; returns its figures."""
    job = Path(work) / "job.il"
    job.write_text(text)
    delete = "".join(f"delete t:{b}\n" for b in boxes)
    out = Path(work) / "out"
    start = time.monotonic()
    generic = Path(work) / "generic.ys"
    generic.write_text(GENERIC_SCRIPT.format(job=job, top=name, delete=delete, out=out))
    run_yosys(generic, Path(work) / "generic.log", work)
    total, cells = yosys_stat.cell_table(Path(f"{out}.cells").read_text())
    total -= sum(cells.pop(b, 0) for b in boxes)  # the submodules' instances are their own records
    paths = port_timing(json.loads(Path(f"{out}.json").read_text()), name, boxes)
    transistors, exact = yosys_stat.transistors(Path(f"{out}.cmos").read_text())
    depth = yosys_stat.depth(Path(f"{out}.ltp").read_text())
    entry = {
        "cells": total or 0,
        "flops": yosys_stat.flops(cells),
        "transistors": transistors or 0,
        "transistors_exact": exact,
        "depth": depth or 0,
        "paths": sorted([src, sink, gates] for (src, sink), gates in paths.items()),
    }
    if xilinx:
        script = Path(work) / "xilinx.ys"
        script.write_text(XILINX_SCRIPT.format(job=job, top=name, delete=delete, out=out))
        run_yosys(script, Path(work) / "xilinx.log", work)
        entry["xilinx"] = yosys_stat.xilinx(yosys_stat.cell_table(Path(f"{out}.xil").read_text())[1])
    entry["seconds"] = round(time.monotonic() - start, 1)
    return entry


def unescape(name):
    """A module or cell name as write_json spells it (no leading backslash)."""
    return name[1:] if name.startswith("\\") else name


def port_timing(netlist, top, boxes):
    """Longest paths of a synthesized record (write_json after flip-flop legalisation) between its
    boundaries: {(source, sink): gates}, counting every cell on the way as `ltp` does. Sources are
    input ports ("in:P"), flip-flop outputs ("reg") and black-box output bits ("box:INST.P[i]");
    sinks are output bits ("out:P[i]"), flip-flop inputs ("reg") and black-box input ports
    ("box:INST.P"). Outputs are kept per bit: a port often bundles fields of very different depth
    (the FSU's edge setup), and a parent that reads a shallow field must not inherit a deep one."""
    module = netlist["modules"][unescape(top)]
    box_types = {unescape(b) for b in boxes}
    arrival = {}  # bit -> {source: gates}
    for name, port in module["ports"].items():
        if port["direction"] == "input":
            for bit in port["bits"]:
                if isinstance(bit, int):
                    arrival[bit] = {f"in:{name}": 0}
    driver_of = {}
    sinks = []  # (bit, sink tag)
    comb = []
    for cname, cell in module["cells"].items():
        kind = cell["type"]
        dirs = cell.get("port_directions", {})
        if kind.startswith("$_DFF") or kind.startswith("$_SDFF") or kind.startswith("$_DLATCH"):
            for bit in cell["connections"].get("Q", []):
                arrival[bit] = {"reg": 0}
            for pin in ("D", "E", "R", "S"):
                sinks += [(bit, "reg") for bit in cell["connections"].get(pin, [])]
        elif kind in box_types:  # a submodule: a record of its own
            inst = unescape(cname)
            for pin, bits in cell["connections"].items():
                if dirs.get(pin) == "output":
                    for i, bit in enumerate(bits):
                        arrival[bit] = {f"box:{inst}.{pin}[{i}]": 0}
                else:
                    sinks += [(bit, f"box:{inst}.{pin}") for bit in bits]
        else:
            ins = [b for pin, bits in cell["connections"].items() if dirs.get(pin) != "output" for b in bits]
            outs = [b for pin, bits in cell["connections"].items() if dirs.get(pin) == "output" for b in bits]
            comb.append((ins, outs))
            for b in outs:
                driver_of[b] = len(comb) - 1
    for name, port in module["ports"].items():
        if port["direction"] == "output":
            sinks += [(bit, f"out:{name}[{i}]") for i, bit in enumerate(port["bits"])]
    # Kahn's order over the combinational cells.
    waiting = [0] * len(comb)
    users = {}
    for i, (ins, _) in enumerate(comb):
        for b in ins:
            if b in driver_of:
                waiting[i] += 1
                users.setdefault(b, []).append(i)
    ready = [i for i, n in enumerate(waiting) if n == 0]
    done = 0
    while ready:
        i = ready.pop()
        done += 1
        ins, outs = comb[i]
        merged = {}
        for b in ins:
            for tag, d in arrival.get(b, {}).items():
                if d + 1 > merged.get(tag, -1):
                    merged[tag] = d + 1
        for b in outs:
            arrival[b] = merged
            for j in users.get(b, ()):
                waiting[j] -= 1
                if waiting[j] == 0:
                    ready.append(j)
    if done != len(comb):
        raise CostError(f"{top}: combinational loop in the synthesized netlist")
    paths = {}
    for bit, sink in sinks:
        for tag, d in arrival.get(bit, {}).items():
            key = (tag, sink)
            if d > paths.get(key, -1):
                paths[key] = d
    return paths


def composed_depth(modules, records, top):
    """Longest path through the hierarchy under `top`, from every record's port-level paths:
    a black-box pin of a parent is the child's port."""
    edges = {}  # node -> [(node, gates)]

    def node(path, tag):
        return f"{path}|{tag}"

    hubs = [0]

    def expand(name, path):
        children = {inst: f"{path}/{inst}" for inst, child in modules[name].instances.items()
                    if not is_inline(modules[child])}
        for src, sink, gates in records[name]["paths"]:
            sources = [node(path, "reg>" if t == "reg" else t) for t in bits_of(src)]
            sinks = [node(path, "reg<" if t == "reg" else t) for t in bits_of(sink)]
            if len(sources) > 1 and len(sinks) > 1:  # every pair: through one hub, not a product
                hubs[0] += 1
                hub = f"hub{hubs[0]}"
                for a in sources:
                    edges.setdefault(a, []).append((hub, 0))
                sources = [hub]
            for a in sources:
                edges.setdefault(a, []).extend((b, gates) for b in sinks)
            for t in bits_of(src):  # an output bit of a child feeds the parent
                if t.startswith("box:"):
                    inst, port = t[4:].rsplit(".", 1)
                    joins.add((node(children[inst], "out:" + port), node(path, t)))
            if sink.startswith("box:"):  # the parent drives an input port of a child
                inst, port = sink[4:].rsplit(".", 1)
                joins.add((node(path, sink), node(children[inst], "in:" + port)))
        for inst, child in modules[name].instances.items():
            if inst in children:
                expand(child, children[inst])

    joins = set()
    expand(top, "")
    for a, b in joins:
        edges.setdefault(a, []).append((b, 0))
    indegree = {}
    for a, outs in edges.items():
        indegree.setdefault(a, 0)
        for b, _ in outs:
            indegree[b] = indegree.get(b, 0) + 1
    longest = {n: 0 for n in indegree}
    previous = {}
    ready = [n for n, d in indegree.items() if d == 0]
    seen = 0
    while ready:
        a = ready.pop()
        seen += 1
        for b, gates in edges.get(a, ()):
            if longest[a] + gates > longest[b] or b not in previous:
                if longest[a] + gates >= longest[b]:
                    longest[b] = longest[a] + gates
                    previous[b] = a
            indegree[b] -= 1
            if indegree[b] == 0:
                ready.append(b)
    if seen != len(indegree):
        raise CostError(f"{top}: a combinational cycle through module ports (port-level paths)")
    if not longest:
        return 0, []
    end = max(longest, key=lambda n: (longest[n], n))
    path = [end]
    while path[-1] in previous:
        path.append(previous[path[-1]])
    # Where the path crosses a boundary, with the gates counted up to there.
    return longest[end], [[n.replace("|", " "), longest[n]] for n in reversed(path)
                          if not n.split("|", 1)[1].startswith("box:")]


INDEXED = re.compile(r"^(.*)\[(\d+)(?::(\d+))?\]$")


def bits_of(tag):
    """The tags one tag stands for: "out:P[3:5]" is out:P[3], out:P[4], out:P[5]."""
    m = INDEXED.match(tag)
    if not m or m.group(3) is None:
        return [tag]
    return [f"{m.group(1)}[{i}]" for i in range(int(m.group(2)), int(m.group(3)) + 1)]


def compress_paths(paths):
    """The same set of paths with runs of consecutive bits written as one range (lossless: a row
    S -> R stands for every pair of S x R, and is only formed where every pair is a path)."""
    def split(tag):
        m = INDEXED.match(tag)
        return (m.group(1), int(m.group(2))) if m and m.group(3) is None else (tag, None)

    def runs(indices):
        indices = sorted(indices)
        start = prev = indices[0]
        for i in indices[1:] + [None]:
            if i is not None and i == prev + 1:
                prev = i
                continue
            yield start, prev
            if i is not None:
                start = prev = i

    def name(base, lo, hi):
        if lo is None:
            return base
        return f"{base}[{lo}]" if lo == hi else f"{base}[{lo}:{hi}]"

    expanded = [(b, s, g) for src, sink, g in paths for a in bits_of(src) for b in [a] for s in bits_of(sink)]
    # Sinks first: each source bit's run of sink bits of one port at one depth.
    by_source = {}
    for src, sink, g in expanded:
        base, i = split(sink)
        by_source.setdefault((src, base, g, i is None), []).append(i)
    rows = []
    for (src, base, g, whole), indices in by_source.items():
        for lo, hi in ([(None, None)] if whole else runs(indices)):
            rows.append((src, name(base, lo, hi), g))
    # Then sources: runs of source bits that reach the same sinks at the same depth.
    by_sink = {}
    for src, sink, g in rows:
        base, i = split(src)
        by_sink.setdefault((base, sink, g, i is None), []).append(i)
    out = []
    for (base, sink, g, whole), indices in by_sink.items():
        for lo, hi in ([(None, None)] if whole else runs(indices)):
            out.append([name(base, lo, hi), sink, g])
    return sorted(out)


def write_record(path, record):
    """A record as JSON, its boundary paths (most of it) compressed and one to a line."""
    record = json.loads(json.dumps(record))
    write_record_rows(path, record, compress_paths(record["result"].pop("paths")))


def write_record_rows(path, record, paths):
    """`record` as JSON with `paths` after it, one row to a line (also scripts/silicon.py's
    records), written to a temporary and renamed into place."""
    text = json.dumps(record, indent=1)
    text = text[:text.rindex("}")].rstrip() + ',\n "paths": [\n'
    text += ",\n".join("  " + json.dumps(p) for p in paths) + "\n ]\n}\n"
    path.parent.mkdir(parents=True, exist_ok=True)
    partial = path.with_name(path.name + ".tmp")
    partial.write_text(text)
    partial.replace(path)


def read_record(path):
    record = json.loads(Path(path).read_text())
    result = record["result"]
    if "paths" in record:
        result["paths"] = record["paths"]
    return result


ADDITIVE = ("cells", "flops", "transistors")


def compose(records, counts):
    """Sum of the records over their instance counts; depth is the deepest record's."""
    out = {k: 0 for k in ADDITIVE}
    out["transistors_exact"] = True
    out["depth"] = 0
    xil = None
    for name, n in counts.items():
        r = records[name]
        for k in ADDITIVE:
            out[k] += n * r[k]
        out["transistors_exact"] = out["transistors_exact"] and r["transistors_exact"]
        out["depth"] = max(out["depth"], r["depth"])
        if "xilinx" in r:
            xil = xil or {k: 0 for k in r["xilinx"]}
            for k, v in r["xilinx"].items():
                xil[k] += n * v
    if xil is not None:
        out["xilinx"] = xil
    return out


def synthesize_missing(param_sets, cache, rtl_dir=REPO / "rtl", jobs=2, xilinx=True, log=None):
    """Synthesizes every record that any of the configurations lacks, each once, `jobs` at a time
    (largest first); returns how many."""
    defaults = package_defaults(rtl_dir)
    yosys = yosys_version()
    cache = Path(cache)
    todo = {}  # key -> (module base, derived name, record text)
    with tempfile.TemporaryDirectory(prefix="tessim-cost-") as tmp:
        for params in param_sets:
            params = {k: int(v) for k, v in params.items() if int(v) != defaults.get(k)}
            modules = elaborate(rtl_dir, params, tmp)
            for name in instance_counts(modules, top_name(modules)):
                text, boxes = record_text(modules, name)
                key = record_key(text, yosys, xilinx)
                if key not in todo and not (cache / f"{key}.json").exists():
                    todo[key] = (modules[name].base, name, text, boxes)

    def work(key):
        base, name, text, boxes = todo[key]
        with tempfile.TemporaryDirectory(prefix="tessim-record-") as rec_tmp:
            result = synthesize_record(name, text, boxes, xilinx, rec_tmp)
        write_record(cache / f"{key}.json", {"schema": RECORD_SCHEMA, "module": base, "derived": name,
                                             "yosys": yosys, "xilinx": xilinx, "result": result})
        if log:
            print(f"  {base:<14} {result['transistors']:>9} transistors, depth {result['depth']:>3}"
                  f" ({result['seconds']} s)", file=log, flush=True)

    if log and todo:
        print(f"yosys_cost: {len(todo)} records to synthesize", file=log, flush=True)
    with ThreadPoolExecutor(max_workers=max(1, jobs)) as pool:
        list(pool.map(work, sorted(todo, key=lambda k: -len(todo[k][2]))))
    return len(todo)


def record_keys(params, rtl_dir=REPO / "rtl", xilinx=True):
    """The keys of every record the configuration is composed of, whether stored or not (an
    elaboration, no synthesis)."""
    defaults = package_defaults(rtl_dir)
    params = {k: int(v) for k, v in params.items() if int(v) != defaults.get(k)}
    yosys = yosys_version()
    with tempfile.TemporaryDirectory(prefix="tessim-cost-") as tmp:
        modules = elaborate(rtl_dir, params, tmp)
        return {record_key(record_text(modules, name)[0], yosys, xilinx)
                for name in instance_counts(modules, top_name(modules))}


def cost(params, cache, rtl_dir=REPO / "rtl", jobs=2, xilinx=True, require_cached=False, log=None):
    """Composed cost of tess_unit with `params` (tess_unit parameter -> value). Synthesizes the
    records the cache lacks (or raises CostError naming them with require_cached)."""
    defaults = package_defaults(rtl_dir)
    params = {k: int(v) for k, v in params.items() if int(v) != defaults.get(k)}
    yosys = yosys_version()
    cache = Path(cache)
    with tempfile.TemporaryDirectory(prefix="tessim-cost-") as tmp:
        modules = elaborate(rtl_dir, params, tmp)
        top = top_name(modules)
        counts = instance_counts(modules, top)
        texts = {name: record_text(modules, name) for name in counts}
        keys = {name: record_key(texts[name][0], yosys, xilinx) for name in counts}
        records, missing = {}, []
        for name in counts:
            path = cache / f"{keys[name]}.json"
            if path.exists():
                records[name] = read_record(path)
            else:
                missing.append(name)
        if missing and require_cached:
            raise CostError("no recorded cost for " + ", ".join(sorted(modules[n].base for n in missing)))

        def work(name):
            with tempfile.TemporaryDirectory(prefix="tessim-record-") as rec_tmp:
                result = synthesize_record(name, *texts[name], xilinx, rec_tmp)
            write_record(cache / f"{keys[name]}.json",
                         {"schema": RECORD_SCHEMA, "module": modules[name].base, "derived": name, "yosys": yosys,
                          "xilinx": xilinx, "result": result})
            if log:
                print(f"  {modules[name].base:<14} {result['transistors']:>9} transistors, depth {result['depth']:>3}"
                      f" ({result['seconds']} s)", file=log, flush=True)
            return name, result

        # Largest first keeps both Yosys processes busy to the end.
        order = sorted(missing, key=lambda n: -len(texts[n][0]))
        with ThreadPoolExecutor(max_workers=max(1, jobs)) as pool:
            for name, result in pool.map(work, order):
                records[name] = result

        blocks = {}
        for block, all_instances in BLOCKS.items():
            owner = next(n for n in counts if modules[n].base == block)
            times = counts[owner] if all_instances else 1
            sub = {n: times * k for n, k in instance_counts(modules, owner).items()}
            blocks[block] = compose(records, sub)
            blocks[block]["depth"], blocks[block]["critical_path"] = composed_depth(modules, records, owner)
        per_record = [{"module": modules[n].base, "derived": n, "instances": counts[n], "key": keys[n],
                       **{k: records[n][k] for k in ("cells", "flops", "transistors", "depth")}}
                      for n in sorted(counts, key=lambda n: (modules[n].base, n))]
        return {"yosys": yosys, "params": params, "blocks": blocks, "records": per_record,
                "synthesized": len(missing),
                "seconds": round(sum(records[n].get("seconds", 0) for n in counts), 1)}


def main(argv):
    ap = argparse.ArgumentParser(prog="yosys_cost.py", description=__doc__.split("\n\n")[0])
    ap.add_argument("-chparam", nargs=2, action="append", default=[], metavar=("NAME", "VALUE"),
                    help="a tess_unit parameter (default: tess_pkg's)")
    ap.add_argument("--cache", default=str(REPO / "docs" / "results" / "costs" / "modules"),
                    help="record directory (default: docs/results/costs/modules)")
    ap.add_argument("--rtl", default=str(REPO / "rtl"), help="RTL directory with tess.f")
    ap.add_argument("--jobs", type=int, default=2, help="Yosys processes in parallel")
    ap.add_argument("--no-xilinx", action="store_true", help="skip synth_xilinx")
    ap.add_argument("--require-cached", action="store_true", help="synthesize nothing; fail if a record is missing")
    ap.add_argument("--json", help="write the result as JSON (- for stdout)")
    ap.add_argument("--depth-budget", type=int, default=DEPTH_BUDGET,
                    help=f"logic levels a register-to-register path may take (default {DEPTH_BUDGET})")
    ap.add_argument("--check-budget", action="store_true",
                    help="exit 3 when the unit's deepest path exceeds the depth budget")
    ap.add_argument("--compare-flat", action="store_true",
                    help="also synthesize the unit flattened (scripts/synth.sh) and print the composition's error")
    args = ap.parse_args(argv)
    for name, value in args.chparam:
        if not value.isdigit():
            ap.error(f"-chparam {name}: '{value}' is not a non-negative integer")
    defaults = package_defaults(args.rtl)
    unknown = [n for n, _ in args.chparam if n not in defaults]
    if unknown:
        ap.error(f"tess_pkg has no parameter {', '.join(unknown)}")
    start = time.monotonic()
    try:
        result = cost(dict(args.chparam), args.cache, args.rtl, args.jobs, not args.no_xilinx,
                      args.require_cached, log=sys.stderr)
    except CostError as e:
        print(f"yosys_cost.py: error: {e}", file=sys.stderr)
        return 1
    elapsed = time.monotonic() - start
    if args.json:
        text = json.dumps(result, indent=2)
        if args.json == "-":
            print(text)
            return 0
        Path(args.json).write_text(text + "\n")
    over = " ".join(f"{k}={v}" for k, v in result["params"].items()) or "defaults"
    print(f"tess_unit ({over}): {result['synthesized']} records synthesized, {elapsed:.0f} s")
    print(f"{'block':<10} {'cells':>8} {'flops':>7} {'transistors':>12} {'depth':>6}")
    for block, e in result["blocks"].items():
        print(f"{block:<10} {e['cells']:>8} {e['flops']:>7} {e['transistors']:>12} {e['depth']:>6}")
    print("deepest path of tess_unit (gates so far, at each boundary it crosses):")
    for where, gates in result["blocks"]["tess_unit"]["critical_path"]:
        print(f"  {gates:>4}  {where}")
    print(f"{'record':<14} {'inst':>4} {'transistors':>12} {'depth':>6}")
    for r in result["records"]:
        print(f"{r['module']:<14} {r['instances']:>4} {r['transistors']:>12} {r['depth']:>6}")
    depth = result["blocks"]["tess_unit"]["depth"]
    deep = over_budget(result, args.depth_budget)
    print(f"depth budget {args.depth_budget}: the unit's deepest path is {depth} levels, "
          + ("within it" if depth <= args.depth_budget else
             f"over it: clock at {clock_levels(depth, args.depth_budget)} levels, "
             f"{args.depth_budget / clock_levels(depth, args.depth_budget):.3f} of the budget's rate")
          + ("; records deeper than the budget: " + ", ".join(f"{m} {d}" for m, d in deep) if deep else ""))
    if args.compare_flat:
        return compare_flat(result, args)
    if args.check_budget and depth > args.depth_budget:
        return 3
    return 0


def compare_flat(result, args):
    """Synthesizes the same configuration flattened (scripts/synth.sh) and prints composed against
    flat for every block and figure, with the relative error of the composition."""
    with tempfile.TemporaryDirectory(prefix="tessim-flat-") as tmp:
        out = Path(tmp) / "flat.json"
        cmd = ["bash", str(REPO / "scripts" / "synth.sh"), "--json", str(out), "--jobs", str(args.jobs)]
        for name, value in result["params"].items():
            cmd += ["-chparam", name, str(value)]
        if args.no_xilinx:
            cmd.append("--no-xilinx")
        proc = subprocess.run(cmd, capture_output=True, text=True)
        if proc.returncode != 0:
            print(f"yosys_cost.py: error: synth.sh failed:\n{proc.stderr.strip()}", file=sys.stderr)
            return 1
        flat = json.loads(out.read_text())
    print(f"composed against flattened ({flat['seconds']} s flat):")
    print(f"{'block':<10} {'figure':<12} {'composed':>10} {'flat':>10} {'error':>8}")
    for block, composed in result["blocks"].items():
        reference = flat["blocks"].get(block)
        if not reference:
            continue
        figures = [(k, composed[k], reference[k]) for k in ("transistors", "cells", "flops", "depth")]
        figures += [(f"xilinx_{k}", v, reference["xilinx"][k]) for k, v in composed.get("xilinx", {}).items()
                    if k in ("lut", "ff", "dsp")]
        for name, c, f in figures:
            error = f"{100.0 * (c - f) / f:+.2f} %" if f else "-"
            print(f"{block:<10} {name:<12} {c:>10} {f:>10} {error:>8}")
    if args.json and args.json != "-":
        data = json.loads(Path(args.json).read_text())
        data["flat"] = flat["blocks"]
        Path(args.json).write_text(json.dumps(data, indent=2) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
