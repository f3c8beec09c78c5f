#!/usr/bin/python3
"""Silicon cost of a configuration of the unit on a real standard-cell library: area, leakage and
static timing on the OSU 0.18 um cells (docs/silicon.md).

    silicon.py [-chparam NAME VALUE]... [--jobs J] [--require-cached] [--json FILE]
               [--liberty FILE] [--cache DIR] [--flat]

Each record of scripts/yosys_cost.py (a module as elaborated for the configuration, its submodules
black boxes) is mapped onto the library with Yosys 0.23 (`synth`, `dfflibmap -liberty`, then
`abc -liberty` with a delay target and a load constraint, so that ABC buffers high fan-out nets and
sizes gates), and timed with OpenSTA: the worst register-to-register path inside the record, and
the delay of every path between the record's boundaries (input ports, registers, the ports of its
black boxes, output bits). A configuration's area and leakage are the records' sums over their
instances; its clock is the longest register-to-register path through the hierarchy, composed from
the records' boundary paths (each crossing counts a buffer's drive and an output load, see
CROSSING below). `--flat` maps and times the unit in one piece instead (minutes to an hour) to
measure what the composition misses.

A record is stored in docs/results/costs/silicon/ under a SHA-256 of its elaborated text (as the
generic records), the library as this flow reads it (the Liberty file with the wire-load model
added), the scripts and constraints, and the Yosys and OpenSTA versions: another library, another
wire-load model or another delay target misses every record.
"""

import argparse
import atexit
import hashlib
import json
import re
import shutil
import subprocess
import sys
import tempfile
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import cost_records  # noqa: E402  (the RTL sources' digest of a composed result)
import yosys_cost  # noqa: E402  (elaboration, records' text, instance counts, path composition)
import yosys_stat  # noqa: E402

REPO = Path(__file__).resolve().parent.parent
LIBERTY = Path("/usr/share/qflow/tech/osu018/osu018_stdcells.lib")
CACHE = REPO / "docs" / "results" / "costs" / "silicon"
RECORD_SCHEMA = 1
# ABC's delay target for mapping (ps): with it, ABC buffers and sizes towards the target. 5 ns is
# about the INT block's own path on this library (its three-way sum is the architecture's deepest
# single-cycle operation), so the target asks for speed where paths are long and costs little
# area elsewhere (docs/silicon.md: +3 % on tess_int against a plain mapping).
DELAY_TARGET_PS = 5000
# What a net at a record's boundary sees: inputs driven by a BUFX2, outputs loaded by 20 fF (about
# two gate inputs and their wire). ABC maps with the same constraint.
DRIVING_CELL = "BUFX2"
OUTPUT_LOAD_PF = 0.02
# Wire load: 0.2 fF per um of wire, 25 um of wire per fan-out (a local net of a placed block of
# about a square millimetre at 0.18 um); no wire resistance. Added to the library as its default
# wire-load model, so OpenSTA loads every net with its pins plus this estimate.
WIRE_LOAD = """\
  wire_load("tessim_local") {
    capacitance : 0.0002;
    resistance : 0;
    area : 0;
    slope : 25;
    fanout_length(1, 25);
    fanout_length(2, 50);
    fanout_length(3, 75);
    fanout_length(4, 100);
    fanout_length(6, 150);
    fanout_length(8, 200);
  }
  default_wire_load : "tessim_local";
  default_wire_load_mode : top;
"""
SEQUENTIAL = re.compile(r"^(DFF|LATCH)")
MAP_SCRIPT = """\
read_rtlil {job}
hierarchy -top {top}
flatten
synth -top {top}
dfflibmap -liberty {lib}
abc -liberty {lib} -D {delay} -constr {constr}
opt_clean
{evert}rename -top {top_name}
tee -q -o {out}.cells stat -liberty {lib}
write_verilog -noattr -noexpr {out}.v
"""
STA_HEADER = """\
read_liberty {lib}
read_verilog {netlist}
link_design {top}
{clock}
set data_inputs [concat {inputs}]
if {{[llength $data_inputs]}} {{
  set_input_delay 0 -clock clk $data_inputs
  set_driving_cell -lib_cell {drive} $data_inputs
}}
if {{[llength [all_outputs]]}} {{
  set_output_delay 0 -clock clk [all_outputs]
  set_load {load} [all_outputs]
}}
"""
PERIOD_NS = 100.0  # every path is reported by its slack against this; delay = period - slack
# Not timed as single-cycle paths: the synchronous reset is held for many cycles and, in silicon,
# distributed by a tree of its own (timed through the hierarchy, the buffers of every level's
# reset fan-out would add up into a path that no cycle of operation uses).
UNTIMED_PORTS = ("rst_ni",)


