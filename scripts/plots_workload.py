"""The study's figures and tables of the TE and its surroundings (scripts/plots.py;
docs/results/load-balancing.md): contexts and INT latency, the normal modes, GPE stalls, and the
tables of the latency, CPG-on-GPE and three-mesh grids."""

from plots_balance import balanced_n, cycles_against_n
from plots_data import distinct, fmt, in_grid, mesh_name, plt, workload


def fig_contexts(rows, out):
    c = in_grid(rows, "contexts")
    if not c:
        return out.skip("contexts and latency", "no rows of grid 'contexts'")
    lats = distinct(c, "int_latency")
    Vs = distinct(c, "te_contexts")
    Ns = distinct(c, "int_blocks")
    fig, axes = plt.subplots(1, len(lats), figsize=(3.6 * len(lats), 3.8), sharey=True, squeeze=False)
    table = []
    for ax, lam in zip(axes[0], lats):
        for i, V in enumerate(Vs):
            pts = sorted((r for r in c if r["int_latency"] == lam and r["te_contexts"] == V),
                         key=lambda r: r["int_blocks"])
            ax.plot([r["int_blocks"] for r in pts], [r["cycles_per_vertex"] for r in pts], "o-", ms=3,
                    color=f"C{i}", label=f"V = {V}")
            ax.plot([r["int_blocks"] for r in pts], [r["analytic.cycles_per_vertex"] for r in pts], ":",
                    color=f"C{i}", lw=1)
            for r in pts:
                sim, model = r["cycles_per_vertex"], r["analytic.cycles_per_vertex"]
                table.append([lam, V, r["int_blocks"], fmt(sim, 4), fmt(model, 4),
                              fmt(100 * (sim - model) / model, 2), r["analytic.bottleneck"]])
        ax.set_xscale("log", base=2)
        ax.set_yscale("log", base=2)
        ax.set_xticks(Ns)
        ax.set_xticklabels([str(x) for x in Ns])
        ax.set_yticks([1, 2, 4, 8, 16])
        ax.set_yticklabels(["1", "2", "4", "8", "16"])
        ax.set_title(f"INT latency Λ = {lam}", fontsize=8)
        ax.set_xlabel("INT blocks N")
    axes[0][0].set_ylabel("cycles per vertex")
    axes[0][0].legend(fontsize=7)
    fig.suptitle(f"TE alone (GPE K = 1): cycles per vertex vs N for V contexts; solid: cycle model, dotted: "
                 f"analytical model ({workload(c, 'mesh', 'tess_factor', 'normals')})", fontsize=8)
    out.save(fig, "contexts_latency")
    out.table("TE alone (K = 1): cycle model vs analytical model", ["Λ", "V", "N", "simulated cycles/vertex",
              "analytic", "difference %", "analytic bottleneck"], table)


def fig_normals(rows, out):
    nrm = in_grid(rows, "normals")
    if not nrm:
        return out.skip("normal modes", "no rows of grid 'normals'")
    Ls = distinct(nrm, "tess_factor")
    Ks = distinct(nrm, "gpe_cycles")
    Ns = distinct(nrm, "int_blocks")
    fig, axes = plt.subplots(1, len(Ls), figsize=(4.2 * len(Ls), 3.8), sharey=True, squeeze=False)
    table = []
    styles = {"quadratic": "-", "reflect": "--", "linear": ":"}
    for ax, L in zip(axes[0], Ls):
        for i, K in enumerate(Ks):
            for mode in ("quadratic", "reflect", "linear"):
                pts = sorted((r for r in nrm if r["tess_factor"] == L and r["gpe_cycles"] == K and
                              r["normals"] == mode), key=lambda r: r["int_blocks"])
                if not pts:
                    continue
                ax.plot([r["int_blocks"] for r in pts], [r["throughput"] for r in pts], styles[mode] + "o",
                        ms=3, color=f"C{i}", label=f"K = {K}, {mode}")
                n_bal, best = balanced_n(pts, K)
                table.append([L, K, mode, pts[0]["cpg_cycles_per_triangle"],
                              fmt(next((r["throughput"] for r in pts if r["int_blocks"] == 2), None), 4),
                              fmt(best, 4), n_bal])
        ax.set_xscale("log", base=2)
        ax.set_xticks(Ns)
        ax.set_xticklabels([str(x) for x in Ns])
        ax.set_xlabel("INT blocks N")
        ax.set_title(f"L = {L}", fontsize=8)
    axes[0][0].set_ylabel("vertices / cycle")
    axes[0][-1].legend(fontsize=6)
    fig.suptitle(f"Normal modes: quadratic (14 ops, C = 245), reflect (14 ops, C = 98), linear (11 ops, C = 20) "
                 f"({workload(nrm, 'mesh', 'cpg_mapping')})", fontsize=8)
    out.save(fig, "normals")
    out.table("Normal modes: throughput at N = 2, best over N, smallest N within 1 % of the best",
              ["L", "K", "normals", "C (CPG cycles)", "N = 2", "best", "smallest N"], table)


