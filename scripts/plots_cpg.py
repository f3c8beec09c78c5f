"""The study's CPG figures (scripts/plots.py; docs/results/load-balancing.md): the CPG's share of
time against L (dedicated or on the GPE), the CPG variants (edge lanes, digit bits) against L and
cost, and CPG copies per cycle and per time at the depth budget's clock."""

import math

import matplotlib.ticker

import yosys_cost  # the depth budget
from plots_balance import pareto
from plots_data import camera_distance, distinct, fmt, in_grid, plt, share, workload


def fig_cpg_share(rows, out):
    t = in_grid(rows, "tess_factor")
    if not t:
        return out.skip("CPG share vs L", "no rows of grid 'tess_factor'")
    Ks = distinct(t, "gpe_cycles")
    Ns = distinct(t, "int_blocks")
    Ls = distinct(t, "tess_factor")
    fig, axes = plt.subplots(3, len(Ks), figsize=(4.2 * len(Ks), 8.4), sharex=True, squeeze=False)
    table = []
    for col, K in enumerate(Ks):
        for i, N in enumerate(Ns):
            for mapping, style in (("dedicated", "-"), ("gpe", "--")):
                pts = sorted((r for r in t if r["gpe_cycles"] == K and r["int_blocks"] == N and
                              r["cpg_mapping"] == mapping), key=lambda r: r["tess_factor"])
                if not pts:
                    continue
                L = [r["tess_factor"] for r in pts]
                label = f"N = {N}, {mapping}"
                axes[0][col].plot(L, [100 * share(r, "te.starved_by_cpg") for r in pts], style + "o", ms=3,
                                  color=f"C{i}", label=label)
                if mapping == "gpe":
                    axes[1][col].plot(L, [100 * share(r, "gpe.cpg") for r in pts], style + "o", ms=3,
                                      color=f"C{i}", label=label)
                axes[2][col].plot(L, [r["throughput"] for r in pts], style + "o", ms=3, color=f"C{i}", label=label)
                for r in pts:
                    table.append([K, N, mapping, r["tess_factor"], fmt(100 * share(r, "te.starved_by_cpg"), 3),
                                  fmt(100 * share(r, "gpe.cpg"), 3), fmt(100 * share(r, "gpe.busy"), 3),
                                  fmt(r["throughput"], 4), fmt(r["analytic.throughput"], 4),
                                  r["analytic.bottleneck"]])
        axes[0][col].set_title(f"K = {K}: TE starved by CPG (% of cycles)", fontsize=8)
        axes[1][col].set_title(f"K = {K}: GPE cycles spent on CPG (% of cycles, gpe mapping)", fontsize=8)
        axes[2][col].set_title(f"K = {K}: throughput (dotted: GPE limit 1/K)", fontsize=8)
        axes[0][col].set_ylabel("%")
        axes[1][col].set_ylabel("%")
        axes[2][col].set_ylabel("vertices / cycle")
        axes[2][col].axhline(1.0 / K, ls=":", color="0.4", lw=0.8)
        axes[2][col].set_xlabel("tessellation factor L")
        for row in axes:
            row[col].set_xscale("log", base=2)
            row[col].set_xticks(Ls)
            row[col].set_xticklabels([str(x) for x in Ls])
    axes[0][0].legend(fontsize=7)
    fig.suptitle(f"CPG share of time vs L, dedicated (solid) and gpe-mapped (dashed) CPG "
                 f"({workload(t, 'mesh', 'normals', 'int_latency', 'te_contexts')}, cpg_gpe_cycles "
                 f"{'/'.join(str(v) for v in distinct(t, 'cpg_gpe_cycles'))})", fontsize=9)
    out.save(fig, "cpg_share_vs_l")
    out.table("CPG share of cycles and throughput vs L",
              ["K", "N", "CPG mapping", "L", "TE starved by CPG %", "GPE on CPG %", "GPE busy %",
               "vertices/cycle", "analytic", "analytic bottleneck"], table)


