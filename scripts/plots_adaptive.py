"""The study's adaptive-factor figures (scripts/plots.py; docs/results/load-balancing.md): the
load per patch of each view, cycles per vertex against the analytical bounds, what buffering
absorbs, and the four D3D11 partitionings."""

import matplotlib.ticker

from plots_balance import cycles_against_n
from plots_data import camera_distance, distinct, fmt, in_grid, plt, workload


VERTEX_BUCKETS = ["3", "4–7", "8–15", "16–31", "32–63", "64–127", "128–255", "256–511", "512–1023",
                  "1024–2047", "2048–4095"]


def log_cycles_against_n(ax, Ns):
    """Cycles per vertex against N on a log axis with plain tick labels (the adaptive figures)."""
    cycles_against_n(ax, Ns)
    ax.set_yscale("log")
    ax.yaxis.set_major_formatter(matplotlib.ticker.ScalarFormatter())
    ax.yaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    ax.set_yticks([2, 3, 4, 5, 7, 10, 14, 20, 30, 40])


def used_buckets(rows):
    """Vertex-count buckets up to the last one any row fills (at least 8)."""
    last = 0
    for r in rows:
        for b in range(len(VERTEX_BUCKETS)):
            if r.get(f"workload.vertices_per_patch_log2_histogram.{b}"):
                last = max(last, b + 1)
    return max(8, last)