class SiliconError(Exception):
    pass


def tool_versions():
    try:
        sta = subprocess.run(["sta", "-version"], capture_output=True, text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError) as e:
        raise SiliconError(f"OpenSTA (sta) not available: {e}")
    return {"yosys": yosys_cost.yosys_version(), "sta": sta}


def library_text(liberty=LIBERTY):
    """The library as this flow reads it: the Liberty file with the wire-load model added."""
    try:
        text = Path(liberty).read_text()
    except OSError as e:
        raise SiliconError(f"{liberty}: cannot read the cell library ({e.strerror})")
    m = re.search(r"^\s*library\s*\(\s*\w+\s*\)\s*\{\s*$", text, re.M)
    if not m:
        raise SiliconError(f"{liberty}: no `library (name) {{` group")
    return text[:m.end()] + "\n" + WIRE_LOAD + text[m.end():]


def cell_library(text):
    """Cell name -> {"area": um2, "leakage_nw": nW, "sequential": bool} from Liberty text."""
    cells = {}
    for m in re.finditer(r"^\s*cell\s*\(\s*(\w+)\s*\)\s*\{(.*?)(?=^\s*cell\s*\(|\Z)", text, re.M | re.S):
        body = m.group(2)
        area = re.search(r"^\s*area\s*:\s*([\d.eE+-]+)", body, re.M)
        leak = re.search(r"^\s*cell_leakage_power\s*:\s*([\d.eE+-]+)", body, re.M)
        cells[m.group(1)] = {"area": float(area.group(1)) if area else 0.0,
                             "leakage_nw": float(leak.group(1)) if leak else 0.0,
                             "sequential": bool(SEQUENTIAL.match(m.group(1)) or re.search(r"^\s*ff\s*\(", body, re.M))}
    if not cells:
        raise SiliconError("the cell library defines no cells")
    return cells


def lef_areas(lef):
    """Macro name -> area in um2 (SIZE W BY H) from a LEF file; {} when there is none."""
    try:
        text = Path(lef).read_text()
    except OSError:
        return {}
    return {m.group(1): float(m.group(2)) * float(m.group(3))
            for m in re.finditer(r"^MACRO\s+(\w+)\s*$.*?^\s*SIZE\s+([\d.]+)\s+BY\s+([\d.]+)", text, re.M | re.S)}


class Library:
    """The library a run maps onto, written once to a work directory for Yosys, ABC and OpenSTA."""

    def __init__(self, liberty=LIBERTY, work=None):
        self.source = Path(liberty)
        self.text = library_text(liberty)
        self.digest = hashlib.sha256(self.text.encode()).hexdigest()
        self.cells = cell_library(self.text)
        # OSU018's Liberty gives its LATCH an area of 0; the cell's footprint in the LEF beside it
        # (5.6 x 10 um) is its area. No mapped record uses a latch; the clock gates are built of one.
        lef = lef_areas(self.source.with_suffix(".lef"))
        self.area_from_lef = sorted(c for c, v in self.cells.items() if v["area"] == 0 and c in lef)
        for c in self.area_from_lef:
            self.cells[c]["area"] = lef[c]
        if work is None:  # a directory of its own, removed when the process ends
            work = tempfile.mkdtemp(prefix="tessim-silicon-lib-")
            atexit.register(shutil.rmtree, work, True)
        self.work = Path(work)
        self.work.mkdir(parents=True, exist_ok=True)
        self.path = self.work / "cells.lib"
        self.path.write_text(self.text)
        self.constr = self.work / "abc.constr"
        self.constr.write_text(f"set_driving_cell {DRIVING_CELL}\nset_load {OUTPUT_LOAD_PF}\n")


def record_key(text, lib, versions):
    ident = {"schema": RECORD_SCHEMA, "library": lib.digest, "map": MAP_SCRIPT, "sta": STA_HEADER,
             "delay_ps": DELAY_TARGET_PS, "drive": DRIVING_CELL, "load_pf": OUTPUT_LOAD_PF,
             "untimed": UNTIMED_PORTS, **versions}
    h = hashlib.sha256(json.dumps(ident, sort_keys=True).encode())
    h.update(text.encode())
    return h.hexdigest()


