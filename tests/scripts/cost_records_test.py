#!/usr/bin/python3
"""Properties of the stored composed costs and of pruning (scripts/cost_records.py):

1. The stored composed result of a configuration equals what Yosys elaborates and composes from
   the module records now (the default unit and one CPG variant): the store is a cache, not data
   of its own.
2. Its key changes with an edit of the RTL sources (not with a comment) and with the parameters;
   a composed result whose records are gone is not used.
3. Pruning a copy of the records keeps every record the listed configurations compose from and
   deletes one they do not use.

    cost_records_test.py TESSIM
"""

import json
import shutil
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "scripts"))
import cost_records  # noqa: E402
import yosys_cost  # noqa: E402

failures = []


def check(what, ok, detail=""):
    print(f"{'ok  ' if ok else 'FAIL'} {what}{': ' + detail if detail and not ok else ''}", flush=True)
    if not ok:
        failures.append(what)


def comparable(result):
    """The figures of a cost() result, JSON-normalised (tuples as lists), without timing fields."""
    r = json.loads(json.dumps(result))
    r.pop("synthesized", None)
    return r


def test_store_matches_elaboration():
    for params in ({}, {"CpBuffers": 4, "CpgCopies": 2, "CpgDigitBits": 8, "CpgLanes": 3}):
        key = cost_records.composed_key(params, True)
        path = cost_records.composed_dir(cost_records.MODULES) / f"{key}.json"
        stored = cost_records.load_composed(path, cost_records.MODULES)
        check(f"a composed result of the current RTL is stored for {params or 'the defaults'}", stored is not None,
              f"{path.name} missing; run scripts/cost_records.py record")
        if stored is None:
            continue
        fresh = yosys_cost.cost(params, cost_records.MODULES, require_cached=True)
        check(f"the stored result equals a fresh elaboration for {params or 'the defaults'}",
              comparable(stored) == comparable(fresh))


def test_keys(tmp):
    base = cost_records.composed_key({}, True)
    copy = Path(tmp) / "rtl"
    shutil.copytree(ROOT / "rtl", copy)
    fifo = copy / "tess_fifo.sv"
    text = fifo.read_text()
    fifo.write_text("// a comment\n/* and another */\n" + text.replace("\n", "\n  ", 3))
    check("a comment or re-indentation changes no composed key", cost_records.composed_key({}, True, copy) == base)
    fifo.write_text(text.replace("endmodule", "  logic unused_extra;\nendmodule", 1))
    check("an edit of an RTL source changes the composed key", cost_records.composed_key({}, True, copy) != base)
    check("a string literal is kept whole", cost_records.without_comments('a = "x // y"; // z') == 'a = "x // y";')
    check("the parameters change the composed key", cost_records.composed_key({"IntBlocks": 3}, True) != base)
    check("a parameter at its default does not", cost_records.composed_key({"IntBlocks": 2}, True) == base)
    check("the Xilinx flag changes the composed key", cost_records.composed_key({}, False) != base)

    cache = Path(tmp) / "modules"
    cache.mkdir()
    stored = cost_records.composed_dir(cost_records.MODULES) / f"{base}.json"
    if stored.exists():
        result = json.loads(stored.read_text())
        (cost_records.composed_dir(cache)).mkdir(parents=True)
        shutil.copy(stored, cost_records.composed_dir(cache) / stored.name)
        for r in result["records"][1:]:
            shutil.copy(cost_records.MODULES / f"{r['key']}.json", cache)
        check("a composed result whose record is gone is not used",
              cost_records.load_composed(cost_records.composed_dir(cache) / stored.name, cache) is None)
        shutil.copy(cost_records.MODULES / f"{result['records'][0]['key']}.json", cache)
        check("it is used again once every record is present",
              cost_records.load_composed(cost_records.composed_dir(cache) / stored.name, cache) is not None)


def test_prune(tmp):
    costs = Path(tmp) / "costs"
    shutil.copytree(cost_records.COSTS, costs)
    orig = (cost_records.COSTS, cost_records.MODULES, cost_records.LIST)
    cost_records.COSTS, cost_records.MODULES, cost_records.LIST = costs, costs / "modules", costs / "configurations.json"
    try:
        # The list of the copy: the configurations with a stored composition of the current RTL.
        listed = json.loads(cost_records.LIST.read_text())
        listed["configurations"] = [c for c in listed["configurations"]
                                    if cost_records.load_composed(cost_records.composed_dir(cost_records.MODULES) /
                                                                  f"{cost_records.composed_key(c['params'], True)}.json",
                                                                  cost_records.MODULES) is not None]
        cost_records.LIST.write_text(json.dumps(listed))
        check("the copy lists configurations to keep", len(listed["configurations"]) > 0)
        stray = cost_records.MODULES / ("0" * 64 + ".json")
        stray.write_text(json.dumps({"schema": yosys_cost.RECORD_SCHEMA, "module": "tess_fifo", "result": {}}))
        used = {r["key"] for _, result, _ in cost_records.current_results(cost_records.MODULES, True)
                for r in result["records"]}
        rc = cost_records.main(["prune"])
        check("prune succeeds when every listed configuration is recorded", rc == 0)
        check("prune deletes a record no listed configuration uses", not stray.exists())
        left = {p.stem for p in cost_records.MODULES.glob("*.json")}
        check("prune keeps every record a listed configuration uses", used <= left, f"{len(used - left)} deleted")
        check("prune keeps nothing else", left == used, f"{len(left - used)} unused left")
    finally:
        cost_records.COSTS, cost_records.MODULES, cost_records.LIST = orig


def main():
    with tempfile.TemporaryDirectory(prefix="tessim-cost-records-test-") as tmp:
        test_keys(tmp)
        test_store_matches_elaboration()
        test_prune(tmp)
    if failures:
        print(f"cost_records_test: {len(failures)} failed", file=sys.stderr)
        return 1
    print("cost_records_test: all passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
