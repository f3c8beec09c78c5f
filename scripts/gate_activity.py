#!/usr/bin/python3
"""Switching activity of a mapped netlist (scripts/silicon.py's records) and its power on the cell
library (docs/silicon.md, Energy).

The netlist is Yosys's `write_verilog -noattr -noexpr` output of a record mapped onto the OSU
0.18 um cells. Its sources are its input ports, the flip-flops' outputs and constants; every other
net is driven by a combinational cell whose Liberty `function` is known. Given, for every source
bit, the probability that it changes between consecutive cycles (its toggle density, from the
RTL's toggle counts) and its probability of being 1, the activity of every net follows under the
zero-delay, lag-one model: each cell's inputs are independent two-state chains, the output changes
in a cycle when its value before and after differ,

    P(y = 1)     = sum over input vectors v with f(v) = 1 of prod P(x_i = v_i)
    P(y changes) = sum over pairs (a, b) with f(a) != f(b) of prod P(x_i: a_i -> b_i)

Densities stay at most one a cycle; glitches are not counted and reconvergent fan-out is taken as
independent. OpenSTA 2.0.17 (Debian's) does not propagate activity through combinational cells,
so the activities are computed here and annotated on every cell pin; OpenSTA then prices them with
the Liberty internal energy tables, the pin and wire-load capacitances, and the clock.
"""

import itertools
import re
import subprocess
from pathlib import Path

CONST = {"1'h0": 0.0, "1'h1": 1.0, "1'b0": 0.0, "1'b1": 1.0, "1'hx": 0.0, "1'bx": 0.0, "1'bz": 0.0}


class NetlistError(Exception):
    pass


def liberty_functions(text):
    """Cell -> {"inputs": [pin], "outputs": {pin: python expression}, "sequential": bool,
    "clock": pin or None} from Liberty text."""
    cells = {}
    for m in re.finditer(r"^\s*cell\s*\(\s*(\w+)\s*\)\s*\{(.*?)(?=^\s*cell\s*\(|\Z)", text, re.M | re.S):
        body = m.group(2)
        ins, outs, clock = [], {}, None
        for p in re.finditer(r"^\s*pin\s*\(\s*(\w+)\s*\)\s*\{(.*?)(?=^\s*pin\s*\(|\Z)", body, re.M | re.S):
            direction = re.search(r"direction\s*:\s*(\w+)", p.group(2))
            if not direction:
                continue
            if direction.group(1) == "input":
                ins.append(p.group(1))
                if re.search(r"^\s*clock\s*:\s*true", p.group(2), re.M):
                    clock = p.group(1)
            else:
                f = re.search(r'function\s*:\s*"([^"]*)"', p.group(2))
                outs[p.group(1)] = f.group(1) if f else None
        sequential = bool(re.search(r"^\s*(ff|latch)\s*\(", body, re.M))
        cells[m.group(1)] = {"inputs": ins, "outputs": {k: (None if sequential else python_expr(v))
                                                        for k, v in outs.items()},
                             "sequential": sequential, "clock": clock}
    return cells


def python_expr(function):
    """A Liberty function ("(!((A B)+C))", "(A^B)") as a Python expression over 0/1 pin values,
    to be taken & 1 (`!` becomes `~`). Python's precedence (~, &, ^, |) differs from Liberty's (!,
    ^, AND, OR) between XOR and AND only; the library's functions parenthesize those."""
    if function is None:
        return None
    s = function.replace("*", " ").replace("&", " ").replace("|", "+")
    tokens = re.findall(r"\w+|[!()+^']", s)
    out = []
    prev_operand = False
    for t in tokens:
        operand_start = t == "(" or t == "!" or re.fullmatch(r"\w+", t)
        if prev_operand and operand_start:
            out.append("&")  # juxtaposition is AND
        if t == "!":
            out.append("~")
        elif t == "+":
            out.append("|")
        elif t == "'":
            out[-1] = f"(~{out[-1]})"
        elif re.fullmatch(r"\w+", t):
            out.append(f"v['{t}']" if not t.isdigit() else t)
        else:
            out.append(t)
        prev_operand = t == ")" or t == "'" or bool(re.fullmatch(r"\w+", t))
    return "".join(out)