def tcl_name(name):
    """A port or pin name as an OpenSTA pattern: brackets that belong to the name escaped."""
    return "{" + name.replace("[", "\\[").replace("]", "\\]") + "}"


def netlist_ports(netlist_text):
    """(direction, name, width) of every port of a written netlist."""
    ports = []
    for m in re.finditer(r"^\s*(input|output)\s+(?:\[(\d+):(\d+)\]\s+)?(\\\S+|\w+)\s*;", netlist_text, re.M):
        name = m.group(4)[1:] if m.group(4).startswith("\\") else m.group(4)
        width = abs(int(m.group(2)) - int(m.group(3))) + 1 if m.group(2) else 1
        ports.append((m.group(1), name, width))
    return ports


def register_names(netlist_text, cells):
    """Flip-flop instance -> the register bit it holds (the net on its Q), in RTL terms."""
    seq = "|".join(sorted(c for c, v in cells.items() if v["sequential"]))
    names = {}
    if not seq:
        return names
    for m in re.finditer(rf"^\s*({seq})\s+(\S+)\s*\((.*?)\);", netlist_text, re.M | re.S):
        q = re.search(r"\.Q\((.*?)\)", m.group(3), re.S)
        if q:
            net = " ".join(q.group(1).split())
            names[m.group(2)] = net[1:].replace(" [", "[") if net.startswith("\\") else net
    return names


ENDPOINT = re.compile(r"^(\S+)\s+(?:\((\w+)\)\s+)?(-?[\d.]+)\s+(-?[\d.]+)\s+(-?[\d.]+)\s+\((MET|VIOLATED)\)")


def parse_ends(text):
    """`report_checks -format end` -> [(endpoint, delay ns)], delay = period - slack (so a flip-flop's
    setup time is in it and an output's external delay of 0 is not)."""
    out = []
    for line in text.splitlines():
        m = ENDPOINT.match(line.strip())
        if m:
            out.append((m.group(1), round(PERIOD_NS - float(m.group(5)), 4)))
    return out