def fig_adaptive(rows, out):
    ad = in_grid(rows, "adaptive")
    if not ad:
        return out.skip("Adaptive factors", "no rows of grid 'adaptive'")
    cameras = sorted(distinct(ad, "camera"), key=camera_distance)
    modes = distinct(ad, "normals")
    Ks = distinct(ad, "gpe_cycles")
    Ns = distinct(ad, "int_blocks")
    fig, axes = plt.subplots(1, 1 + len(modes), figsize=(4.4 * (1 + len(modes)), 3.9), squeeze=False)
    ax = axes[0][0]
    width = 0.8 / len(cameras)
    table = []
    nb = used_buckets(ad)
    for i, cam in enumerate(cameras):
        r = next(r for r in ad if r["camera"] == cam)
        hist = [r[f"workload.vertices_per_patch_log2_histogram.{b}"] for b in range(len(VERTEX_BUCKETS))]
        ax.bar([b + (i - (len(cameras) - 1) / 2) * width for b in range(nb)], hist[:nb], width,
               color=f"C{i}", label=f"eye at {camera_distance(cam):.1f}")
        table.append([f"{camera_distance(cam):.1f}", r["workload.vertices_per_patch.min"],
                      fmt(r["workload.vertices_per_patch.mean"], 4), r["workload.vertices_per_patch.max"]] +
                     [n for n in hist[:nb]])
    ax.set_xticks(range(nb))
    ax.set_xticklabels(VERTEX_BUCKETS[:nb], fontsize=6, rotation=30)
    ax.set_xlabel("vertices per patch")
    ax.set_ylabel("patches")
    ax.set_title("per-patch load", fontsize=8)
    ax.legend(fontsize=6)
    perf = []
    for ax, mode in zip(axes[0][1:], modes):
        for i, cam in enumerate(cameras):
            for k_i, K in enumerate(Ks):
                pts = sorted((r for r in ad if r["camera"] == cam and r["normals"] == mode and r["gpe_cycles"] == K),
                             key=lambda r: r["int_blocks"])
                style = "o-" if k_i == 0 else "x--"
                ax.plot([r["int_blocks"] for r in pts], [r["cycles_per_vertex"] for r in pts], style, ms=4,
                        color=f"C{i}", label=f"eye at {camera_distance(cam):.1f}, K = {K}")
                for r in pts:
                    perf.append([mode, f"{camera_distance(cam):.1f}", K, r["int_blocks"],
                                 fmt(r["workload.vertices_per_patch.mean"], 4), fmt(r["cycles_per_vertex"], 4),
                                 fmt(r["analytic.varying.no_buffer_cycles_per_vertex"], 4),
                                 fmt(r["analytic.varying.full_buffer_cycles_per_vertex"], 4),
                                 r["bottleneck"].split(":")[0]])
        log_cycles_against_n(ax, Ns)
        ax.set_title(f"{mode} normals: K = {Ks[0]} solid, K = {Ks[-1]} dashed", fontsize=8)
    axes[0][-1].legend(fontsize=6)
    fig.suptitle(f"Adaptive factors: every triangle its own D3D11 factors from a camera ({workload(ad, 'mesh', 'partitioning')}, "
                 f"{ad[0]['pixels_per_segment']} pixels per segment)", fontsize=8)
    out.save(fig, "adaptive")
    out.table("Adaptive factors: patches by vertex count", ["eye distance", "min", "mean", "max"] + VERTEX_BUCKETS[:nb],
              table)
    out.table("Adaptive factors: cycles per vertex against the two analytical bounds",
              ["normals", "eye distance", "K", "N", "vertices per patch", "simulated", "no-buffer bound",
               "full-buffer bound", "limit"], perf,
              note="No-buffer bound: every patch costs max(C + 1, P·b) on its own; full-buffer bound: "
                   "max(n(C + 1), V·b) for the whole run (sim/config/analytic.hpp).")

    bf = in_grid(rows, "adaptive_buffers")
    if not bf:
        return out.skip("Adaptive factors: buffers", "no rows of grid 'adaptive_buffers'")
    table = []
    fig, axes = plt.subplots(1, len(distinct(bf, "camera")), figsize=(4.6 * len(distinct(bf, "camera")), 3.8),
                             squeeze=False)
    for ax, cam in zip(axes[0], sorted(distinct(bf, "camera"), key=camera_distance)):
        for n_i, N in enumerate(distinct(bf, "int_blocks")):
            for v_i, V in enumerate(distinct(bf, "te_contexts")):
                pts = sorted((r for r in bf if r["camera"] == cam and r["int_blocks"] == N and r["te_contexts"] == V),
                             key=lambda r: r["vtx_fifo_depth"])
                ax.plot([r["vtx_fifo_depth"] for r in pts], [r["cycles_per_vertex"] for r in pts],
                        "o-" if v_i == 0 else "x--", ms=4, color=f"C{n_i}", label=f"N = {N}, V = {V}")
                table.append([f"{camera_distance(cam):.1f}", N, V] + [fmt(r["cycles_per_vertex"], 4) for r in pts] +
                             [fmt(pts[0]["analytic.varying.no_buffer_cycles_per_vertex"], 4),
                              fmt(pts[0]["analytic.varying.full_buffer_cycles_per_vertex"], 4)])
            r0 = next(r for r in bf if r["camera"] == cam and r["int_blocks"] == N)
            ax.axhline(r0["analytic.varying.full_buffer_cycles_per_vertex"], color=f"C{n_i}", lw=0.7, ls=":")
        ax.set_xscale("log", base=2)
        ax.set_xlabel("VTX FIFO depth")
        ax.set_ylabel("cycles per vertex")
        ax.set_title(f"eye at {camera_distance(cam):.1f} (dotted: full-buffer bound)", fontsize=8)
    axes[0][-1].legend(fontsize=6)
    fig.suptitle(f"Adaptive factors: what buffering absorbs ({workload(bf, 'mesh', 'normals', 'gpe_cycles')})",
                 fontsize=8)
    out.save(fig, "adaptive_buffers")
    depths = distinct(bf, "vtx_fifo_depth")
    out.table("Adaptive factors: cycles per vertex against the VTX FIFO depth and the contexts",
              ["eye distance", "N", "V"] + [f"VTX FIFO {d}" for d in depths] + ["no-buffer bound", "full-buffer bound"],
              table)