def cell_tables(functions):
    """Cell -> {output pin: (inputs, truth table, input vectors with output 1, pairs of input vectors
    (before, after) whose outputs differ)} for combinational cells; a vector's bit i (from the
    top) is input i."""
    tables = {}
    for cell, f in functions.items():
        if f["sequential"]:
            continue
        per = {}
        for pin, expr in f["outputs"].items():
            if expr is None:
                continue
            used = [i for i in f["inputs"] if f"v['{i}']" in expr]
            code = compile(expr, f"{cell}.{pin}", "eval")
            table = []
            for bits in itertools.product((0, 1), repeat=len(used)):
                table.append(eval(code, {}, {"v": dict(zip(used, bits))}) & 1)  # noqa: S307 (the library's own functions)
            ones = [v for v, out in enumerate(table) if out]
            diff = [(a, b) for a in range(len(table)) for b in range(len(table)) if table[a] != table[b]]
            per[pin] = (used, table, ones, diff)
        tables[cell] = per
    return tables


def propagate_cell(entry, probs, dens):
    """(P(y = 1), P(y changes in a cycle)) of one cell output under the zero-delay, lag-one model:
    each input is 1 with probability p and changes between consecutive cycles with probability d,
    independently of the others; the output changes when its values before and after differ."""
    used, table, ones, diff = entry
    n = len(probs)
    stay = []  # per input: P(0->0), P(0->1), P(1->0), P(1->1)
    for p, d in zip(probs, dens):
        d = min(d, 2 * min(p, 1 - p))
        stay.append(((1 - p) - d / 2, d / 2, d / 2, p - d / 2))
    p_one = 0.0
    for v in ones:
        w = 1.0
        for i in range(n):
            w *= probs[i] if (v >> (n - 1 - i)) & 1 else 1.0 - probs[i]
        p_one += w
    if not any(dens):
        return p_one, 0.0
    change = 0.0
    for a, b in diff:
        w = 1.0
        for i in range(n):
            shift = n - 1 - i
            w *= stay[i][((a >> shift) & 1) * 2 + ((b >> shift) & 1)]
            if w == 0.0:
                break
        change += w
    return p_one, change


def canonical(ref):
    """A net reference of the netlist (`\\a.b [3]`, `_12_`, `x[0]`) as one name (`a.b[3]`)."""
    ref = ref.strip()
    if ref.startswith("\\"):
        ref = ref[1:]
    return re.sub(r"\s+\[", "[", ref).strip()


def parse_netlist(text):
    """(ports {name: (direction, width)}, widths {name: (msb, lsb)}, cells [(type, name, {pin: net})],
    aliases [(lhs bit, rhs bit or constant)]) of a written netlist."""
    widths = {}
    ports = {}
    for m in re.finditer(r"^\s*(input|output|wire|reg)\s+(?:\[(\d+):(\d+)\]\s+)?(\\\S+|\w+)\s*;", text, re.M):
        name = canonical(m.group(4))
        rng = (int(m.group(2)), int(m.group(3))) if m.group(2) else None
        widths[name] = rng
        if m.group(1) in ("input", "output"):
            ports[name] = (m.group(1), rng)
    cells = []
    for m in re.finditer(r"^\s*(\w+)\s+(\\\S+|\w+)\s*\((.*?)\);", text, re.M | re.S):
        if m.group(1) in ("module", "assign", "input", "output", "wire", "reg"):
            continue
        pins = {p.group(1): canonical(p.group(2)) for p in re.finditer(r"\.(\w+)\(\s*([^()]*?)\s*\)", m.group(3))}
        cells.append((m.group(1), canonical(m.group(2)), pins))
    aliases = []
    for m in re.finditer(r"^\s*assign\s+(.*?)\s*=\s*(.*?)\s*;", text, re.M | re.S):
        lhs, rhs = bits(m.group(1), widths), bits(m.group(2), widths)
        if len(lhs) != len(rhs):
            raise NetlistError(f"assign of {len(rhs)} bits to {len(lhs)}: {m.group(0)[:120]}")
        aliases += list(zip(lhs, rhs))
    return ports, widths, cells, aliases