def time_netlist(lib, netlist, top, boxes, work, whole=False):
    """OpenSTA on a mapped record: {"worst": {...}, "paths": [[source, sink, ns]]}. Sources are
    input ports ("in:P"), registers ("reg") and black-box output ports ("box:INST.P"); sinks are
    output ports ("out:P"), registers ("reg") and black-box input ports ("box:INST.P"), the tags
    of scripts/yosys_cost.py so that its path composition applies. `whole` (a flattened unit)
    reports the worst register-to-register path only."""
    text = Path(netlist).read_text()
    # The black boxes' pins became ports named INST.PIN; OpenSTA 2019 refuses delays on escaped
    # port names with brackets and dots, so they are renamed box<i> for timing.
    pins = {}
    for i, (d, n, w) in enumerate(netlist_ports(text)):
        if not re.fullmatch(r"\w+", n):
            pins[f"box{i}"] = n
            text = text.replace(f"\\{n} ", f"box{i} ")
    Path(netlist).write_text(text)
    ports = netlist_ports(text)
    names = register_names(text, lib.cells)

    def owner(port):  # (black-box instance, pin) or None for a port of the record itself
        port = pins.get(port, port)
        for inst in boxes:
            if port.startswith(inst + "."):
                return inst, port[len(inst) + 1:]
        return None

    def pattern(name, width):
        return tcl_name(name) if width == 1 else "{" + name.replace("[", "\\[").replace("]", "\\]") + "[*]}"

    clock_ports = [n for d, n, w in ports if d == "input" and n == "clk_i"]
    clock = (f"create_clock -name clk -period {PERIOD_NS} [get_ports clk_i]" if clock_ports
             else f"create_clock -name clk -period {PERIOD_NS}")
    data_in = [(n, w) for d, n, w in ports if d == "input" and n != "clk_i"]
    timed_in = [(n, w) for n, w in data_in if pins.get(n, n).rsplit(".", 1)[-1] not in UNTIMED_PORTS]
    script = STA_HEADER.format(lib=lib.path, netlist=netlist, top=top, clock=clock, drive=DRIVING_CELL,
                               load=OUTPUT_LOAD_PF,
                               inputs=" ".join(f"[get_ports {pattern(n, w)}]" for n, w in data_in))
    script += ('puts "#WORST"\nif {[llength [all_registers]]} {\n  report_checks -from [all_registers -clock_pins] '
               '-to [all_registers -data_pins] -format full -digits 4\n}\n')
    groups = []
    if not whole:
        if register_names(text, lib.cells) or re.search(r"^\s*(DFF|LATCH)\w*\s", text, re.M):
            groups.append(("reg", "[all_registers -clock_pins]"))
        for n, w in timed_in:
            box = owner(n)
            groups.append((f"box:{box[0]}.{box[1]}" if box else f"in:{n}", f"[get_ports {pattern(n, w)}]"))
        for tag, objects in groups:
            script += (f'puts {{#FROM {tag}}}\nreport_checks -from {objects} -group_count 100000000 '
                       f'-endpoint_count 1 -format end -digits 4\n')
        if groups and groups[0][0] == "reg":  # the register each boundary sink's worst path starts at
            for n, w in [(n, w) for d, n, w in ports if d == "output"]:
                if pins.get(n, n).rsplit(".", 1)[-1] in ("clk_i",) + UNTIMED_PORTS:
                    continue
                script += (f'puts {{#START {n}}}\nreport_checks -from [all_registers -clock_pins] '
                           f'-to [get_ports {pattern(n, w)}] -format full -digits 4\n')
    script += "exit\n"
    tcl = Path(work) / "sta.tcl"
    tcl.write_text(script)
    proc = subprocess.run(["sta", "-no_init", "-no_splash", "-exit", str(tcl)], capture_output=True, text=True,
                          cwd=work)
    if proc.returncode != 0 or "Error" in proc.stdout:
        tail = "\n".join((proc.stdout + proc.stderr).splitlines()[-15:])
        raise SiliconError(f"OpenSTA failed on {top}:\n{tail}")
    sections = re.split(r"^#(WORST|FROM .*|START .*)$", proc.stdout, flags=re.M)
    worst = {"ns": 0.0, "from": None, "to": None, "cells": 0}
    paths = {}
    ends = {}  # "source -> sink": [start register, end register] of the worst such path
    out_ports = {n for d, n, w in ports if d == "output"}
    for head, body in zip(sections[1::2], sections[2::2]):
        if head == "WORST":
            worst = parse_worst(body, names)
            continue
        if head.startswith("START "):
            start = re.search(r"Startpoint:\s+(\S+)", body)
            port = head[6:]
            box = owner(port)
            sink = f"box:{box[0]}.{box[1]}" if box else f"out:{port}"
            if start and f"reg -> {sink}" in ends:
                ends[f"reg -> {sink}"][0] = names.get(start.group(1), start.group(1))
            continue
        source = head[5:]
        for endpoint, ns in parse_ends(body):
            pin = endpoint.rsplit("/", 1)
            if len(pin) == 2:
                sink = "reg"
                if ns > paths.get((source, sink), -1.0):
                    ends[f"{source} -> reg"] = [None, names.get(pin[0], pin[0])]
            else:
                base = re.sub(r"\[\d+\]$", "", endpoint)
                if pins.get(base, base).rsplit(".", 1)[-1] in ("clk_i",) + UNTIMED_PORTS:
                    continue
                box = owner(base)
                if box:
                    sink = f"box:{box[0]}.{box[1]}"
                elif base in out_ports or endpoint in out_ports:
                    sink = f"out:{base}"
                else:
                    raise SiliconError(f"{top}: OpenSTA endpoint {endpoint} is no port of the record")
            if source == "reg" and sink == "reg":
                continue  # the worst one is `worst`; composition takes a record's own reg-to-reg max
            if source == "reg":
                ends.setdefault(f"reg -> {sink}", [None, None])
            key = (source, sink)
            paths[key] = max(paths.get(key, 0.0), ns)
    rows = sorted([s, t, ns] for (s, t), ns in paths.items())
    if worst["ns"] > 0:
        rows.append(["reg", "reg", worst["ns"]])
    return {"worst": worst, "paths": rows, "ends": dict(sorted(ends.items()))}


