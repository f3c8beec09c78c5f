"""The study's balance figures (scripts/plots.py; docs/results/load-balancing.md): throughput and
utilisation against the INT blocks N per GPE rate K, and throughput against the unit's Yosys cost
with its Pareto front, per cycle and per time at the depth budget's clock."""

import yosys_cost  # the depth budget
from plots_data import distinct, fmt, in_grid, plt, share, workload


def cycles_against_n(ax, Ns):
    """Axes of a cycles-per-vertex against N panel."""
    ax.set_xticks(Ns)
    ax.set_xlabel("INT blocks N")
    ax.set_ylabel("cycles per vertex")


def balanced_n(rows, K):
    """Smallest N whose throughput reaches 99 % of the best throughput measured at this K."""
    at_k = sorted((r for r in rows if r["gpe_cycles"] == K), key=lambda r: r["int_blocks"])
    if not at_k:
        return None, None
    best = max(r["throughput"] for r in at_k)
    for r in at_k:
        if r["throughput"] >= 0.99 * best:
            return r["int_blocks"], best
    return None, best


def fig_throughput_vs_n(rows, out):
    b = in_grid(rows, "balance")
    if not b:
        return out.skip("throughput vs N", "no rows of grid 'balance'")
    Ks = distinct(b, "gpe_cycles")
    Ns = distinct(b, "int_blocks")
    fig, ax = plt.subplots(figsize=(7, 4.4))
    cmap = plt.get_cmap("viridis")
    table = []
    for i, K in enumerate(Ks):
        pts = sorted((r for r in b if r["gpe_cycles"] == K), key=lambda r: r["int_blocks"])
        color = cmap(i / max(1, len(Ks) - 1))
        ax.plot([r["int_blocks"] for r in pts], [r["throughput"] for r in pts], "o-", color=color,
                ms=4, label=f"K = {K}")
        ax.plot([r["int_blocks"] for r in pts], [r["analytic.throughput"] for r in pts], ":",
                color=color, lw=1)
        n_bal, best = balanced_n(b, K)
        if n_bal is not None:
            r = next(r for r in pts if r["int_blocks"] == n_bal)
            ax.plot([n_bal], [r["throughput"]], "s", ms=10, mfc="none", mec=color, mew=1.5)
        row1 = next((r for r in pts if r["int_blocks"] == 1), None)
        row2 = next((r for r in pts if r["int_blocks"] == 2), None)
        table.append([K, fmt(row1["throughput"] if row1 else None, 4), fmt(row2["throughput"] if row2 else None, 4),
                      fmt(best, 4), fmt(1.0 / K, 4), n_bal,
                      fmt(row2["throughput"] / best if row2 and best else None, 3)])
    ax.set_xscale("log", base=2)
    ax.set_xticks(Ns)
    ax.set_xticklabels([str(n) for n in Ns])
    ax.set_yscale("log", base=2)
    ticks = [1 / 16, 1 / 14, 1 / 8, 1 / 7, 1 / 4, 1 / 2, 1]
    ax.set_yticks(ticks)
    ax.set_yticklabels(["1/16", "1/14", "1/8", "1/7", "1/4", "1/2", "1"])
    ax.minorticks_off()
    ax.set_xlabel("INT blocks N")
    ax.set_ylabel("throughput (vertices accepted by the GPE per cycle)")
    ax.set_title(f"Throughput vs INT blocks, one line per GPE rate K ({workload(b, 'mesh', 'tess_factor', 'int_latency', 'te_contexts', 'normals', 'cpg_mapping')})\n"
                 "solid: cycle model; dotted: analytical model; square: smallest N within 1 % of the best at that K",
                 fontsize=8)
    ax.legend(loc="center left", bbox_to_anchor=(1.01, 0.5))
    out.save(fig, "throughput_vs_n")
    out.table("Balance: throughput (vertices/cycle) and the smallest sufficient N per GPE rate K",
              ["K", "N = 1", "N = 2", "best over N", "GPE limit 1/K", "smallest N within 1 % of best",
               "N = 2 / best"], table,
              note=f"Grid `balance` ({workload(b, 'mesh', 'tess_factor', 'int_latency', 'te_contexts', 'normals', 'cpg_mapping')}), N in {Ns}.")


