#!/usr/bin/python3
"""Every number in the prose of docs/results/*.md, accounted for.

A number in the prose of the result pages (load-balancing.md, performance.md, silhouette.md;
tables.md and stpn_table.md are generated whole, and a block between
`<!-- generated: ... -->` and `<!-- end generated -->` is generated too) is one of:

- checked: a claim file in docs/results/claims/ quotes the sentence and gives, for the number,
  an expression over committed data files whose value the number must round to; or a check of
  tests/scripts/doc_claims_test.py captures it in a group of its pattern;
- a label: a section (§12), a parameter setting (L = 8, N = 1…6, Λ = 3, a configuration name
  such as 3x1 ×4), a list item's number, a code span, a heading, a link; or, in a claim file,
  a number labelled with its kind and reason: `input` (a setting the study chose), `formula` (a
  constant of a formula), `design` (a fixed property of the design stated in docs/), `outside`
  (a figure from a cited paper, chip or standard), `target` (a goal).

Anything else is uncovered, and `doc_claims` fails on it. Run
    /usr/bin/python3 tests/scripts/claims.py --uncovered [--doc NAME] [--section '## 12.']
to list the uncovered numbers with their line and context, and
    /usr/bin/python3 tests/scripts/claims.py --check [--file CLAIMS.json]
to evaluate the claim files alone (no tessim needed); `--check --fix` rewrites every number that
disagrees with its data to what the data give and prints each change for review.

A claim file is JSON:
    {"doc": "docs/results/load-balancing.md",
     "data": {"full": "docs/results/full/results.csv"},          aliases for data files
     "claims": [
       {"quote": "0.0681 vertices/cycle per million transistors",  unique in the doc (or in
        "section": "## Answer in short",                           the section), whitespace-blind
        "values": {"0.0681": "expression"},                        a number of the quote: its data
        "labels": {"8": "input: the study's tessellation factor"}, or its kind and reason
        "tol": 0.0}]}                                              optional relative tolerance
A number that occurs more than once in a quote is named "text#k" (k from 1) when its occurrences
differ; plain "text" applies to all of them. An expression must read a data file through one of
j(file), rows(file, **where), row(file, **where), table(file, heading, column=None),
cell(file, heading, first_cell, column) (a number), text(file)
and may use num(x), min, max, sum, len, abs, round, sorted, any, all, math; `file` is an alias
of the claim file's "data" or a path from the repository root. A number passes when the value
rounds to it at the decimals it is written with (1 960, 1,960 and 14 % are whole numbers, 0.0480
has four decimals), or lies within the relative tolerance `tol` of the claim.
"""
import argparse
import ast
import csv
import json
import math
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
DOCS = ["docs/results/load-balancing.md", "docs/results/performance.md", "docs/results/silhouette.md"]
CLAIMS_DIR = ROOT / "docs/results/claims"
LABEL_KINDS = {"input", "formula", "design", "outside", "target"}
LOADERS = {"j", "rows", "row", "table", "cell", "text"}

NUMBER = re.compile(r"(?<![\w.])[-−]?(?:\d{1,3}(?:[ \u2009\u202f]\d{3})+(?![\d,])|\d{1,3}(?:,\d{3})+(?![\d,])|\d+)"
                    r"(?:\.\d+)?(?![\w]|\.\d)")
_PARAM = r"(?:L|N|K|V|Λ|r|Ec|Nb|R|W|I|D|β)"
_SEQ = r"\d+(?:\s*(?:–|…|\.\.)\s*\d+)*"   # a value or a range; a list after a comma may be a result
AUTO_LABELS = [
    re.compile(rf"§{_SEQ}"),
    re.compile(rf"(?<![\w]){_PARAM}\s*(?:=|≤|≥|<|>)\s*{_SEQ}(?![.\d])"),
    re.compile(rf"(?<![\w]){_PARAM}\s*∈\s*\{{[\d, ]+\}}"),
    re.compile(r"(?<![\w])β\s*(?:=|≤|≥|<|>)\s*\d+\.\d+"),   # the band's width, a setting
    re.compile(r"\b\d+x\d+(?: reg)?\s*×\s*\d+\b"),
    re.compile(r"^\s*\d+\. ", re.M),
    re.compile(r"Direct3D\s+\d+"),   # a standard's name
]