def cpg_variant(r):
    return (r.get("cpg_lanes") or 1, r.get("cpg_digit_bits") or 1)


def cpg_label(v):
    lanes, r = v
    return "sequential (Ec 1, r 1)" if v == (1, 1) else f"Ec {lanes}, r {r}"


# Reaching the GPE's rate: at least this share of 1/K over the whole run (fill and drain included).
GPE_RATE_SHARE = 0.97


def fig_cpg_pareto(costed, variants, pL, Ks, out):
    """Throughput against the unit's transistors over CPG variant and N, with the Pareto front."""
    fig, axes = plt.subplots(len(Ks), len(pL), figsize=(4 * len(pL), 3.6 * len(Ks)), squeeze=False)
    front_rows = []
    for i, K in enumerate(Ks):
        for j, L in enumerate(pL):
            ax = axes[i][j]
            pts = [(r["cost_unit_transistors"] / 1e6, r["throughput"],
                    f"{'S' if cpg_variant(r) == (1, 1) else f'{cpg_variant(r)[0]}x{cpg_variant(r)[1]}'} N{r['int_blocks']}", r)
                   for r in costed if r["gpe_cycles"] == K and r["tess_factor"] == L and r["normals"] == "quadratic"]
            front = pareto(pts)
            for v_i, v in enumerate(variants):
                sel = [p for p in pts if cpg_variant(p[3]) == v]
                ax.plot([p[0] for p in sel], [p[1] for p in sel], "o", ms=3, color=f"C{v_i % 10}", label=cpg_label(v))
            ax.step([p[0] for p in front], [p[1] for p in front], "-", where="post", color="k", lw=0.8)
            for p in front:
                ax.annotate(p[2], (p[0], p[1]), textcoords="offset points", xytext=(3, -8), fontsize=6)
                front_rows.append([K, L, p[2], fmt(p[0], 4), fmt(p[1], 4), fmt(p[1] / p[0], 4)])
            ax.axhline(1.0 / K, ls="--", color="0.4", lw=0.8)
            ax.set_title(f"quadratic, L = {L}, K = {K} (dashed: 1/K)", fontsize=8)
            ax.set_xlabel("whole unit, million transistors")
            ax.set_ylabel("vertices / cycle")
    axes[0][0].legend(fontsize=6)
    fig.suptitle("Throughput against the unit's transistors over CPG variant × N (line: Pareto front; "
                 "label Ec×r or S for the sequential CPG)", fontsize=9)
    fig.tight_layout(rect=(0, 0, 1, 0.96))
    out.save(fig, "cpg_pareto")
    out.table("Pareto front over CPG variant and N (quadratic normals)",
              ["K", "L", "configuration", "unit Mtr", "vertices/cycle", "vertices/cycle/Mtr"], front_rows)