def parse_worst(body, names):
    """The worst register-to-register path of a `report_checks -format full`: its delay (period -
    slack), its start and end registers in RTL terms, and its number of cells."""
    start = re.search(r"Startpoint:\s+(\S+)", body)
    end = re.search(r"Endpoint:\s+(\S+)", body)
    slack = re.search(r"^\s*(-?[\d.]+)\s+slack", body, re.M)
    if not (start and end and slack):
        return {"ns": 0.0, "from": None, "to": None, "cells": 0}
    cells = len(re.findall(r"^\s*-?[\d.]+\s+-?[\d.]+\s+[v^]\s+\S+/\S+\s+\(\w+\)", body, re.M))

    def rtl(inst):
        return names.get(inst, inst)

    return {"ns": round(PERIOD_NS - float(slack.group(1)), 4), "from": rtl(start.group(1)),
            "to": rtl(end.group(1).rsplit("/", 1)[0]), "cells": cells}


def write_mapped(lib, name, text, boxes, work):
    """Maps one record onto the library with MAP_SCRIPT: WORK/mapped.v (the netlist, top `rec`,
    the black boxes' pins as ports named INST.PIN) and WORK/mapped.cells (its `stat`). Returns
    WORK/mapped."""
    job = Path(work) / "job.il"
    job.write_text(text)
    out = Path(work) / "mapped"
    evert = "expose -evert t:*tess_*\n" if boxes else ""
    script = Path(work) / "map.ys"
    script.write_text(MAP_SCRIPT.format(job=job, top=name, lib=lib.path, delay=DELAY_TARGET_PS, constr=lib.constr,
                                        evert=evert, top_name="rec", out=out))
    yosys_cost.run_yosys(script, Path(work) / "map.log", work)
    return out


def map_record(lib, name, text, boxes, work, whole=False):
    """Maps one record (or, with `whole`, a flattened design) onto the library and times it;
    `boxes` are its black-box instances, whose pins become ports of the mapped netlist."""
    start = time.monotonic()
    out = write_mapped(lib, name, text, boxes, work)
    total, cells = yosys_stat.cell_table(Path(f"{out}.cells").read_text())
    unknown = sorted(c for c in cells if c not in lib.cells)
    if unknown:
        raise SiliconError(f"{name}: cells the library does not define after mapping: {', '.join(unknown)}")
    timing = time_netlist(lib, f"{out}.v", "rec", sorted(boxes, key=len, reverse=True), work, whole)
    area_seq = sum(n * lib.cells[c]["area"] for c, n in cells.items() if lib.cells[c]["sequential"])
    area_comb = sum(n * lib.cells[c]["area"] for c, n in cells.items() if not lib.cells[c]["sequential"])
    result = {
        "cells": total or 0,
        "flops": sum(n for c, n in cells.items() if lib.cells[c]["sequential"]),
        "buffers": sum(n for c, n in cells.items() if c.startswith(("BUF", "CLKBUF"))),
        "area_um2": {"comb": round(area_comb, 1), "seq": round(area_seq, 1)},
        "leakage_nw": round(sum(n * lib.cells[c]["leakage_nw"] for c, n in cells.items()), 3),
        "cell_counts": dict(sorted(cells.items())),
        "worst": timing["worst"],
        "ends": timing["ends"],
        "paths": timing["paths"],
        "seconds": round(time.monotonic() - start, 1),
    }
    return result


def record_path(cache, key):
    return Path(cache) / f"{key}.json"


def write_record(path, record):
    record = json.loads(json.dumps(record))
    yosys_cost.write_record_rows(path, record, record["result"].pop("paths"))


def read_record(path):
    result = yosys_cost.read_record(path)
    result.setdefault("paths", [])
    return result


def plan(params, lib, versions, rtl_dir=REPO / "rtl"):
    """The configuration's records: (modules, top, counts, {derived name: (text, instances, key)})."""
    with tempfile.TemporaryDirectory(prefix="tessim-silicon-") as tmp:
        modules = yosys_cost.elaborate(rtl_dir, params, tmp)
    top = yosys_cost.top_name(modules)
    counts = yosys_cost.instance_counts(modules, top)
    jobs = {}
    for name in counts:
        text, _ = yosys_cost.record_text(modules, name)
        instances = sorted(inst for inst, child in modules[name].instances.items()
                           if not yosys_cost.is_inline(modules[child]))
        jobs[name] = (text, instances, record_key(text, lib, versions))
    return modules, top, counts, jobs