def masked(text: str) -> str:
    """The doc with everything that is not prose blanked (newlines kept, offsets unchanged): code
    blocks and spans, link targets, headings, comments and generated blocks."""
    out = list(text)

    def blank(a, b):
        for i in range(a, b):
            if out[i] != "\n":
                out[i] = " "

    for pattern, flags in ((r"^```.*?^```", re.M | re.S),
                           (r"<!-- generated:.*?<!-- end generated -->", re.S),
                           (r"<!--.*?-->", re.S), (r"`(?:[^`\n]|\n(?![ \t]*\n))*`", 0), (r"!\[[^\]]*\]", 0), (r"\]\([^)]*\)", 0), (r"^#+ .*$", re.M),
                           (r"^\|[-| :]+\|$", re.M)):
        for m in re.finditer(pattern, "".join(out), flags):
            blank(m.start(), m.end())
    return "".join(out)


def value_of(token: str) -> float:
    return float(re.sub(r"[ ,\u2009\u202f]", "", token).replace("−", "-"))


def decimals(token: str) -> int:
    return len(token.split(".")[1]) if "." in token else 0


def agrees(token: str, value, tol: float) -> bool:
    if isinstance(value, str):
        return value == token
    if isinstance(value, bool) or not isinstance(value, (int, float)) or math.isnan(value):
        return False
    stated = value_of(token)
    if tol:
        return abs(value - stated) <= tol * max(abs(stated), abs(value))
    return abs(value - stated) <= 0.5 * 10 ** -decimals(token) * (1 + 1e-9) + 1e-12


class Normalized:
    """A text with its whitespace runs collapsed to single spaces, and the way back to offsets."""

    def __init__(self, text: str):
        self.text, self.where = [], []
        space = True
        for i, ch in enumerate(text):
            if ch.isspace():
                if not space:
                    self.text.append(" ")
                    self.where.append(i)
                space = True
            else:
                self.text.append(ch)
                self.where.append(i)
                space = False
        self.text = "".join(self.text)

    def span(self, start: int, end: int):
        return self.where[start], self.where[end - 1] + 1


class Doc:
    def __init__(self, path: str):
        self.path = path
        self.text = (ROOT / path).read_text()
        self.prose = masked(self.text)
        self.norm = Normalized(self.text)
        labelled = set()
        for rule in AUTO_LABELS:
            for m in rule.finditer(self.prose):
                labelled.update(range(m.start(), m.end()))
        self.tokens = [(m.start(), m.end(), m.group()) for m in NUMBER.finditer(self.prose)
                       if m.start() not in labelled]
        self.covered = {}  # token start -> how

    def line(self, offset: int) -> int:
        return self.text.count("\n", 0, offset) + 1

    def section_bounds(self, heading: str):
        start = self.text.find(heading)
        if start < 0:
            raise ValueError(f"no section {heading!r}")
        end = self.text.find("\n## ", start + len(heading))
        return start, end if end >= 0 else len(self.text)

    def find_quote(self, quote: str, section: str = None):
        """The offsets of a quote that occurs once (in the section), whitespace-blind."""
        q = " ".join(quote.split())
        lo, hi = self.section_bounds(section) if section else (0, len(self.text))
        hits = [m.start() for m in re.finditer(re.escape(q), self.norm.text)
                if lo <= self.norm.where[m.start()] < hi]
        if len(hits) != 1:
            raise ValueError(f"quote found {len(hits)} times{' in ' + section if section else ''}: {q[:80]!r}")
        return self.norm.span(hits[0], hits[0] + len(q))

    def tokens_in(self, start: int, end: int):
        return [t for t in self.tokens if start <= t[0] and t[1] <= end]

    def cover(self, start: int, end: int, how: str):
        for t in self.tokens_in(start, end):
            self.covered.setdefault(t[0], how)

    def context(self, start: int, end: int) -> str:
        """A number's surroundings on one line, for reports."""
        return " ".join(self.text[max(0, start - 50):end + 30].split())

    def uncovered(self, section: str = None):
        lo, hi = self.section_bounds(section) if section else (0, len(self.text))
        return [t for t in self.tokens if t[0] not in self.covered and lo <= t[0] < hi]