def fig_utilisation_vs_n(rows, out):
    b = in_grid(rows, "balance")
    if not b:
        return out.skip("utilisation vs N", "no rows of grid 'balance'")
    Ks = distinct(b, "gpe_cycles")
    Ns = distinct(b, "int_blocks")
    fig, axes = plt.subplots(1, 2, figsize=(9, 3.8), sharex=True)
    cmap = plt.get_cmap("viridis")
    for i, K in enumerate(Ks):
        pts = sorted((r for r in b if r["gpe_cycles"] == K), key=lambda r: r["int_blocks"])
        color = cmap(i / max(1, len(Ks) - 1))
        n = [r["int_blocks"] for r in pts]
        axes[0].plot(n, [100 * r["int.utilisation"] for r in pts], "o-", ms=3, color=color, label=f"K = {K}")
        axes[1].plot(n, [100 * share(r, "gpe.busy") for r in pts], "o-", ms=3, color=color, label=f"K = {K}")
    for ax, title in zip(axes, ["INT utilisation = Σ busy / (N · cycles)", "GPE busy share of cycles"]):
        ax.set_xscale("log", base=2)
        ax.set_xticks(Ns)
        ax.set_xticklabels([str(x) for x in Ns])
        ax.set_xlabel("INT blocks N")
        ax.set_ylabel("%")
        ax.set_ylim(0, 105)
        ax.set_title(title, fontsize=9)
    axes[1].legend(fontsize=7, loc="center left", bbox_to_anchor=(1.01, 0.5))
    fig.suptitle(f"Utilisation vs N ({workload(b, 'mesh', 'tess_factor', 'int_latency', 'te_contexts', 'normals')})",
                 fontsize=9)
    out.save(fig, "utilisation_vs_n")


PARETO_MARGIN = 0.005  # a dearer configuration must be more than 0.5 % faster to count as faster


def pareto(points):
    """Points (cost, throughput, ...) that no cheaper-or-equal point matches in throughput
    (within PARETO_MARGIN: fill and drain make equal rates differ in the last digits)."""
    front = []
    best = 0.0
    for p in sorted(points, key=lambda p: (p[0], -p[1])):
        if p[1] > best * (1 + PARETO_MARGIN):
            front.append(p)
            best = p[1]
    return front