def synthesize(jobs_by_key, lib, cache, jobs=2, log=None):
    """Maps and times the records in `jobs_by_key` (key -> (module base, derived, text, instances)),
    largest first, `jobs` at a time, and stores them."""
    versions = tool_versions()

    def work(key):
        base, name, text, instances = jobs_by_key[key]
        with tempfile.TemporaryDirectory(prefix="tessim-silicon-rec-") as tmp:
            result = map_record(lib, name, text, instances, tmp)
        write_record(record_path(cache, key), {"schema": RECORD_SCHEMA, "module": base, "derived": name,
                                               "library": str(lib.source), "library_sha256": lib.digest,
                                               **versions, "result": result})
        if log:
            area = result["area_um2"]["comb"] + result["area_um2"]["seq"]
            print(f"  {base:<16} {area / 1e6:8.4f} mm2, worst reg-reg {result['worst']['ns']:6.3f} ns"
                  f" ({result['seconds']} s)", file=log, flush=True)

    if log and jobs_by_key:
        print(f"silicon: {len(jobs_by_key)} records to map and time", file=log, flush=True)
    with ThreadPoolExecutor(max_workers=max(1, jobs)) as pool:
        list(pool.map(work, sorted(jobs_by_key, key=lambda k: -len(jobs_by_key[k][2]))))


# Reported blocks: those of scripts/yosys_cost.py (the unit, the CPG with its copies together, one
# INT block) and the TE with its INT blocks, whose loop through the INT blocks is the path the
# INT-block count and latency act on.
BLOCKS = {**yosys_cost.BLOCKS, "tess_te": False}


def composed_key(params, lib, versions, rtl_dir=REPO / "rtl"):
    """A configuration's composed result is stored under the RTL sources (comments aside), the
    parameters, the library and everything a record's key holds but the record's text."""
    ident = {"schema": RECORD_SCHEMA, "library": lib.digest, "map": MAP_SCRIPT, "sta": STA_HEADER,
             "delay_ps": DELAY_TARGET_PS, "drive": DRIVING_CELL, "load_pf": OUTPUT_LOAD_PF, "untimed": UNTIMED_PORTS,
             "blocks": sorted(BLOCKS), "sources": cost_records.sources_digest(rtl_dir), "params": params, **versions}
    return hashlib.sha256(json.dumps(ident, sort_keys=True).encode()).hexdigest()


_LIBRARIES = {}


def library(liberty=LIBERTY):
    """The Library of a Liberty file, written out once per process."""
    key = str(Path(liberty).resolve())
    if key not in _LIBRARIES:
        _LIBRARIES[key] = Library(liberty)
    return _LIBRARIES[key]


def cost(params, cache=CACHE, rtl_dir=REPO / "rtl", jobs=2, require_cached=False, log=None, liberty=LIBERTY):
    """Silicon cost of tess_unit with `params`: area, leakage, clock, per block and per record.
    A stored composed result of the current RTL (beside the records) is used while every record
    it names is present; otherwise the configuration is elaborated and composed, and stored."""
    params = cost_records.normalized(params, rtl_dir)
    versions = tool_versions()
    lib = library(liberty)
    stored = Path(cache).parent / "silicon-configurations" / f"{composed_key(params, lib, versions, rtl_dir)}.json"
    if stored.exists():
        result = json.loads(stored.read_text())
        if all(record_path(cache, r["key"]).exists() for r in result["records"]):
            return result
    result = compose_configuration(params, lib, versions, cache, rtl_dir, jobs, require_cached, log)
    stored.parent.mkdir(parents=True, exist_ok=True)
    partial = stored.with_name(stored.name + ".tmp")
    partial.write_text(json.dumps(dict(result, synthesized=0), indent=1, sort_keys=True) + "\n")
    partial.replace(stored)
    return result


