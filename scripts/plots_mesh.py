"""The study's figures that read the mesh through `tessim info` (scripts/plots.py;
docs/results/load-balancing.md): the fixed-point error against the coordinate and barycentric
widths with the arithmetic bound, and the bus traffic the unit saves."""

import math

from plots_data import distinct, fmt, fmt_kb, in_grid, mesh_name, plt, workload


def arithmetic_bound(F, I, info):
    """Position bound of docs/number-formats.md §5.1 (Euclidean, relative to the diagonal): the
    bound in unit coordinates from `tessim schema`, scaled by the mesh's half-extent."""
    return info["position_bound"][(I, F)] * info["half_extent"] / info["diagonal"]


def fig_errors(rows, out, mesh_info):
    w = [r for r in in_grid(rows, "widths") if r.get("error.position_max") is not None]
    if not w:
        return out.skip("error vs width", "no rows of grid 'widths' with errors")
    from matplotlib.lines import Line2D
    fig, axes = plt.subplots(2, 2, figsize=(9, 6.4), sharex="col")
    table = {}  # (mesh, F, B) -> row: each measured point once
    meshes = distinct(w, "mesh")
    Bs_all = distinct(w, "bary_bits")
    handles = []

    def add_rows(pts):
        for r in pts:
            table[(mesh_name(r["mesh"]), r["coord_frac_bits"], r["bary_bits"])] = [
                mesh_name(r["mesh"]), r["coord_int_bits"], r["coord_frac_bits"], r["bary_bits"],
                1 + r["coord_int_bits"] + r["coord_frac_bits"], r["tess_factor"],
                fmt(r["error.position_max"]), fmt(r["error.position_rms"]),
                fmt(r["error.normal_angle_max"]), fmt(r["error.normal_angle_rms"]), r["cpg_cycles_per_triangle"]]

    for m_i, mesh in enumerate(meshes):
        color = f"C{m_i}"
        handles.append(Line2D([], [], color=color, marker="o", ms=3, label=mesh_name(mesh)))
        wm = [r for r in w if r["mesh"] == mesh and r["normals"] == "quadratic"]
        info = mesh_info(mesh)
        # Left: coordinate fraction bits F, solid at the largest B, dashed at the others.
        for B in distinct(wm, "bary_bits"):
            pts = sorted((r for r in wm if r["bary_bits"] == B), key=lambda r: r["coord_frac_bits"])
            if len(pts) < 3:
                continue
            F = [r["coord_frac_bits"] for r in pts]
            ls = "-" if B == max(Bs_all) else "--"
            axes[0][0].plot(F, [r["error.position_max"] for r in pts], marker="o", ms=3, color=color, ls=ls)
            axes[1][0].plot(F, [r["error.normal_angle_max"] for r in pts], marker="o", ms=3, color=color, ls=ls)
            if info and B == max(Bs_all):
                axes[0][0].plot(F, [arithmetic_bound(f, pts[0]["coord_int_bits"], info) for f in F], color=color, lw=0.8, ls=":")
            add_rows(pts)
        # Right: barycentric bits B at the largest F.
        Fmax = max(distinct(wm, "coord_frac_bits"))
        pts = sorted((r for r in wm if r["coord_frac_bits"] == Fmax), key=lambda r: r["bary_bits"])
        if len(pts) >= 3:
            Bs = [r["bary_bits"] for r in pts]
            axes[0][1].plot(Bs, [r["error.position_max"] for r in pts], "o-", ms=3, color=color)
            axes[0][1].plot(Bs, [r["error.position_rms"] for r in pts], "-", lw=0.8, alpha=0.5, color=color)
            axes[1][1].plot(Bs, [r["error.normal_angle_max"] for r in pts], "o-", ms=3, color=color)
            axes[1][1].plot(Bs, [r["error.normal_angle_rms"] for r in pts], "-", lw=0.8, alpha=0.5, color=color)
            add_rows(pts)
            axes[0][1].set_title(f"barycentric bits B (F = {Fmax}); thin: RMS", fontsize=8)
    f_sweep_bs = [B for B in Bs_all if len({r["coord_frac_bits"] for r in w if r["bary_bits"] == B}) >= 3]
    handles += [Line2D([], [], color="0.3", ls="-", label=f"max, B = {max(Bs_all)}")]
    handles += [Line2D([], [], color="0.3", ls="--", label=f"max, B = {B}") for B in f_sweep_bs if B != max(Bs_all)]
    handles += [Line2D([], [], color="0.3", ls=":", lw=0.8,
                       label="arithmetic bound (number-formats §5.1;\nno input or weight quantization)")]
    axes[0][0].set_title("coordinate fraction bits F (I = 3, W = 4 + F)", fontsize=8)
    axes[0][0].set_ylabel("position error / bbox diagonal")
    axes[1][0].set_ylabel("normal angle error (rad)")
    axes[1][0].set_xlabel("F")
    axes[1][1].set_xlabel("B")
    for ax in axes.flat:
        ax.set_yscale("log")
    axes[0][0].legend(handles=handles, fontsize=6)
    fig.suptitle(f"Fixed-point error of the unit against the float64 reference, worst output vertex "
                 f"({workload(w, 'tess_factor', 'normals')}; tessim sim -o vs tessim tessellate)", fontsize=8)
    out.save(fig, "error_vs_width")
    table = [table[k] for k in sorted(table)]
    out.table("Fixed-point error against the float64 reference",
              ["mesh", "I", "F", "B", "W", "L", "position max", "position RMS", "normal angle max (rad)",
               "normal angle RMS (rad)", "C (CPG cycles)"], table,
              note="Positions relative to the input mesh's bounding-box diagonal; normals as angles. "
                   "Every output vertex of the mesh is compared.")
    wn = [r for r in in_grid(rows, "widths_normals") if r.get("error.position_max") is not None]
    if wn:
        out.table("Fixed-point error by normal mode (worst vertex; positions / diagonal, normals in rad)",
                  ["mesh", "normals", "F", "B", "position max", "normal angle max", "normal angle RMS"],
                  [[mesh_name(r["mesh"]), r["normals"], r["coord_frac_bits"], r["bary_bits"],
                    fmt(r["error.position_max"]), fmt(r["error.normal_angle_max"]), fmt(r["error.normal_angle_rms"])]
                   for r in sorted(wn, key=lambda r: (mesh_name(r["mesh"]), r["normals"], r["coord_frac_bits"]))])