class Data:
    """The loaders an expression may call; each file is read once."""

    def __init__(self, aliases: dict):
        self.aliases, self.cache = aliases, {}

    def path(self, name: str) -> Path:
        p = ROOT / self.aliases.get(name, name)
        if not p.is_file():
            raise ValueError(f"no data file {p.relative_to(ROOT)}")
        return p

    def _read(self, name, kind):
        key = (name, kind)
        if key not in self.cache:
            p = self.path(name)
            if kind == "json":
                self.cache[key] = json.loads(p.read_text())
            elif kind == "csv":
                with open(p, newline="") as f:
                    self.cache[key] = list(csv.DictReader(f))
            else:
                self.cache[key] = p.read_text()
        return self.cache[key]

    def j(self, name):
        return self._read(name, "json")

    def text(self, name):
        return self._read(name, "text")

    def rows(self, name, **where):
        return [r for r in self._read(name, "csv") if all(str(r.get(k)) == str(v) for k, v in where.items())]

    def row(self, name, **where):
        found = self.rows(name, **where)
        if len(found) != 1:
            raise ValueError(f"{len(found)} rows of {name} where {where}")
        return found[0]

    def table(self, name, heading, column=None):
        """The first markdown table after `heading` in a generated page: a list of rows (dicts by
        header cell), or one column of them."""
        body = self.text(name)
        at = body.find(heading)
        if at < 0:
            raise ValueError(f"no {heading!r} in {name}")
        lines = [l for l in body[at:].splitlines()[1:]]
        first = next(i for i, l in enumerate(lines) if l.startswith("|"))
        block = []
        for l in lines[first:]:
            if not l.startswith("|"):
                break
            block.append([c.strip(" *") for c in l.strip().strip("|").split("|")])
        head, rest = block[0], [r for r in block[1:] if not set("".join(r)) <= set("-: ")]
        out = [dict(zip(head, r)) for r in rest]
        return [r[column] for r in out] if column else out

    def cell(self, name, heading, first, column):
        """One cell of that table, as a number: the row whose first cell is `first`."""
        rows = [r for r in self.table(name, heading) if next(iter(r.values())) == str(first)]
        if len(rows) != 1:
            raise ValueError(f"{len(rows)} rows {first!r} in {heading!r} of {name}")
        return num(rows[0][column])


def num(x):
    """A cell or field as a number: '1 960', '14 %', '0.0480', '1.2×' read as numbers."""
    if isinstance(x, (int, float)):
        return x
    return float(re.sub(r"[\s,\u2009\u202f%×*]", "", str(x)).replace("−", "-"))


def evaluate(expr: str, data: Data):
    tree = ast.parse(expr, mode="eval")
    called = {n.func.id for n in ast.walk(tree) if isinstance(n, ast.Call) and isinstance(n.func, ast.Name)}
    if not called & LOADERS:
        raise ValueError(f"expression reads no data file: {expr!r}")
    scope = {"j": data.j, "rows": data.rows, "row": data.row, "table": data.table, "cell": data.cell, "text": data.text, "num": num,
             "min": min, "max": max, "sum": sum, "len": len, "abs": abs, "round": round, "sorted": sorted,
             "any": any, "all": all, "math": math, "float": float, "int": int, "set": set, "next": next,
             "zip": zip, "range": range, "enumerate": enumerate, "list": list, "dict": dict, "str": str}
    return eval(compile(tree, "<claim>", "eval"), {"__builtins__": {}, **scope})  # globals: comprehensions see them


def claim_files():
    return sorted(p for p in CLAIMS_DIR.glob("*.json") if p.name != "pending.json") if CLAIMS_DIR.is_dir() else []


def written_as(token: str, value: float) -> str:
    """`value` written the way `token` is: its decimals, its thousands separator, its minus sign."""
    digits = decimals(token)
    text = f"{abs(value):,.{digits}f}"
    if re.search(r"\d[ \u2009\u202f]\d", token):
        text = text.replace(",", re.search(r"\d([ \u2009\u202f])\d", token).group(1))
    elif "," not in token:
        text = text.replace(",", "")
    if value < 0 and round(abs(value), digits) != 0:
        text = ("−" if "−" in token or not token.startswith("-") else "-") + text
    return text