def compose_configuration(params, lib, versions, cache, rtl_dir, jobs, require_cached, log):
    modules, top, counts, jobs_of = plan(params, lib, versions, rtl_dir)
    missing = {jobs_of[n][2]: (modules[n].base, n, jobs_of[n][0], jobs_of[n][1]) for n in counts
               if not record_path(cache, jobs_of[n][2]).exists()}
    if missing and require_cached:
        raise SiliconError("no silicon record for " + ", ".join(sorted({v[0] for v in missing.values()})))
    synthesize(missing, lib, cache, jobs, log)
    records = {n: read_record(record_path(cache, jobs_of[n][2])) for n in counts}
    blocks = {}
    for block, all_instances in BLOCKS.items():
        owner = next(n for n in counts if modules[n].base == block)
        times = counts[owner] if all_instances else 1
        sub = {n: times * k for n, k in yosys_cost.instance_counts(modules, owner).items()}
        blocks[block] = compose(records, sub)
        ns, path = yosys_cost.composed_depth(modules, records, owner)
        blocks[block]["clock_ns"] = round(ns, 4)
        blocks[block]["critical_path"] = [[where, round(t, 4)] for where, t in path]
        blocks[block]["critical_path_ends"] = path_ends(modules, records, owner, path)
    unit = blocks["tess_unit"]
    per_record = [{"module": modules[n].base, "derived": n, "instances": counts[n], "key": jobs_of[n][2],
                   "area_um2": round(records[n]["area_um2"]["comb"] + records[n]["area_um2"]["seq"], 1),
                   "leakage_nw": records[n]["leakage_nw"], "worst_ns": records[n]["worst"]["ns"],
                   "worst_from": records[n]["worst"]["from"], "worst_to": records[n]["worst"]["to"]}
                  for n in sorted(counts, key=lambda n: (modules[n].base, n))]
    return {"library": str(lib.source), "library_sha256": lib.digest, **versions, "params": params,
            "area_mm2": round(unit["area_um2"] / 1e6, 6), "clock_ns": unit["clock_ns"],
            "clock_mhz": round(1000.0 / unit["clock_ns"], 3) if unit["clock_ns"] else None,
            "leakage_uw": round(unit["leakage_nw"] / 1000.0, 4),
            "blocks": blocks, "records": per_record, "synthesized": len(missing)}


def compose(records, counts):
    out = {"cells": 0, "flops": 0, "buffers": 0, "area_um2": 0.0, "area_comb_um2": 0.0, "area_seq_um2": 0.0,
           "leakage_nw": 0.0}
    for name, n in counts.items():
        r = records[name]
        out["cells"] += n * r["cells"]
        out["flops"] += n * r["flops"]
        out["buffers"] += n * r["buffers"]
        out["area_comb_um2"] += n * r["area_um2"]["comb"]
        out["area_seq_um2"] += n * r["area_um2"]["seq"]
        out["leakage_nw"] += n * r["leakage_nw"]
    out["area_um2"] = out["area_comb_um2"] + out["area_seq_um2"]
    return {k: (round(v, 3) if isinstance(v, float) else v) for k, v in out.items()}


def path_ends(modules, records, owner, path):
    """The composed critical path's start and end registers in RTL terms (instance path and
    register bit): from the worst path of the first record it leaves and of the last it enters."""
    if len(path) < 2:
        return None

    def split(node):
        where, tag = node.split(" ", 1)
        return where, tag

    def record_at(where):
        name = owner
        for inst in [p for p in where.split("/") if p]:
            name = modules[name].instances[inst]
        return name

    def tag_in(where, node):  # a node as the tag of the record at `where` sees it
        w, tag = split(node)
        if w == where:
            return "reg" if tag.startswith("reg") else tag
        child = w[len(where) + 1:]
        return f"box:{child}.{tag.split(':', 1)[1]}"

    def named(where, reg):
        if reg is None:
            return f"{where.strip('/') or 'tess_unit'} (a register)"
        return f"{where.strip('/')}.{reg}" if where.strip("/") else reg

    (first, _), (second, _) = path[0], path[1]
    (last, _), (before, _) = path[-1], path[-2]
    first_at, last_at = split(first)[0], split(last)[0]
    if len(path) == 2 and first_at == last_at:
        w = records[record_at(first_at)]["worst"]
        return {"from": named(first_at, w["from"]), "to": named(last_at, w["to"])}
    start = records[record_at(first_at)].get("ends", {}).get(f"reg -> {tag_in(first_at, second)}", [None, None])[0]
    end = records[record_at(last_at)].get("ends", {}).get(f"{tag_in(last_at, before)} -> reg", [None, None])[1]
    return {"from": named(first_at, start), "to": named(last_at, end)}