def fig_stall(rows, out):
    st = in_grid(rows, "stall")
    if not st:
        return out.skip("GPE random stalls", "no rows of grid 'stall'")
    Ks = distinct(st, "gpe_cycles")
    probs = distinct(st, "gpe_stall_prob")
    depths = distinct(st, "vtx_fifo_depth")
    Ns = distinct(st, "int_blocks")
    fig, axes = plt.subplots(1, len(Ks), figsize=(4.2 * len(Ks), 3.8), squeeze=False)
    table = []
    for ax, K in zip(axes[0], Ks):
        for i, prob in enumerate(probs):
            for d_i, depth in enumerate(depths):
                pts = sorted((r for r in st if r["gpe_cycles"] == K and r["gpe_stall_prob"] == prob and
                              r["vtx_fifo_depth"] == depth), key=lambda r: r["int_blocks"])
                ax.plot([r["int_blocks"] for r in pts], [r["cycles_per_vertex"] for r in pts],
                        "o-" if d_i == 0 else "x--", ms=4, color=f"C{i}", lw=1.5 if d_i == 0 else 1,
                        label=f"stall {prob}, VTX FIFO {depth}")
                table.append([K, prob, depth] + [fmt(r["cycles_per_vertex"], 4) for r in pts] +
                             [fmt(K - 1 + 1 / (1 - prob), 4)])
        cycles_against_n(ax, Ns)
        ax.set_title(f"K = {K}", fontsize=8)
    axes[0][-1].legend(fontsize=6)
    fig.suptitle(f"GPE with random stalls (probability per cycle), VTX FIFO depth 2 (solid) and 8 (dashed) "
                 f"({workload(st, 'mesh', 'tess_factor', 'normals')})", fontsize=8)
    out.save(fig, "gpe_stall")
    out.table("GPE random stalls: cycles per vertex", ["K", "stall probability", "VTX FIFO depth"] +
              [f"N = {n}" for n in Ns] + ["GPE alone: K − 1 + 1/(1 − p)"], table)


def tables_extra(rows, out):
    lg = in_grid(rows, "latency_gpe")
    if lg:
        table = []
        for K in distinct(lg, "gpe_cycles"):
            for lam in distinct(lg, "int_latency"):
                for V in distinct(lg, "te_contexts"):
                    pts = sorted((r for r in lg if r["gpe_cycles"] == K and r["int_latency"] == lam and
                                  r["te_contexts"] == V), key=lambda r: r["int_blocks"])
                    reach = [r["int_blocks"] for r in pts if r["cycles_per_vertex"] <= K * 1.01]
                    table.append([K, lam, V] + [fmt(r["cycles_per_vertex"], 4) for r in pts] +
                                 [reach[0] if reach else "none ≤ " + str(pts[-1]["int_blocks"])])
        out.table("INT latency and contexts against the GPE: cycles per vertex",
                  ["K", "Λ", "V"] + [f"N = {n}" for n in distinct(lg, "int_blocks")] +
                  ["smallest N at the GPE limit (≤ 1.01 K)"], table,
                  note=f"Grid `latency_gpe` ({workload(lg, 'mesh', 'tess_factor', 'normals', 'cpg_mapping')}).")
    cg = in_grid(rows, "cpg_gpe_cycles")
    if cg:
        Cs = distinct(cg, "cpg_gpe_cycles")
        table = []
        for L in distinct(cg, "tess_factor"):
            pts = sorted((r for r in cg if r["tess_factor"] == L), key=lambda r: r["cpg_gpe_cycles"])
            table.append([L] + [f"{fmt(r['cycles_per_vertex'], 4)} ({fmt(r['analytic.cycles_per_vertex'], 4)})"
                                for r in pts])
        out.table("CPG on the GPE: cycles per vertex (analytic in brackets) vs GPE cycles per triangle",
                  ["L"] + [f"C = {c}" for c in Cs], table,
                  note=f"Grid `cpg_gpe_cycles` ({workload(cg, 'mesh', 'int_blocks', 'gpe_cycles', 'normals')}).")
    bm = in_grid(rows, "balance_meshes") + [r for r in in_grid(rows, "balance")
                                             if r["gpe_cycles"] in distinct(in_grid(rows, "balance_meshes"), "gpe_cycles")
                                             and r["int_blocks"] in distinct(in_grid(rows, "balance_meshes"), "int_blocks")]
    if in_grid(rows, "balance_meshes"):
        Ns = distinct(bm, "int_blocks")
        table = []
        for mesh in distinct(bm, "mesh"):
            for K in distinct(bm, "gpe_cycles"):
                pts = sorted((r for r in bm if r["mesh"] == mesh and r["gpe_cycles"] == K),
                             key=lambda r: r["int_blocks"])
                table.append([mesh_name(mesh), pts[0]["triangles"], K] + [fmt(r["cycles_per_vertex"], 5) for r in pts] +
                             [pts[0]["warnings.degenerate_patches"]])
        out.table("Same grid on three meshes: cycles per vertex", ["mesh", "triangles", "K"] +
                  [f"N = {n}" for n in Ns] + ["degenerate patches"], table,
                  note=f"{workload(bm, 'tess_factor', 'normals', 'cpg_mapping', 'int_latency', 'te_contexts')}.")