def fig_cpg_variants(rows, out):
    """The CPG variants (grids cpg, cpg_fast): cycles per vertex against L, the cheapest unit
    that keeps up with the GPE at each L, throughput against cost, and the fastest unit."""
    g = in_grid(rows, "cpg")
    if not g:
        return out.skip("CPG variants", "no rows of grid 'cpg'")
    variants = sorted({cpg_variant(r) for r in g}, key=lambda v: (v[0], v[1]))
    Ls = distinct(g, "tess_factor")
    ops = {r["normals"]: r["int.ops_per_vertex"] for r in g}

    # Cycles per vertex against L, one line per variant.
    panels = [(m, n, K) for m in ("quadratic", "reflect") for n, K in ((2, 8), (4, 4))
              if any(r["normals"] == m and r["int_blocks"] == n and r["gpe_cycles"] == K for r in g)]
    fig, axes = plt.subplots(2, 2, figsize=(10.5, 8), sharex=True, squeeze=False)
    for ax, (mode, n, K) in zip(axes.flat, panels):
        for i, v in enumerate(variants):
            pts = sorted((r for r in g if cpg_variant(r) == v and r["normals"] == mode and r["int_blocks"] == n
                          and r["gpe_cycles"] == K), key=lambda r: r["tess_factor"])
            if not pts:
                continue
            ax.plot([r["tess_factor"] for r in pts], [r["cycles_per_vertex"] for r in pts],
                    "-o" if v[0] == 1 else "--s", ms=3, color=f"C{i % 10}", label=cpg_label(v))
            ax.plot([r["tess_factor"] for r in pts], [r["analytic.run_cycles_per_vertex"] for r in pts], "x",
                    ms=4, color="k", alpha=0.5)
        bound = max(K, ops[mode] / n)
        ax.axhline(bound, ls=":", color="0.3", lw=1)
        ax.set_title(f"{mode}, N = {n}, K = {K} (dotted: max(K, {ops[mode]}/N) = {fmt(bound, 3)}; x: model)",
                     fontsize=8)
        ax.set_xscale("log", base=2)
        ax.set_yscale("log")
        ax.yaxis.set_major_formatter(matplotlib.ticker.ScalarFormatter())
        ax.yaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
        ax.set_yticks([t for t in (2, 4, 8, 16, 32, 64) if t <= max(r["cycles_per_vertex"] for r in g) * 1.5])
        ax.set_xticks(Ls)
        ax.set_xticklabels([str(x) for x in Ls])
        ax.set_ylabel("cycles / vertex")
        ax.set_xlabel("tessellation factor L")
    axes[0][0].legend(fontsize=6, ncol=2)
    fig.suptitle(f"Cycles per vertex against L for each CPG variant: Ec edge lanes, r bits a cycle "
                 f"({workload(g, 'mesh', 'int_latency', 'te_contexts')})", fontsize=9)
    out.save(fig, "cpg_variants_vs_l")

    # C and the cost of each variant.
    table = []
    for v in variants:
        rv = [r for r in g if cpg_variant(r) == v]
        C = {m: next((r["cpg_cycles_per_triangle"] for r in rv if r["normals"] == m), "–") for m in ("quadratic", "reflect")}
        c = next((r for r in rv if r.get("cost_cpg_transistors") is not None), None)
        n2 = next((r for r in rv if r["int_blocks"] == 2 and r.get("cost_unit_transistors") is not None), None)
        table.append([cpg_label(v), C["quadratic"], C["reflect"],
                      fmt(c["cost_cpg_transistors"] / 1e6, 4) if c else "–",
                      c["cost_cpg_cells"] if c else "–", c["cost_cpg_flops"] if c else "–",
                      c["cost_cpg_depth"] if c else "–", c["cost_cpg_xilinx_lut"] if c else "–",
                      c["cost_cpg_xilinx_dsp"] if c else "–",
                      fmt(n2["cost_unit_transistors"] / 1e6, 4) if n2 else "–"])
    if not any(row[3] != "–" for row in table):
        out.skip("CPG variant costs", "no cost_cpg_* columns on grid 'cpg' (run scripts/costs.py)")
    out.table("CPG variants: cycles per triangle and cost",
              ["CPG", "C quadratic", "C reflect", "CPG Mtr", "CPG cells", "CPG flops", "CPG depth", "CPG LUT",
               "CPG DSP", "unit N = 2, Mtr"], table,
              note="Yosys 0.23, composed from per-module records (scripts/yosys_cost.py): the CPG is tess_cpg "
                   "and its submodules, the unit the N = 2 unit with that CPG.")

    # The cheapest unit that reaches the GPE's rate, per L.
    costed = [r for r in g if r.get("cost_unit_transistors") is not None]
    seq_depth = {r["int_blocks"]: r["cost_unit_depth"] for r in costed if cpg_variant(r) == (1, 1)}
    table = []
    for K in distinct(g, "gpe_cycles"):
        for mode in distinct(g, "normals"):
            for L in Ls:
                pts = [r for r in g if r["gpe_cycles"] == K and r["normals"] == mode and r["tess_factor"] == L]
                ok = [r for r in pts if r["throughput"] >= GPE_RATE_SHARE / K]
                seq = [r for r in ok if cpg_variant(r) == (1, 1)]
                ok_costed = [r for r in ok if r.get("cost_unit_transistors") is not None]
                best = min(ok_costed, key=lambda r: r["cost_unit_transistors"]) if ok_costed else None
                # The same, among units no deeper than with the sequential CPG (no slower clock).
                flat = [r for r in ok_costed if r["cost_unit_depth"] <= seq_depth.get(r["int_blocks"], 0)]
                best_flat = min(flat, key=lambda r: r["cost_unit_transistors"]) if flat else None
                fastest = max(pts, key=lambda r: r["throughput"]) if pts else None
                table.append([K, mode, L,
                              f"{cpg_label(cpg_variant(best))}, N = {best['int_blocks']}" if best else "none",
                              fmt(best["cost_unit_transistors"] / 1e6, 4) if best else "–",
                              fmt(best["throughput"] * K, 4) if best else "–",
                              best["cost_unit_depth"] if best else "–",
                              f"{cpg_label(cpg_variant(best_flat))}, N = {best_flat['int_blocks']} "
                              f"({fmt(best_flat['cost_unit_transistors'] / 1e6, 4)})" if best_flat else "none",
                              f"N = {min(r['int_blocks'] for r in seq)}" if seq else "none",
                              f"{fmt(fastest['throughput'] * K, 4)} ({cpg_label(cpg_variant(fastest))}, "
                              f"N = {fastest['int_blocks']})" if fastest else "–"])
    out.table("Cheapest unit that reaches the GPE's rate, per L",
              ["K", "normals", "L", f"cheapest (CPG, N) with throughput ≥ {GPE_RATE_SHARE}/K", "unit Mtr",
               "throughput × K", "unit depth", "cheapest no deeper than the sequential unit (Mtr)",
               "sequential CPG: smallest N", "best throughput × K (CPG, N)"], table,
              note=f"Grid `cpg` ({workload(g, 'mesh', 'int_latency', 'te_contexts')}); costs as in the table above.")

    # Throughput against cost, with the Pareto front, at K = 8 and K = 4 for small L.
    pL = [L for L in (2, 4, 8) if L in Ls]
    Ks = [K for K in (8, 4) if K in distinct(g, "gpe_cycles")]
    if costed:
        fig_cpg_pareto(costed, variants, pL, Ks, out)
    else:
        out.skip("CPG variants: throughput vs transistors", "no costed rows in grid 'cpg'")

    # A fast GPE (K = 1): the fastest units.
    f = in_grid(rows, "cpg_fast")
    if f:
        table = []
        for mode in distinct(f, "normals"):
            for L in distinct(f, "tess_factor"):
                pts = sorted((r for r in f if r["normals"] == mode and r["tess_factor"] == L),
                             key=lambda r: (r["cpg_digit_bits"], r["int_blocks"]))
                best = max(pts, key=lambda r: r["throughput"])
                table.append([mode, L] + [fmt(r["throughput"], 4) for r in pts] +
                             [f"{cpg_label(cpg_variant(best))}, N = {best['int_blocks']}: {best['bottleneck'].split(':')[0]}"])
        cols = [f"Ec {r['cpg_lanes']} r {r['cpg_digit_bits']} N {r['int_blocks']}"
                for r in sorted((r for r in f if r["normals"] == distinct(f, "normals")[0] and
                                 r["tess_factor"] == distinct(f, "tess_factor")[0]),
                                key=lambda r: (r["cpg_digit_bits"], r["int_blocks"]))]
        out.table("A fast geometry engine (K = 1): vertices per cycle", ["normals", "L"] + cols + ["best: bottleneck"],
                  table, note=f"Grid `cpg_fast` ({workload(f, 'mesh', 'int_latency', 'te_contexts', 'gpe_cycles')}).")

    # Adaptive factors with a faster CPG.
    a = in_grid(rows, "cpg_adaptive")
    if a:
        av = sorted({cpg_variant(r) for r in a})
        table = []
        for cam in sorted(distinct(a, "camera"), key=camera_distance):
            for n in distinct(a, "int_blocks"):
                for K in distinct(a, "gpe_cycles"):
                    pts = {cpg_variant(r): r for r in a if r["camera"] == cam and r["int_blocks"] == n
                           and r["gpe_cycles"] == K}
                    some = next(iter(pts.values()))
                    table.append([fmt(camera_distance(cam), 3), fmt(some["workload.vertices_per_patch.mean"], 3), n, K] +
                                 [fmt(pts[v]["cycles_per_vertex"], 4) if v in pts else "–" for v in av] +
                                 [fmt(max(K, some["int.ops_per_vertex"] / n), 3)])
        out.table("Adaptive factors with each CPG variant: cycles per vertex",
                  ["view distance", "mean vertices/patch", "N", "K"] + [cpg_label(v) for v in av] + ["max(K, ops/N)"],
                  table, note=f"Grid `cpg_adaptive` ({workload(a, 'mesh', 'normals', 'pixels_per_segment', 'te_contexts')}).")

    # The analytical model against the simulation on the CPG grids.
    both = g + (f or [])
    errs = sorted(abs(r["analytic.run_cycles"] - r["cycles"]) / r["cycles"] for r in both)
    worst = max(both, key=lambda r: abs(r["analytic.run_cycles"] - r["cycles"]) / r["cycles"])
    out.table("Analytical model against the cycle model, CPG variants",
              ["points", "within 0.1 %", "within 1 %", "largest difference", "at"],
              [[len(errs), sum(e <= 1e-3 for e in errs), sum(e <= 1e-2 for e in errs), f"{fmt(100 * errs[-1], 3)} %",
                f"{cpg_label(cpg_variant(worst))}, N = {worst['int_blocks']}, L = {worst['tess_factor']}, "
                f"K = {worst['gpe_cycles']}, V = {worst['te_contexts']}, {worst['normals']}"]])


