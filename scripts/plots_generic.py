"""One figure of any sweep (scripts/plots.py --x KEY --y KEY [--hue] [--facet] [--where]): --y
against --x, a line per --hue value, a panel per --facet value, rows that agree on the rest
averaged."""

import sys
from collections import defaultdict
from pathlib import Path

from plots_data import distinct, parse_value, plt


def generic_figure(rows, args):
    """One figure of any sweep: --y against --x, a line per --hue value, a panel per --facet value."""
    where = []
    for group in args.where:
        cond = {}
        for item in group:
            if "=" not in item:
                print(f"plots.py: error: --where '{item}': expected KEY=VALUE[,VALUE...]", file=sys.stderr)
                return 2
            key, values = item.split("=", 1)
            cond[key] = {parse_value(v) for v in values.split(",")}
        where.append(cond)
    keys = [k for k in (args.x, args.y, args.hue, args.facet) if k]
    columns = set().union(*(r.keys() for r in rows))
    missing = [k for k in keys + [k for w in where for k in w] if k not in columns and k != "grid"]
    if missing:
        print(f"plots.py: error: no column {', '.join(sorted(set(missing)))} in {args.results}", file=sys.stderr)
        return 2
    def matches(r, key, values):  # grid=NAME: the row belongs to that grid of its spec
        return bool(r["grid_set"] & {str(v) for v in values}) if key == "grid" else r.get(key) in values

    sel = [r for r in rows if (not where or any(all(matches(r, k, v) for k, v in w.items()) for w in where))
           and all(r.get(k) is not None for k in keys)]
    if not sel:
        print("plots.py: error: no row has all of " + ", ".join(keys) + (" and matches --where" if where else ""),
              file=sys.stderr)
        return 2
    facets = distinct(sel, args.facet) if args.facet else [None]
    hues = distinct(sel, args.hue) if args.hue else [None]
    cols = min(3, len(facets))
    nrows = (len(facets) + cols - 1) // cols
    fig, axes = plt.subplots(nrows, cols, figsize=(4.6 * cols, 3.6 * nrows), squeeze=False)
    averaged = 0
    for ax, fv in zip(axes.flat, facets):
        for i, hv in enumerate(hues):
            groups = defaultdict(list)
            for r in sel:
                if (args.facet is None or r[args.facet] == fv) and (args.hue is None or r[args.hue] == hv):
                    groups[r[args.x]].append(r[args.y])
            if not groups:
                continue
            xs = sorted(groups)
            averaged = max(averaged, max(len(v) for v in groups.values()))
            ax.plot(xs, [sum(groups[x]) / len(groups[x]) for x in xs], "o-", ms=3, color=f"C{i % 10}",
                    label=f"{args.hue} = {hv}" if args.hue else None)
        ax.set_xlabel(args.x)
        ax.set_ylabel(args.y)
        if args.logx:
            ax.set_xscale("log")
        if args.logy:
            ax.set_yscale("log")
        if args.facet:
            ax.set_title(f"{args.facet} = {fv}", fontsize=8)
        if args.hue:
            ax.legend(fontsize=6)
    for ax in list(axes.flat)[len(facets):]:
        ax.set_visible(False)
    note = f"; points averaged over up to {averaged} rows" if averaged > 1 else ""
    fig.suptitle(f"{args.y} against {args.x} ({len(sel)} rows of {Path(args.results).name}{note})", fontsize=9)
    fig.tight_layout()
    out = Path(args.output)
    out.parent.mkdir(parents=True, exist_ok=True)
    meta_png, meta_svg = {"Software": None}, {"Date": None}
    fig.savefig(out, bbox_inches="tight", metadata=meta_png if out.suffix == ".png" else meta_svg)
    if out.suffix == ".png":
        fig.savefig(out.with_suffix(".svg"), bbox_inches="tight", metadata=meta_svg)
    plt.close(fig)
    print(f"plots.py: wrote {out} ({len(sel)} rows)", file=sys.stderr)
    return 0