def check_claim_files(docs: dict, files=None, stale=None):
    """Evaluates every claim; marks what it covers in `docs`. Returns the failures; appends each
    number that disagrees with its data to `stale` as (claim file, claim index, key, tokens, value)."""
    failures = []
    for path in files or claim_files():
        name = path.relative_to(ROOT)
        try:
            spec = json.loads(path.read_text())
        except ValueError as e:
            failures.append(f"{name}: not JSON: {e}")
            continue
        doc = docs.get(spec.get("doc"))
        if doc is None:
            failures.append(f"{name}: doc {spec.get('doc')!r} is not one of {sorted(docs)}")
            continue
        data = Data(spec.get("data", {}))
        for i, c in enumerate(spec.get("claims", [])):
            where = f"{name}: claim {i + 1} ({' '.join(c.get('quote', '').split())[:60]!r})"
            try:
                start, end = doc.find_quote(c["quote"], c.get("section"))
            except (KeyError, ValueError) as e:
                failures.append(f"{where}: {e}")
                continue
            inside = doc.tokens_in(start, end)
            by_text = {}
            for t in inside:
                by_text.setdefault(t[2], []).append(t)
            entries = [(k, v, "value") for k, v in c.get("values", {}).items()] + \
                      [(k, v, "label") for k, v in c.get("labels", {}).items()]
            if not entries:
                failures.append(f"{where}: neither values nor labels")
            for key, spec_value, kind in entries:
                text_, _, nth = key.partition("#")
                found = by_text.get(text_, [])
                if nth:
                    found = found[int(nth) - 1:int(nth)] if nth.isdigit() and int(nth) <= len(found) else []
                if not found:
                    failures.append(f"{where}: the quote has no number {key!r} (numbers: "
                                    f"{sorted(by_text)})")
                    continue
                if kind == "label":
                    category = spec_value.split(":")[0].strip()
                    if category not in LABEL_KINDS or not spec_value.partition(":")[2].strip():
                        failures.append(f"{where}: label of {key!r} is not 'KIND: reason' with KIND in "
                                        f"{sorted(LABEL_KINDS)}: {spec_value!r}")
                        continue
                    for t in found:
                        doc.covered.setdefault(t[0], f"label {category}")
                    continue
                try:
                    value = evaluate(spec_value, data)
                except Exception as e:  # noqa: BLE001 - a broken expression is a failure to report
                    failures.append(f"{where}: {key}: {type(e).__name__}: {e}")
                    continue
                if not agrees(text_, value, float(c.get("tol", 0))):
                    failures.append(f"{where}: the doc says {text_}, the data give {value!r} "
                                    f"({doc.path}:{doc.line(found[0][0])})")
                    if stale is not None and isinstance(value, (int, float)) and not c.get("tol"):
                        stale.append((path, i, key, found, value))
                    continue
                for t in found:
                    doc.covered[t[0]] = f"claim {name}"
    return failures


class Recorder:
    """Stands in for the `re` module of doc_claims_test.py: every match it makes is recorded, so
    that the numbers its checks capture count as checked."""

    def __init__(self):
        self.matches = []  # (string, [(start, end) of each group])

    def __getattr__(self, name):
        return getattr(re, name)

    def _keep(self, m, string):
        if m is not None and m.re.groups:
            self.matches.append((string, [m.span(g) for g in range(1, m.re.groups + 1) if m.span(g)[0] >= 0]))
        return m

    def search(self, pattern, string, flags=0):
        return self._keep(re.search(pattern, string, flags), string)

    def match(self, pattern, string, flags=0):
        return self._keep(re.match(pattern, string, flags), string)

    def fullmatch(self, pattern, string, flags=0):
        return self._keep(re.fullmatch(pattern, string, flags), string)

    def finditer(self, pattern, string, flags=0):
        return (self._keep(m, string) for m in re.finditer(pattern, string, flags))

    def findall(self, pattern, string, flags=0):
        for m in re.finditer(pattern, string, flags):
            self._keep(m, string)
        return re.findall(pattern, string, flags)

    def apply(self, docs: dict):
        """Marks the numbers inside recorded groups, where the matched string is (a unique piece
        of) one of the docs, as-is or whitespace-collapsed."""
        for string, spans in self.matches:
            if not spans:
                continue
            for doc in docs.values():
                base = None
                if doc.text.count(string) == 1:
                    at = doc.text.index(string)
                    base = lambda a, b, at=at: (at + a, at + b)
                elif doc.norm.text.count(string) == 1:
                    at = doc.norm.text.index(string)
                    base = lambda a, b, at=at, doc=doc: doc.norm.span(at + a, at + b)
                if base is None:
                    continue
                for a, b in spans:
                    if b > a:
                        doc.cover(*base(a, b), "doc_claims_test.py")