# Bus formats of docs/results/load-balancing.md §9 (after Boubekeur & Schlick 2005, §5): the host
# sends float32 positions and normals and 32-bit indices.
FLOAT_VERTEX_BYTES = 24  # position + normal, 6 x float32
INDEX_BYTES = 4


def item_bits(item, r):
    """Bits of one item of the unit's interfaces (`tessim schema`, interface.items: "triangle" in,
    "vertex" out) in row r's configuration: terms coef * product of variables."""
    alpha_bits = r.get("alpha_bits") or 0
    values = {"W": 1 + r["coord_int_bits"] + r["coord_frac_bits"], "bary_bits": r["bary_bits"],
              "int_blocks": r["int_blocks"], "cpg_tags": r.get("cpg_tags") or 0, "alpha_bits": alpha_bits,
              "takes_alpha": 1 if alpha_bits > 0 else 0}
    return sum(t["coef"] * math.prod(values[v] for v in t["of"]) for t in item["terms"])


def bus_traffic(rows, out, topology, items):
    t = in_grid(rows, "tess_factor")
    if not t:
        return out.skip("bus traffic", "no rows of grid 'tess_factor'")
    by_l = {}
    for r in t:
        by_l.setdefault(r["tess_factor"], r)
    mesh = next(iter(by_l.values()))["mesh"]
    topo = topology(mesh)
    if topo is None:
        return out.skip("bus traffic", f"no topology of {mesh}")
    V, E, T = topo["vertices"], topo["edges"], topo["triangles"]
    coarse = V * FLOAT_VERTEX_BYTES + T * 3 * INDEX_BYTES
    table = []
    for L, r in sorted(by_l.items()):
        if r["triangles_in"] != T:
            continue
        # The unit's output is watertight (shared-edge vertices bit-identical), so the host-side
        # equivalent is the welded mesh: coarse vertices, L - 1 points per edge, the interior points.
        welded = V + E * (L - 1) + T * (L - 1) * (L - 2) // 2
        tess = welded * FLOAT_VERTEX_BYTES + T * L * L * 3 * INDEX_BYTES
        unit_in = T * item_bits(items["triangle"], r) / 8
        unit_out = r["vertices_out"] * item_bits(items["vertex"], r) / 8
        table.append([L, T * L * L, welded, r["vertices_out"], fmt_kb(coarse / 1e3), fmt_kb(tess / 1e3),
                      fmt_kb(tess / coarse) if tess / coarse >= 1000 else fmt(tess / coarse, 3),
                      fmt_kb((tess - coarse) / 1e3), fmt_kb(unit_in / 1e3),
                      fmt_kb(unit_out / 1e3)])
    out.table(f"Bus traffic saved by tessellating in the unit ({mesh_name(mesh)}: {V} vertices, {E} edges, "
              f"{T} triangles)",
              ["L", "triangles out", "welded vertices out", "vertices emitted by the unit",
               "coarse mesh kB", "tessellated mesh kB", "tessellated / coarse", "kB saved per pass",
               "unit input stream kB", "unit output stream kB"], table,
              note="Per pass over the mesh. Host-bus formats: float32 position + normal per vertex "
                   f"({FLOAT_VERTEX_BYTES} B), three 32-bit indices per triangle. Without the unit the host sends "
                   "the tessellated mesh, welded (V + E(L−1) + T(L−1)(L−2)/2 vertices, T·L² triangles); with it, "
                   "the coarse mesh. The last two columns are the unit's own interfaces "
                   "(docs/microarchitecture.md §3; widths from `tessim schema`, interface.items): per triangle in "
                   "18 W-bit coordinates, the pattern descriptor (L, pattern, four D3D11 factors) and the id, "
                   f"{items['triangle']['width']} bits; per vertex out 6 W-bit coordinates, (u, v), (j, k, L), "
                   f"the index in the patch, id, last, flags, {items['vertex']['width']} bits — each patch emits "
                   "its shared-edge vertices again, so the unit's output count is T(L+1)(L+2)/2.")
