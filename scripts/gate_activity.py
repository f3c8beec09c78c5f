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
independent (scripts/gate_check.py measures what that costs against a gate-level simulation).

The activities are then priced from the Liberty tables (`price`): each cell output's internal
energy per transition (the mean of its rise and fall tables over its arcs, at its net's load and a
reference input slew), each net's 1/2 C V^2 per change (pin capacitances plus the wire-load
model), input pins' passive energy, and each flip-flop's clock pin once up and once down a cycle.
Debian's OpenSTA 2.0.17 cannot do this: it ignores activities annotated on combinational outputs,
propagating its own from the input ports only (none from registers), and charges a transition the
sum of the rise and fall tables rather than one of them.
"""

import itertools
import re

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


# ---- Pricing from the Liberty tables (OpenSTA 2.0.17 ignores activities annotated on
# combinational outputs: it propagates its own from the input ports and none from registers) ----

VDD = 1.8
REFERENCE_SLEW_NS = 0.12  # the input transition every table is read at (no timing-driven slews)


def groups(text, name):
    """[(argument, body)] of every `name(argument) { body }` group in `text`, braces balanced."""
    out = []
    for m in re.finditer(r"\b" + name + r"\s*\(([^)]*)\)\s*\{", text):
        depth, i = 1, m.end()
        while depth and i < len(text):
            if text[i] == "{":
                depth += 1
            elif text[i] == "}":
                depth -= 1
            i += 1
        out.append((m.group(1).strip().strip('"'), text[m.end():i - 1]))
    return out


def table(body):
    """(index_1, index_2 or None, values as rows) of a Liberty table group body."""
    def numbers(key):
        m = re.search(key + r'\s*\(\s*"([^"]*)"\s*\)', body)
        return [float(x) for x in m.group(1).split(",")] if m else None
    values = re.search(r"values\s*\((.*?)\)\s*;", body, re.S).group(1)
    rows = [[float(x) for x in r.split(",")] for r in re.findall(r'"([^"]*)"', values)]
    return numbers("index_1"), numbers("index_2"), rows


def lookup(tab, x, y=None):
    """Linear interpolation (and extrapolation) in a table: x on index_1, y on index_2."""
    i1, i2, rows = tab

    def locate(index, v):
        if len(index) == 1:
            return 0, 0, 0.0
        k = 0
        while k < len(index) - 2 and v > index[k + 1]:
            k += 1
        return k, k + 1, (v - index[k]) / (index[k + 1] - index[k])

    if i2 is None or len(rows) == 1:
        row = rows[0] if len(rows) == 1 else [r[0] for r in rows]
        a, b, t = locate(i1, x)
        return row[a] + t * (row[b] - row[a])
    a, b, t = locate(i1, x)
    c, d, u = locate(i2, y)
    top = rows[a][c] + u * (rows[a][d] - rows[a][c])
    bottom = rows[b][c] + u * (rows[b][d] - rows[b][c])
    return top + t * (bottom - top)


def liberty_power(text):
    """Cell -> {"caps": {input pin: pF}, "passive": {input pin: (rise table, fall table)},
    "arcs": {output pin: [(related pin, rise table, fall table)]}, "clock": pin or None}."""
    cells = {}
    for name, body in groups(text, "cell"):
        caps, passive, arcs, clock = {}, {}, {}, None
        for pin, pbody in groups(body, "pin"):
            direction = re.search(r"direction\s*:\s*(\w+)", pbody).group(1)
            if direction == "input":
                cap = re.search(r"^\s*capacitance\s*:\s*([\d.eE+-]+)", pbody, re.M)
                caps[pin] = float(cap.group(1)) if cap else 0.0
                if re.search(r"^\s*clock\s*:\s*true", pbody, re.M):
                    clock = pin
            for _, ip in groups(pbody, "internal_power"):
                related = re.search(r'related_pin\s*:\s*"([^"]*)"', ip)
                rise = [table(b) for _, b in groups(ip, "rise_power")]
                fall = [table(b) for _, b in groups(ip, "fall_power")]
                if not rise or not fall:
                    continue
                if direction == "input" and not related:
                    passive[pin] = (rise[0], fall[0])
                elif direction == "output":
                    arcs.setdefault(pin, []).append((related.group(1) if related else None, rise[0], fall[0]))
        cells[name] = {"caps": caps, "passive": passive, "arcs": arcs, "clock": clock}
    return cells


def wire_load_pf(fanout, per_um_pf=0.0002, um_per_fanout=25.0):
    """The wire-load model scripts/silicon.py adds to the library: 25 um of wire per fan-out."""
    return per_um_pf * um_per_fanout * fanout


def price(netlist, act, power, output_load_pf=0.02):
    """Energy per cycle (pJ) of a mapped netlist with activity `act` (net -> (probability,
    changes per cycle)): {"internal": cells' internal energy, "switching": nets' 1/2 C V^2,
    "clock": flip-flops' clock pins, two transitions a cycle}. Loads are the pins' capacitances,
    the wire-load estimate and the record's output load; tables are read at REFERENCE_SLEW_NS."""
    loads, fanout = {}, {}
    for ctype, inst, pins in netlist.cells:
        caps = power[ctype]["caps"]
        for pin, net in pins.items():
            if pin in caps:
                n = netlist.find(net)
                loads[n] = loads.get(n, 0.0) + caps[pin]
                fanout[n] = fanout.get(n, 0) + 1
    for name, (direction, rng) in netlist.ports.items():
        if direction != "output":
            continue
        bits = [name] if rng is None else [f"{name}[{i}]" for i in range(min(rng), max(rng) + 1)]
        for b in bits:
            n = netlist.find(b)
            loads[n] = loads.get(n, 0.0) + output_load_pf
            fanout[n] = fanout.get(n, 0) + 1

    def cap(n):
        return loads.get(n, 0.0) + wire_load_pf(fanout.get(n, 0))

    internal = switching = clock = 0.0
    driven = set()
    for ctype, inst, pins in netlist.cells:
        cell = power[ctype]
        for pin, (rise, fall) in cell["passive"].items():
            net = pins.get(pin)
            if net is None:
                continue
            if pin == cell["clock"]:
                clock += lookup(rise, 0.0) + lookup(fall, 0.0)  # the ideal clock: one rise and one fall
            else:
                internal += act.get(netlist.find(net), (0.5, 0.0))[1] * (lookup(rise, REFERENCE_SLEW_NS)
                                                                        + lookup(fall, REFERENCE_SLEW_NS)) / 2
        for out, arcs in cell["arcs"].items():
            net = pins.get(out)
            if net is None:
                continue
            n = netlist.find(net)
            d = act.get(n, (0.5, 0.0))[1]
            c = cap(n)
            e = sum(lookup(r, c, REFERENCE_SLEW_NS) + lookup(f, c, REFERENCE_SLEW_NS) for _, r, f in arcs) / (2 * len(arcs))
            internal += d * e
            switching += d * 0.5 * c * VDD * VDD
            driven.add(n)
    for b in netlist.input_bits:  # nets driven by the record's inputs
        n = netlist.find(b)
        if b != "clk_i" and n not in driven:
            switching += act.get(n, (0.5, 0.0))[1] * 0.5 * cap(n) * VDD * VDD
    return {"internal": internal, "switching": switching, "clock": clock}