def fix_stale(docs: dict, stale: list) -> list:
    """Rewrites each stale number to what its data give, written as the doc writes it, in the doc
    and in its claim (the quote and the key); returns the changes, for review: a changed number
    can change what its sentence concludes."""
    edits = {}  # doc path -> {offset: (end, old, new)}
    renames = {}  # (claim file, index) -> [(key, new key)]
    for path, index, key, found, value in stale:
        spec = json.loads(path.read_text())
        doc = docs[spec["doc"]]
        text_, _, nth = key.partition("#")
        new = written_as(text_, value)
        for start, end, tok in found:
            edits.setdefault(doc.path, {})[start] = (end, tok, new)
        renames.setdefault((path, index), []).append((key, new + ("#" + nth if nth else "")))
    spans = {}
    for path, index in renames:
        spec = json.loads(path.read_text())
        c = spec["claims"][index]
        spans[(path, index)] = docs[spec["doc"]].find_quote(c["quote"], c.get("section")), spec["doc"]
    changes = []
    for doc_path, at in edits.items():
        doc = docs[doc_path]
        text = doc.text
        shift = {}
        for start in sorted(at, reverse=True):
            end, old, new = at[start]
            text = text[:start] + new + text[end:]
            shift[start] = (end, len(new) - (end - start))
            changes.append(f"{doc_path}:{doc.line(start)}: {old} -> {new}")
        (ROOT / doc_path).write_text(text)
        for (path, index), ((lo, hi), d) in spans.items():
            if d != doc_path:
                continue
            delta_lo = sum(dl for s0, (e0, dl) in shift.items() if e0 <= lo)
            delta_hi = sum(dl for s0, (e0, dl) in shift.items() if e0 <= hi)
            spec = json.loads(path.read_text())
            c = spec["claims"][index]
            c["quote"] = " ".join(text[lo + delta_lo:hi + delta_hi].split())
            for field in ("values", "labels"):
                if field in c:
                    names = dict(renames[(path, index)])
                    c[field] = {names.get(k, k): v for k, v in c[field].items()}
            path.write_text(json.dumps(spec, indent=1, ensure_ascii=False) + "\n")
    return sorted(changes)