def fig_adaptive_partitioning(rows, out):
    """The four D3D11 partitionings on the same adaptive views: load per patch and cycles per
    vertex against N (grid adaptive_partitioning)."""
    ap = in_grid(rows, "adaptive_partitioning")
    if not ap:
        return out.skip("Adaptive factors: partitionings", "no rows of grid 'adaptive_partitioning'")
    cameras = sorted(distinct(ap, "camera"), key=camera_distance)
    parts = [p for p in ("integer", "pow2", "fractional_odd", "fractional_even") if p in distinct(ap, "partitioning")]
    Ks = distinct(ap, "gpe_cycles")
    Ns = distinct(ap, "int_blocks")
    fig, axes = plt.subplots(1, 1 + len(cameras), figsize=(4.2 * (1 + len(cameras)), 3.8), squeeze=False)
    ax = axes[0][0]
    width = 0.8 / len(parts)
    near = cameras[0]
    nb = used_buckets(ap)
    load = []
    for i, part in enumerate(parts):
        for cam in cameras:
            r = next(r for r in ap if r["camera"] == cam and r["partitioning"] == part)
            hist = [r[f"workload.vertices_per_patch_log2_histogram.{b}"] for b in range(len(VERTEX_BUCKETS))]
            load.append([part, f"{camera_distance(cam):.1f}", r["workload.vertices_per_patch.min"],
                         fmt(r["workload.vertices_per_patch.mean"], 4), r["workload.vertices_per_patch.max"]] + hist[:nb])
            if cam == near:
                ax.bar([b + (i - (len(parts) - 1) / 2) * width for b in range(nb)], hist[:nb], width, color=f"C{i}",
                       label=part)
    ax.set_xticks(range(nb))
    ax.set_xticklabels(VERTEX_BUCKETS[:nb], fontsize=6, rotation=30)
    ax.set_xlabel("vertices per patch")
    ax.set_ylabel("patches")
    ax.set_title(f"per-patch load, eye at {camera_distance(near):.1f}", fontsize=8)
    ax.legend(fontsize=6)
    perf = []
    for ax, cam in zip(axes[0][1:], cameras):
        for i, part in enumerate(parts):
            for k_i, K in enumerate(Ks):
                pts = sorted((r for r in ap if r["camera"] == cam and r["partitioning"] == part and r["gpe_cycles"] == K),
                             key=lambda r: r["int_blocks"])
                ax.plot([r["int_blocks"] for r in pts], [r["cycles_per_vertex"] for r in pts],
                        "o-" if k_i == 0 else "x--", ms=4, color=f"C{i}", label=f"{part}, K = {K}")
                for r in pts:
                    perf.append([part, f"{camera_distance(cam):.1f}", K, r["int_blocks"],
                                 fmt(r["workload.vertices_per_patch.mean"], 4), fmt(r["cycles_per_vertex"], 4),
                                 fmt(r["int.utilisation"], 3),
                                 fmt(r["analytic.varying.no_buffer_cycles_per_vertex"], 4),
                                 fmt(r["analytic.varying.full_buffer_cycles_per_vertex"], 4),
                                 r["bottleneck"].split(":")[0]])
        log_cycles_against_n(ax, Ns)
        ax.set_title(f"eye at {camera_distance(cam):.1f}: K = {Ks[0]} solid, K = {Ks[-1]} dashed", fontsize=8)
    axes[0][-1].legend(fontsize=6)
    fig.suptitle(f"Adaptive D3D11 patterns, the four partitionings ({workload(ap, 'mesh', 'normals')}, "
                 f"{ap[0]['pixels_per_segment']} pixels per segment)", fontsize=8)
    out.save(fig, "adaptive_partitioning")
    out.table("Adaptive factors by partitioning: patches by vertex count",
              ["partitioning", "eye distance", "min", "mean", "max"] + VERTEX_BUCKETS[:nb], load)
    out.table("Adaptive factors by partitioning: cycles per vertex",
              ["partitioning", "eye distance", "K", "N", "vertices per patch", "simulated", "INT utilisation",
               "no-buffer bound", "full-buffer bound", "limit"], perf)