def bits(expr, widths):
    """The bits of an expression of a written netlist, most significant first."""
    expr = expr.strip()
    if expr.startswith("{"):
        out = []
        for part in split_concat(expr[1:-1]):
            out += bits(part, widths)
        return out
    c = re.fullmatch(r"(\d+)'([hbd])([0-9a-fA-FxXzZ]+)", expr)
    if c:
        n = int(c.group(1))
        digits = c.group(3).lower()
        if "x" in digits or "z" in digits:
            return ["1'h0"] * n
        value = int(digits, {"h": 16, "b": 2, "d": 10}[c.group(2)])
        return [f"1'h{(value >> (n - 1 - i)) & 1}" for i in range(n)]
    m = re.fullmatch(r"(\\\S+|[\w$.]+)\s*(?:\[(\d+)(?::(\d+))?\])?", expr)
    if not m:
        raise NetlistError(f"cannot read the netlist expression {expr[:80]}")
    name = canonical(m.group(1))
    rng = widths.get(name)
    if m.group(2) is not None and m.group(3) is None:
        return [f"{name}[{m.group(2)}]"]
    if m.group(2) is not None:
        hi, lo = int(m.group(2)), int(m.group(3))
    elif rng is not None:
        hi, lo = rng
    else:
        return [name]
    step = -1 if hi >= lo else 1
    return [f"{name}[{i}]" for i in range(hi, lo + step, step)]


def split_concat(body):
    parts, depth, cur = [], 0, ""
    for ch in body:
        if ch == "{":
            depth += 1
        elif ch == "}":
            depth -= 1
        if ch == "," and depth == 0:
            parts.append(cur)
            cur = ""
        else:
            cur += ch
    if cur.strip():
        parts.append(cur)
    return parts


def rename_box_ports(text):
    """The netlist with ports whose names are not plain identifiers (a black box's pins, INST.PIN)
    renamed box<i>, and {box<i>: INST.PIN}: OpenSTA 2.0.17 does not find escaped port names with
    brackets and dots."""
    renamed = {}
    for i, m in enumerate(re.finditer(r"^\s*(?:input|output)\s+(?:\[\d+:\d+\]\s+)?\\(\S+)\s*;", text, re.M)):
        renamed[f"box{i}"] = m.group(1)
    for new, old in renamed.items():
        text = text.replace(f"\\{old} ", f"{new} ")
    return text, renamed


class Netlist:
    """A mapped record ready for propagation: its sources, its combinational cells in topological
    order, and which cell pins sit on which net."""

    def __init__(self, text, functions):
        self.ports, widths, cells, aliases = parse_netlist(text)
        parent = {}

        def find(x):
            while parent.get(x, x) != x:
                parent[x] = parent.get(parent[x], parent[x])
                x = parent[x]
            return x

        for lhs, rhs in aliases:
            a, b = find(lhs), find(rhs)
            if a != b:
                # keep a constant or a source as the representative
                if b in CONST or a not in CONST:
                    parent[a] = b
                else:
                    parent[b] = a
        self.find = find
        self.input_bits = []
        for name, (direction, rng) in self.ports.items():
            if direction != "input":
                continue
            if rng is None:
                self.input_bits.append(name)
            else:
                hi, lo = rng
                step = -1 if hi >= lo else 1
                self.input_bits += [f"{name}[{i}]" for i in range(hi, lo + step, step)]
        self.flops = []  # (instance, Q net)
        self.flop_inputs = {}  # Q net -> D net
        self.comb = []   # (type, instance, {pin: net})
        self.cells = cells
        self.driver = {}
        for ctype, inst, pins in cells:
            f = functions.get(ctype)
            if f is None:
                raise NetlistError(f"cell {ctype} ({inst}) is not in the library")
            pins = {k: find(v) for k, v in pins.items()}
            if f["sequential"]:
                q = pins.get("Q")
                if q is not None:
                    self.flops.append((inst, q))
                    if "D" in pins:
                        self.flop_inputs[q] = pins["D"]
                continue
            self.comb.append((ctype, inst, pins))
            for out in f["outputs"]:
                if out in pins:
                    self.driver[pins[out]] = (ctype, inst)
        self.order = self._topological(functions)

    def _topological(self, functions):
        pending = {}
        users = {}
        for idx, (ctype, inst, pins) in enumerate(self.comb):
            ins = [pins[i] for i in functions[ctype]["inputs"] if i in pins and pins[i] in self.driver]
            pending[idx] = len(ins)
            for n in ins:
                users.setdefault(n, []).append(idx)
        ready = [i for i, k in pending.items() if k == 0]
        order = []
        while ready:
            idx = ready.pop()
            order.append(idx)
            ctype, inst, pins = self.comb[idx]
            for out in functions[ctype]["outputs"]:
                for u in users.get(pins.get(out), []):
                    pending[u] -= 1
                    if pending[u] == 0:
                        ready.append(u)
        if len(order) != len(self.comb):
            raise NetlistError(f"combinational loop: {len(self.comb) - len(order)} cells not ordered")
        return order