def flat(params, lib, rtl_dir=REPO / "rtl"):
    """The unit mapped and timed in one piece: area, leakage, worst register-to-register path."""
    params = cost_records.normalized(params, rtl_dir)
    sources = " ".join(str(p) for p in yosys_cost.rtl_sources(rtl_dir))
    chparam = "".join(f"chparam -set {k} {v} tess_unit\n" for k, v in params.items())
    with tempfile.TemporaryDirectory(prefix="tessim-silicon-flat-") as tmp:
        script = Path(tmp) / "read.ys"
        script.write_text(f"read_verilog -sv -I{rtl_dir} {sources}\n{chparam}hierarchy -check -top tess_unit\n"
                          f"proc\nflatten\nwrite_rtlil {tmp}/flat.il\n")
        yosys_cost.run_yosys(script, Path(tmp) / "read.log", tmp)
        text = (Path(tmp) / "flat.il").read_text()
        name = re.search(r"^module (\S*tess_unit\S*)$", text, re.M).group(1)
        result = map_record(lib, name, text, [], tmp, whole=True)
    area = result["area_um2"]["comb"] + result["area_um2"]["seq"]
    return {"params": params, "area_mm2": round(area / 1e6, 6), "area_um2": result["area_um2"],
            "cells": result["cells"], "flops": result["flops"], "buffers": result["buffers"],
            "leakage_nw": result["leakage_nw"], "clock_ns": result["worst"]["ns"], "worst": result["worst"],
            "seconds": result["seconds"]}


def main(argv):
    ap = argparse.ArgumentParser(prog="silicon.py", description=__doc__.split("\n\n")[0])
    ap.add_argument("-chparam", nargs=2, action="append", default=[], metavar=("NAME", "VALUE"),
                    help="a tess_unit parameter (default: tess_pkg's)")
    ap.add_argument("--cache", default=str(CACHE), help="record directory (default: docs/results/costs/silicon)")
    ap.add_argument("--liberty", default=str(LIBERTY), help=f"cell library (default: {LIBERTY})")
    ap.add_argument("--jobs", type=int, default=2, help="Yosys processes in parallel")
    ap.add_argument("--require-cached", action="store_true", help="map nothing; fail if a record is missing")
    ap.add_argument("--flat", action="store_true", help="map and time the unit in one piece (slow)")
    ap.add_argument("--json", help="write the result as JSON (- for standard output)")
    args = ap.parse_args(argv)
    for name, value in args.chparam:
        if not value.isdigit():
            ap.error(f"-chparam {name}: '{value}' is not a non-negative integer")
    defaults = yosys_cost.package_defaults(REPO / "rtl")
    unknown = [n for n, _ in args.chparam if n not in defaults]
    if unknown:
        ap.error(f"tess_pkg has no parameter {', '.join(unknown)}")
    start = time.monotonic()
    try:
        if args.flat:
            result = flat(dict(args.chparam), library(args.liberty))
        else:
            result = cost(dict(args.chparam), args.cache, jobs=args.jobs, require_cached=args.require_cached,
                          log=sys.stderr, liberty=args.liberty)
    except (SiliconError, yosys_cost.CostError) as e:
        print(f"silicon.py: error: {e}", file=sys.stderr)
        return 1
    if args.json:
        text = json.dumps(result, indent=1) + "\n"
        if args.json == "-":
            sys.stdout.write(text)
            return 0
        partial = Path(args.json + ".tmp")
        partial.write_text(text)
        partial.replace(args.json)
    over = " ".join(f"{k}={v}" for k, v in result["params"].items()) or "defaults"
    print(f"tess_unit ({over}){' flattened' if args.flat else ''}: {time.monotonic() - start:.0f} s")
    print(f"  area {result['area_mm2']:.4f} mm2, clock {result['clock_ns']:.3f} ns "
          f"({1000.0 / result['clock_ns']:.1f} MHz)" if result["clock_ns"] else "")
    if args.flat:
        w = result["worst"]
        print(f"  worst path {w['from']} -> {w['to']}, {w['cells']} cells")
        return 0
    print(f"{'block':<10} {'mm2':>9} {'comb mm2':>9} {'seq mm2':>9} {'cells':>8} {'flops':>7} {'leak uW':>8} {'ns':>7}")
    for block, e in result["blocks"].items():
        print(f"{block:<10} {e['area_um2'] / 1e6:9.4f} {e['area_comb_um2'] / 1e6:9.4f} {e['area_seq_um2'] / 1e6:9.4f}"
              f" {e['cells']:>8} {e['flops']:>7} {e['leakage_nw'] / 1e3:8.2f} {e['clock_ns']:7.3f}")
    ends = result["blocks"]["tess_unit"]["critical_path_ends"]
    if ends:
        print(f"critical path: {ends['from']} -> {ends['to']}")
    for where, ns in result["blocks"]["tess_unit"]["critical_path"]:
        print(f"  {ns:8.3f} ns  {where}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