def replace_in_doc(path: str, old: str, new: str) -> int:
    """Replaces the one occurrence of `old` in a doc under a lock, so that several editors of one
    page do not overwrite each other."""
    import fcntl
    target = ROOT / path
    with open(ROOT / ".git" / "claims-edit.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        text = target.read_text()
        if text.count(old) != 1:
            print(f"claims: {path}: {old!r} occurs {text.count(old)} times, not once", file=sys.stderr)
            return 1
        target.write_text(text.replace(old, new))
    return 0


def pending() -> dict:
    """What is not accounted for yet, from docs/results/claims/pending.json: {doc: [entry, ...]},
    an entry a section heading or {"quote": ..., "why": ...} (a quote unique in the doc)."""
    p = CLAIMS_DIR / "pending.json"
    return json.loads(p.read_text())["pending"] if p.is_file() else {}


def ratchet(docs: dict) -> list:
    """Uncovered numbers outside the pending sections and quotes, and pending entries with none left."""
    problems = []
    held = {path: [] for path in docs}
    for path, entries in pending().items():
        if path not in docs:
            problems.append(f"pending.json: {path} is not one of {sorted(docs)}")
            continue
        doc = docs[path]
        for entry in entries:
            try:
                if isinstance(entry, str):
                    span, name = doc.section_bounds(entry), repr(entry)
                else:
                    if not entry.get("why"):
                        problems.append(f"pending.json: {path}: {entry.get('quote')!r} gives no reason")
                    span, name = doc.find_quote(entry["quote"]), repr(" ".join(entry["quote"].split())[:60])
            except (KeyError, ValueError) as e:
                problems.append(f"pending.json: {path}: {e}")
                continue
            held[path].append(span)
            if not [t for t in doc.uncovered() if span[0] <= t[0] < span[1]]:
                problems.append(f"{path}: {name} is accounted for; remove it from pending.json")
    for doc in docs.values():
        for start, end, tok in doc.uncovered():
            if not any(lo <= start < hi for lo, hi in held[doc.path]):
                ctx = doc.context(start, end)
                problems.append(f"{doc.path}:{doc.line(start)}: {tok} is neither checked nor labelled … {ctx} …")
    return problems


def recorded(tessim) -> Recorder:
    """doc_claims_test's matches, kept in the temporary directory while the files it reads are
    unchanged (its checks run Verilated and simulated jobs for about 20 s)."""
    import hashlib
    import tempfile
    sys.path.insert(0, str(Path(__file__).parent))
    import doc_claims_test  # noqa: E402
    inputs = [Path(doc_claims_test.__file__)] + sorted((ROOT / "docs").rglob("*.md")) + [ROOT / "README.md"]
    digest = hashlib.sha256(b"".join(p.read_bytes() for p in inputs)).hexdigest()
    cache = Path(tempfile.gettempdir()) / "tessim-doc-claims-cache" / f"recorded-{digest}.json"
    recorder = Recorder()
    if cache.is_file():
        recorder.matches = json.loads(cache.read_text())
        return recorder
    doc_claims_test.re = recorder
    doc_claims_test.run_checks(str(Path(tessim or ROOT / "build/bin/tessim").resolve()), lambda *args: None, cached=True)
    cache.parent.mkdir(parents=True, exist_ok=True)
    cache.write_text(json.dumps(recorder.matches))
    return recorder


def load_docs():
    return {p: Doc(p) for p in DOCS}


def report(docs: dict, section: str = None, only: str = None) -> int:
    total = 0
    for doc in docs.values():
        if only and only not in doc.path:
            continue
        left = doc.uncovered(section)
        total += len(left)
        for start, end, tok in left:
            ctx = doc.context(start, end)
            print(f"{doc.path}:{doc.line(start)}: {tok}   … {ctx} …")
    return total


def summary(docs: dict) -> str:
    parts = []
    for doc in docs.values():
        parts.append(f"{Path(doc.path).name}: {len(doc.tokens) - len(doc.uncovered())}/{len(doc.tokens)}")
    return "numbers in the prose accounted for: " + ", ".join(parts)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--check", action="store_true", help="evaluate the claim files only")
    ap.add_argument("--file", action="append", type=Path, help="only this claim file (with --check)")
    ap.add_argument("--uncovered", action="store_true",
                    help="list the numbers neither checked nor labelled (runs doc_claims_test's checks)")
    ap.add_argument("--tessim", help="tessim binary for doc_claims_test's simulated checks")
    ap.add_argument("--doc", help="only this doc (a substring of its path)")
    ap.add_argument("--section", help="only this section, e.g. '## 12.'")
    ap.add_argument("--fix", action="store_true",
                    help="rewrite every number that disagrees with its data to what the data give, as the doc "
                         "writes numbers, in the doc and its claim; prints each change: review them, since a "
                         "changed number can change a conclusion")
    ap.add_argument("--replace", nargs=3, metavar=("DOC", "OLD", "NEW"),
                    help="replace the one occurrence of OLD in DOC, under a lock shared by all editors")
    a = ap.parse_args()
    if a.replace:
        return replace_in_doc(*a.replace)
    docs = load_docs()
    stale = []
    failures = check_claim_files(docs, [f.resolve() for f in a.file] if a.file else None, stale)
    if a.fix:
        for change in fix_stale(docs, stale):
            print(change)
        docs = load_docs()
        failures = check_claim_files(docs, [f.resolve() for f in a.file] if a.file else None)
    for f in failures:
        print(f"claims: {f}", file=sys.stderr)
    if a.uncovered:
        recorded(a.tessim).apply(docs)
        left = report(docs, a.section, a.doc)
        print(summary(docs))
        print(f"uncovered: {left}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