def propagate(netlist, tables, source):
    """Net -> (probability, density) for every net, from `source(net)` -> (probability, density)
    for the netlist's sources (input bits and flip-flop outputs; constants are fixed)."""
    act = {}
    for c, v in CONST.items():
        act[c] = (v, 0.0)
    for net in netlist.input_bits:
        if net != "clk_i":  # the clock is OpenSTA's: two transitions a cycle
            act[netlist.find(net)] = source(net)
    for inst, q in netlist.flops:
        act[q] = source(q)
    for idx in netlist.order:
        ctype, inst, pins = netlist.comb[idx]
        for out, entry in tables[ctype].items():
            if out not in pins:
                continue
            probs, dens = [], []
            for i in entry[0]:
                p, d = act.get(pins.get(i), (0.5, 0.0))
                probs.append(p)
                dens.append(d)
            act[pins[out]] = propagate_cell(entry, probs, dens)
    return act


def power_script(lib_path, netlist_path, act, netlist, period_ns, top="rec"):
    """An OpenSTA script that annotates `act` on every cell pin and input port and reports power."""
    lines = [f"read_liberty {lib_path}", f"read_verilog {netlist_path}", f"link_design {top}"]
    if "clk_i" in netlist.ports:
        lines.append(f"create_clock -name clk -period {period_ns} [get_ports clk_i]")
    else:
        lines.append(f"create_clock -name clk -period {period_ns}")
    # Inputs in the clock's domain: OpenSTA prices a pin's activity per cycle of its clock, and
    # gives nothing to logic no clock reaches (a record without flip-flops).
    lines.append("set_input_delay 0 -clock clk [all_inputs]")
    lines.append("sta::set_power_input_activity 0 0.5")
    lines.append("proc a {p d y} { sta::set_power_pin_activity [get_pins $p] $d $y }")
    lines.append("proc i {p d y} { sta::set_power_input_port_activity [get_ports $p] $d $y }")
    for net in netlist.input_bits:
        if net == "clk_i":
            continue
        p, d = act.get(netlist.find(net), (0.5, 0.0))
        lines.append(f"i {{{net}}} {d:.6g} {p:.6g}")  # a port bit: its index is not escaped
    for ctype, inst, pins in netlist.cells:
        for pin, net in pins.items():
            if pin == "CLK":
                continue
            p, d = act.get(netlist.find(net), (0.5, 0.0))
            lines.append(f"a {tcl_brace(inst)[:-1]}/{pin}}} {d:.6g} {p:.6g}")
    lines.append("report_power -digits 6")
    lines.append("exit")
    return "\n".join(lines) + "\n"


def tcl_brace(name):
    return "{" + name.replace("[", "\\[").replace("]", "\\]") + "}"


def run_power(lib_path, netlist_path, act, netlist, work, period_ns=10.0, top="rec"):
    """{"internal_w", "switching_w", "leakage_w", "sequential_w", "combinational_w"} of OpenSTA's
    report_power with `act` annotated."""
    script = Path(work) / "power.tcl"
    script.write_text(power_script(lib_path, netlist_path, act, netlist, period_ns, top))
    proc = subprocess.run(["sta", "-no_init", "-no_splash", "-exit", str(script)], capture_output=True, text=True,
                          cwd=work)
    if proc.returncode != 0 or "Error" in proc.stdout:
        tail = "\n".join((proc.stdout + proc.stderr).splitlines()[-10:])
        raise NetlistError(f"OpenSTA power failed:\n{tail}")
    rows = {}
    for m in re.finditer(r"^(Sequential|Combinational|Total)\s+([\d.eE+-]+)\s+([\d.eE+-]+)\s+([\d.eE+-]+)\s+([\d.eE+-]+)",
                         proc.stdout, re.M):
        rows[m.group(1)] = [float(m.group(i)) for i in range(2, 6)]
    if "Total" not in rows:
        raise NetlistError("OpenSTA printed no power report")
    internal, switching, leakage, total = rows["Total"]
    return {"internal_w": internal, "switching_w": switching, "leakage_w": leakage,
            "sequential_w": rows.get("Sequential", [0, 0, 0, 0])[3],
            "combinational_w": rows.get("Combinational", [0, 0, 0, 0])[3], "period_ns": period_ns}