def fig_cost(rows, out):
    costed = [r for r in rows if r.get("cost_unit_transistors") is not None]
    b = [r for r in costed if "balance" in r["grid_set"] or "costs" in r["grid_set"]]
    if not b:
        return out.skip("throughput vs transistors", "no costed rows (run scripts/costs.py)")
    Ks = [K for K in (1, 4, 6, 8, 12) if any(r["gpe_cycles"] == K for r in b)]
    if not Ks:
        Ks = distinct(b, "gpe_cycles")[:5]
    fig, grid = plt.subplots(2, 3, figsize=(11, 7))
    axes = list(grid.flat)[:len(Ks)]
    table = []
    efficiency = {}
    for ax, K in zip(axes, Ks):
        pts = []
        for r in b:
            if r["gpe_cycles"] != K:
                continue
            label = f"N{r['int_blocks']}"
            if r["int_latency"] != 1:
                label += f" Λ{r['int_latency']}"
            if r["te_contexts"] != 4:
                label += f" V{r['te_contexts']}"
            if r["coord_frac_bits"] != 20 or r["bary_bits"] != 16:
                label += f" F{r['coord_frac_bits']} B{r['bary_bits']}"
            pts.append((r["cost_unit_transistors"] / 1e6, r["throughput"], label, r))
        # One point per RTL configuration.
        seen, uniq = set(), []
        for p in sorted(pts, key=lambda p: p[2]):
            if p[2] not in seen:
                seen.add(p[2])
                uniq.append(p)
        front = pareto(uniq)
        ax.plot([p[0] for p in uniq], [p[1] for p in uniq], "o", color="0.6", ms=4)
        ax.step([p[0] for p in front], [p[1] for p in front], "-", where="post", color="C3", lw=1)
        ax.plot([p[0] for p in front], [p[1] for p in front], "o", color="C3", ms=6, label="Pareto front")
        # Labels alternate below and above their points: neighbours in cost often share a rate.
        for i, p in enumerate(sorted(uniq, key=lambda p: p[0])):
            ax.annotate(p[2], (p[0], p[1]), textcoords="offset points", xytext=(3, -9 if i % 2 == 0 else 5),
                        fontsize=6)
            efficiency.setdefault(p[2], {})[K] = (p[1] / p[0], p[0])
        ax.axhline(1.0 / K, ls="--", color="0.4", lw=0.8)
        ax.set_title(f"K = {K} (dashed: GPE limit 1/K)", fontsize=8)
        ax.set_xlabel("whole unit, million transistors")
        ax.set_ylabel("vertices / cycle")
        for p in front:
            r = p[3]
            table.append([K, p[2], fmt(p[0], 4), fmt(p[1], 4), fmt(p[1] / p[0], 4),
                          fmt(r.get("cost_int_transistors", 0) / 1e6, 3),
                          fmt(r.get("cost_cpg_transistors", 0) / 1e6, 3), r.get("cost_unit_depth", "–"),
                          r.get("cost_unit_xilinx_lut", "–")])
    # Last panel: throughput per transistor, the "performance for the hardware" of each configuration.
    eff_ax = grid.flat[-1]
    labels = sorted(efficiency, key=lambda l: min(c for _, c in efficiency[l].values()))
    for i, K in enumerate(Ks):
        xs = [j for j, l in enumerate(labels) if K in efficiency[l]]
        eff_ax.plot(xs, [efficiency[labels[j]][K][0] for j in xs], "o-", ms=3, color=f"C{i}", label=f"K = {K}")
    eff_ax.set_xticks(range(len(labels)))
    eff_ax.set_xticklabels(labels, rotation=45, ha="right", fontsize=7)
    eff_ax.set_ylabel("vertices / cycle per million transistors")
    eff_ax.set_title("throughput per transistor", fontsize=8)
    eff_ax.legend(fontsize=6)
    for ax in list(grid.flat)[len(Ks):-1]:
        ax.axis("off")
    axes[0].legend(fontsize=7, loc="lower right")
    fig.tight_layout(rect=(0, 0, 1, 0.95))
    fig.suptitle(f"Throughput vs hardware cost ({workload(b, 'mesh', 'tess_factor', 'normals')}); "
                 "label: INT blocks N; latency Λ, contexts V, widths F/B where not 1, 4, 20/16", fontsize=8)
    out.save(fig, "throughput_vs_cost")
    out.table("Pareto front: throughput vs transistors of the whole unit",
              ["K", "configuration", "unit Mtransistors", "vertices/cycle", "vertices/cycle per Mtr.",
               "one INT block Mtr.", "CPG Mtr.", "logic depth", "Xilinx LUTs"], table,
              note="A configuration is on the front when every configuration with fewer or as many transistors "
                   "is at least 0.5 % slower. Costs: scripts/costs.py (scripts/synth.sh, Yosys 0.23).")
    # Throughput per transistor at every K of the balance grid (default Λ, V and widths).
    bal = [r for r in costed if "balance" in r["grid_set"]]
    Ns = distinct(bal, "int_blocks")
    rows_eff = []
    for K in distinct(bal, "gpe_cycles"):
        vals = {r["int_blocks"]: r["throughput"] / (r["cost_unit_transistors"] / 1e6)
                for r in bal if r["gpe_cycles"] == K}
        best = max(vals, key=vals.get)
        rows_eff.append([K] + [(f"**{fmt(vals[n], 4)}**" if n == best else fmt(vals[n], 4)) if n in vals else "–"
                               for n in Ns])
    if rows_eff:
        out.table("Throughput per million transistors (vertices/cycle/Mtr.; best per K in bold)",
                  ["K"] + [f"N = {n}" for n in Ns], rows_eff,
                  note=f"Grid `balance` ({workload(bal, 'mesh', 'tess_factor', 'int_latency', 'te_contexts', 'normals')}), "
                       "whole-unit transistors.")
    # Per time instead of per cycle: each configuration at its own clock, the depth budget or its
    # deepest path if longer (scripts/yosys_cost.py, DEPTH_BUDGET), in units of the budget's cycle.
    timed = [r for r in bal if r.get("cost_time_throughput") is not None]
    if timed:
        depths = {r["int_blocks"]: r["cost_unit_depth"] for r in timed}
        rows_time = []
        for K in distinct(timed, "gpe_cycles"):
            vals = {r["int_blocks"]: r["cost_time_throughput"] for r in timed if r["gpe_cycles"] == K}
            best = max(vals, key=vals.get)
            rows_time.append([K] + [(f"**{fmt(vals[n], 4)}**" if n == best else fmt(vals[n], 4)) if n in vals
                                    else "–" for n in Ns])
        budget = yosys_cost.DEPTH_BUDGET
        out.table(f"Throughput per time at the configuration's clock (vertices per {budget}-level budget cycle)",
                  ["K"] + [f"N = {n}" for n in Ns], rows_time,
                  note=f"Clock: max({budget}, the unit's deepest path) gate levels (`ltp`, generic cells); depths "
                       + ", ".join(f"N = {n}: {d}" for n, d in sorted(depths.items()))
                       + f". Entries are vertices/cycle x {budget} / clock levels; best per K in bold. The GPE's K "
                         "is counted in cycles of the unit's clock.")
    # All costed configurations, once each.
    configs = {}
    for r in costed:
        key = (r["int_blocks"], r["int_latency"], r["te_contexts"], r["coord_int_bits"], r["coord_frac_bits"],
               r["bary_bits"])
        configs.setdefault(key, r)
    out.table("Hardware cost of every synthesized configuration",
              ["N", "Λ", "V", "I.F", "B", "unit Mtr.", "unit cells", "unit FF", "depth", "LUT", "FF (Xilinx)",
               "DSP", "INT block Mtr.", "CPG Mtr.", "CPG depth"],
              [[k[0], k[1], k[2], f"{k[3]}.{k[4]}", k[5], fmt(r["cost_unit_transistors"] / 1e6, 4),
                r.get("cost_unit_cells", "–"), r.get("cost_unit_flops", "–"), r.get("cost_unit_depth", "–"),
                r.get("cost_unit_xilinx_lut", "–"), r.get("cost_unit_xilinx_ff", "–"),
                r.get("cost_unit_xilinx_dsp", "–"),
                fmt((r.get("cost_int_transistors") or float("nan")) / 1e6, 3),
                fmt((r.get("cost_cpg_transistors") or float("nan")) / 1e6, 3), r.get("cost_cpg_depth", "–")]
               for k, r in sorted(configs.items())])