def copies_of(r):
    return r.get("cpg_copies") or 1


def registered(r):
    """Registered CPG products at INT latency Λ (grids cpg_budget*): the within-budget design."""
    return bool(r.get("cpg_product_reg") or 0)


def copies_label(r):
    lanes, bits = cpg_variant(r)
    return (f"{lanes}x{bits}" + (f" ×{copies_of(r)}" if copies_of(r) > 1 else "") +
            (f" [reg, Λ {r['int_latency']}]" if registered(r) else ""))


# The pick of a grid cell: the cheapest configuration within this share of the fastest one.
PICK_SHARE = 0.97


def cheapest_near_best(pts, key):
    """The cheapest (unit transistors) of `pts` whose `key` is at least PICK_SHARE of the best."""
    if not pts:
        return None, None
    best = max(r[key] for r in pts)
    near = [r for r in pts if r[key] >= PICK_SHARE * best]
    return min(near, key=lambda r: r["cost_unit_transistors"]), best


def fig_cpg_copies(rows, out):
    """CPG copies (grids cpg_copies, cpg_copies_adaptive, cpg_copies_fast): throughput per cycle
    and per unit of time at the depth budget's clock against the unit's transistors, the picks on
    both bases, and the fast-GPE target."""
    g = [r for r in in_grid(rows, "cpg_copies") if r.get("cost_time_throughput") is not None]
    if not g:
        return out.skip("CPG copies", "no costed rows of grid 'cpg_copies' (run scripts/costs.py)")
    # The same workloads with registered CPG products at INT latency 3 (grids cpg_budget*): the
    # configurations that fit the depth budget, ranked beside the others.
    g = g + [r for r in in_grid(rows, "cpg_budget") if r.get("cost_time_throughput") is not None]
    budget = yosys_cost.DEPTH_BUDGET
    Ls = distinct(g, "tess_factor")
    K = g[0]["gpe_cycles"]

    def variant(r):
        return cpg_variant(r) + (registered(r),)

    variants = sorted({variant(r) for r in g})
    fig, axes = plt.subplots(2, len(Ls), figsize=(4.2 * len(Ls), 7.4), squeeze=False)
    for j, L in enumerate(Ls):
        for i, (key, ylabel) in enumerate((("throughput", "vertices / cycle"),
                                           ("cost_time_throughput", f"vertices / budget cycle ({budget} levels)"))):
            ax = axes[i][j]
            for v_i, v in enumerate(variants):
                pts = sorted((r for r in g if r["tess_factor"] == L and variant(r) == v), key=copies_of)
                style = (":^" if v[2] else "-o") if v[0] == 1 else (":v" if v[2] else "--s")
                ax.plot([r["cost_unit_transistors"] / 1e6 for r in pts], [r[key] for r in pts],
                        style, ms=3, color=f"C{v_i % 10}",
                        label=cpg_label(v[:2]) + (", registered, Λ 3" if v[2] else ""))
                for r in pts:
                    ax.annotate(str(copies_of(r)), (r["cost_unit_transistors"] / 1e6, r[key]),
                                textcoords="offset points", xytext=(2, 2), fontsize=5)
            if i == 0:
                ax.axhline(1.0 / K, ls="--", color="0.4", lw=0.8)
            ax.set_xscale("log")
            ax.set_title(f"L = {L}, {'per cycle (dashed: 1/K)' if i == 0 else 'per unit of time'}", fontsize=8)
            ax.set_xlabel("whole unit, million transistors")
            ax.set_ylabel(ylabel, fontsize=7)
    axes[0][0].legend(fontsize=6)
    fig.suptitle(f"CPG copies (number at each point) for each CPG (Ec×r): per cycle and at the configuration's "
                 f"clock, max({budget}, its logic depth) levels ({workload(g, 'mesh', 'normals', 'int_blocks', 'gpe_cycles', 'cp_buffers')})",
                 fontsize=8)
    fig.tight_layout(rect=(0, 0, 1, 0.95))
    out.save(fig, "cpg_copies")

    def pick_rows(cells):
        table = []
        for label, pts in cells:
            by_cycle, best_cycle = cheapest_near_best(pts, "throughput")
            by_time, best_time = cheapest_near_best(pts, "cost_time_throughput")
            by_eff = max(pts, key=lambda r: r["cost_time_throughput_per_mtr"])
            table.append([label,
                          f"{copies_label(by_cycle)}: {fmt(by_cycle['throughput'] * K, 4)}, "
                          f"{fmt(by_cycle['cost_unit_transistors'] / 1e6, 4)} Mtr, depth {by_cycle['cost_unit_depth']}",
                          f"{copies_label(by_time)}: {fmt(by_time['cost_time_throughput'] * K, 4)}, "
                          f"{fmt(by_time['cost_unit_transistors'] / 1e6, 4)} Mtr, depth {by_time['cost_unit_depth']}",
                          f"{copies_label(by_eff)}: {fmt(by_eff['cost_time_throughput_per_mtr'] * 1e3, 4)}",
                          "same" if copies_label(by_cycle) == copies_label(by_time) else "**differ**"])
        return table

    cols = ["workload", f"per cycle: cheapest within {PICK_SHARE} of the fastest (Ec×r ×Mc: throughput × K, cost)",
            "per time: the same at the configuration's clock (throughput × K per budget cycle)",
            "per time and transistor: best (10⁻³ vertices per budget cycle per Mtr)", "picks"]
    cells = [(f"L = {L}", [r for r in g if r["tess_factor"] == L]) for L in Ls]
    a = [r for r in in_grid(rows, "cpg_copies_adaptive") + in_grid(rows, "cpg_budget_adaptive")
         if r.get("cost_time_throughput") is not None]
    for cam in sorted(distinct(a, "camera"), key=camera_distance):
        pts = [r for r in a if r["camera"] == cam]
        cells.append((f"adaptive, view distance {fmt(camera_distance(cam), 3)} "
                      f"({fmt(pts[0]['workload.vertices_per_patch.mean'], 3)} vertices/patch)", pts))
    out.table("CPG copies: what to pick per cycle and per unit of time", cols, pick_rows(cells),
              note=f"Grids `cpg_copies`, `cpg_copies_adaptive` (INT latency 1) and `cpg_budget`, `cpg_budget_adaptive` "
                   f"(registered CPG products, INT latency 3: [reg, Λ 3]) ({workload(g, 'mesh', 'normals', 'int_blocks', 'gpe_cycles', 'cp_buffers')}); "
                   f"Ec×r ×Mc: edge lanes, digit bits, copies. Time: each configuration at its own clock of "
                   f"max({budget}, its deepest path) gate levels (scripts/yosys_cost.py, DEPTH_BUDGET), in units of "
                   f"the budget's cycle; K counts cycles of the unit's clock.")

    # Every configuration: C, copies, the start interval, cost, depth, per-cycle and per-time rates.
    table = []
    for r in sorted((r for r in g if r["tess_factor"] == Ls[0]), key=lambda r: (variant(r), copies_of(r))):
        table.append([copies_label(r), r["cpg_cycles_per_triangle"], copies_of(r),
                      math.ceil((r["cpg_cycles_per_triangle"] + 1) / copies_of(r)),
                      fmt(r["cost_cpg_transistors"] / 1e6, 4), fmt(r["cost_unit_transistors"] / 1e6, 4),
                      r["cost_cpg_depth"], r["cost_unit_depth"], r["cost_clock_levels"]] +
                     [fmt(next(x["throughput"] for x in g if x["tess_factor"] == L and copies_label(x) == copies_label(r)) * K, 4)
                      for L in Ls] +
                     [fmt(next(x["cost_time_throughput"] for x in g if x["tess_factor"] == L and copies_label(x) == copies_label(r)) * K, 4)
                      for L in Ls])
    out.table("CPG copies: every configuration",
              ["Ec×r ×Mc", "C", "Mc", "start interval", "CPG Mtr", "unit Mtr", "CPG depth", "unit depth",
               "clock levels"] + [f"throughput × K, L = {L}" for L in Ls] + [f"per budget cycle × K, L = {L}" for L in Ls],
              table, note="start interval: ⌈(C + 1)/Mc⌉ cycles between triangles when the TE keeps up.")

    # The fast geometry engine (K = 1): the L = 1..3 target of 0.95 vertices per cycle.
    f = in_grid(rows, "cpg_copies_fast")
    if f:
        table = []
        for L in distinct(f, "tess_factor"):
            for bits in distinct(f, "cpg_digit_bits"):
                pts = {copies_of(r): r for r in f if r["tess_factor"] == L and r["cpg_digit_bits"] == bits}
                first = min((m for m, r in pts.items() if r["throughput"] >= 0.95), default=None)
                table.append([L, f"3x{bits}", next(iter(pts.values()))["cpg_cycles_per_triangle"]] +
                             [fmt(pts[m]["throughput"], 4) if m in pts else "–" for m in distinct(f, "cpg_copies")] +
                             [first if first is not None else "none"])
        out.table("A fast geometry engine (K = 1): vertices per cycle against CPG copies",
                  ["L", "CPG", "C"] + [f"Mc = {m}" for m in distinct(f, "cpg_copies")] + ["fewest copies for ≥ 0.95"],
                  table, note=f"Grid `cpg_copies_fast` ({workload(f, 'mesh', 'normals', 'int_blocks', 'te_contexts', 'cp_buffers', 'gpe_cycles')}).")
