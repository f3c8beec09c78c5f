#!/usr/bin/env python3
"""The bad-input campaign (docs/verification.md, Bad-input campaign).

Runs `tessim` on hundreds of inputs that must be refused — malformed and hostile mesh files,
configs, statistics, images, factor and camera strings, option values, output targets — across
every subcommand, and checks the contract of docs/architecture.md (Bad input) for each run:

  * exit status 2,
  * stderr begins with "tessim: error: ", holds no sanitizer or library report, no raw control
    byte, and is at most MAX_MESSAGE bytes (hostile values are escaped and truncated),
  * the run's working directory holds afterwards exactly what it held before (nothing written,
    no temporary left behind),
  * the run ends within the time limit (no unbounded read, no blocked open).

Run it against the sanitizer build for the full check (ASan/UBSan/LSan reports fail a case):

    cmake --preset sanitize && cmake --build --preset sanitize --target tessim
    /usr/bin/python3 scripts/bad_input_campaign.py --tessim build-sanitize/bin/tessim

ctest runs it against the release build (test `bad_input_campaign`). Exit status 0 only when
every case held; `--json OUT` writes one record per case.
"""
from __future__ import annotations

import argparse
import concurrent.futures
import json
import os
import shutil
import struct
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path

CUBE = Path("/usr/share/assimp/models/OFF/Cube.off")
MAX_MESSAGE = 4096  # bytes of stderr a refused run may print
SANITIZER_MARKS = ("AddressSanitizer", "LeakSanitizer", "UndefinedBehaviorSanitizer", "runtime error:",
                   "Segmentation fault", "terminate called", "[json.exception")


@dataclass
class Case:
    group: str
    args: list[str]          # {data}/{work} are replaced by the fixture and working directories
    setup: list[str] = field(default_factory=list)  # names created in {work} before the run
    timeout: float = 60.0
    full_fs: int | None = None  # {work} is a small tmpfs with this many KiB left free (root only)
    full_stdout: bool = False   # standard output is /dev/full (every write fails with ENOSPC)


# ---------------------------------------------------------------------------------------------
# Fixtures: bad files, written once into the data directory.

TRI_OFF = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"
TRI_OBJ = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"


def ply_ascii(vertex_props: list[str], vertices: list[str], faces: list[str], extra_header: str = "",
              face_count: int | None = None, vertex_count: int | None = None) -> str:
    header = ["ply", "format ascii 1.0", f"element vertex {len(vertices) if vertex_count is None else vertex_count}"]
    header += [f"property float {p}" for p in vertex_props]
    header += [f"element face {len(faces) if face_count is None else face_count}", "property list uchar int vertex_indices"]
    if extra_header:
        header.append(extra_header)
    header.append("end_header")
    return "\n".join(header + vertices + faces) + "\n"


def tagged_ply(rows: list[str]) -> str:
    props = ["x", "y", "z", "dx", "dy", "dz", "sigma", "theta", "beta"]
    return ply_ascii(props, rows, ["3 0 1 2"])


def binary_ply(count_override: int | None = None, truncate: int = 0) -> bytes:
    verts = [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)]
    n = len(verts) if count_override is None else count_override
    head = ("ply\nformat binary_little_endian 1.0\n"
            f"element vertex {n}\nproperty float x\nproperty float y\nproperty float z\n"
            "element face 1\nproperty list uchar int vertex_indices\nend_header\n").encode()
    body = b"".join(struct.pack("<3f", *v) for v in verts) + struct.pack("<B3i", 3, 0, 1, 2)
    data = head + body
    return data[:len(data) - truncate] if truncate else data


def mesh_fixtures() -> dict[str, bytes]:
    nan_row = "nan 0 0"
    m: dict[str, bytes] = {}
    # OFF
    m["empty.off"] = b""
    m["header_only.off"] = b"OFF\n"
    m["bad_counts.off"] = b"OFF\n3 x 0\n"
    m["truncated.off"] = b"OFF\n3 1 0\n0 0 0\n1 0 0\n"
    m["index_range.off"] = TRI_OFF.replace("3 0 1 2", "3 0 1 7").encode()
    m["negative_index.off"] = TRI_OFF.replace("3 0 1 2", "3 0 -1 2").encode()
    m["nan.off"] = TRI_OFF.replace("1 0 0\n", "nan 0 0\n").encode()
    m["inf.off"] = TRI_OFF.replace("1 0 0\n", "inf 0 0\n").encode()
    m["huge_count.off"] = b"OFF\n4000000000 1 0\n0 0 0\n"
    m["control_byte.off"] = TRI_OFF.replace("1 0 0\n", "1 \x10 0\n").encode()
    m["no_faces.off"] = b"OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n"
    m["word.off"] = TRI_OFF.replace("1 0 0\n", "1 zero 0\n").encode()
    m["far_away.off"] = b"OFF\n3 1 0\n1e9 0 0\n1000000000.001 0 0\n1e9 0.001 0\n3 0 1 2\n"
    m["huge_value.off"] = TRI_OFF.replace("1 0 0\n", "1e400 0 0\n").encode()
    # OBJ
    m["index_range.obj"] = TRI_OBJ.replace("f 1 2 3", "f 1 2 9").encode()
    m["zero_index.obj"] = TRI_OBJ.replace("f 1 2 3", "f 0 1 2").encode()
    m["nan.obj"] = TRI_OBJ.replace("v 1 0 0", "v nan 0 0").encode()
    m["no_faces.obj"] = b"v 0 0 0\nv 1 0 0\n"
    m["garbage.obj"] = bytes(range(256)) * 8
    # PLY, ASCII
    good = ["0 0 0", "1 0 0", "0 1 0"]
    m["bad_magic.ply"] = b"plx\n"
    m["no_end_header.ply"] = b"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
    m["bad_format.ply"] = ply_ascii(["x", "y", "z"], good, ["3 0 1 2"]).replace("ascii 1.0", "ascii 9.9").encode()
    m["truncated_vertices.ply"] = ply_ascii(["x", "y", "z"], good[:2], [], vertex_count=3, face_count=0).encode()
    m["truncated_faces.ply"] = ply_ascii(["x", "y", "z"], good, [], face_count=2).encode()
    m["index_range.ply"] = ply_ascii(["x", "y", "z"], good, ["3 0 1 5"]).encode()
    m["nan.ply"] = ply_ascii(["x", "y", "z"], [nan_row] + good[1:], ["3 0 1 2"]).encode()
    m["duplicate_x.ply"] = ply_ascii(["x", "x", "y", "z"], ["0 5 0 0", "1 5 0 0", "0 5 1 0"], ["3 0 1 2"]).encode()
    m["duplicate_element.ply"] = (ply_ascii(["x", "y", "z"], good, ["3 0 1 2"])
                                  .replace("end_header", "element vertex 0\nend_header")).encode()
    m["unknown_type.ply"] = ply_ascii(["x", "y", "z"], good, ["3 0 1 2"]).replace("property float z", "property quad z").encode()
    m["huge_count.ply"] = ply_ascii(["x", "y", "z"], good, ["3 0 1 2"], vertex_count=4000000000).encode()
    m["word_value.ply"] = ply_ascii(["x", "y", "z"], ["0 zero 0"] + good[1:], ["3 0 1 2"]).encode()
    m["control_byte.ply"] = ply_ascii(["x", "y", "z"], ["0 \x10 0"] + good[1:], ["3 0 1 2"]).encode()
    # PLY, binary
    m["binary_truncated.ply"] = binary_ply(truncate=5)
    m["binary_count.ply"] = binary_ply(count_override=1000)
    m["binary_garbage.ply"] = binary_ply()[:60] + b"\xff" * 3
    # Scalar tags out of range or breaking the format's rules
    base = ["0 0 0", "1 0 0", "0 1 0"]
    tag = lambda xyz, t: f"{xyz} {t}"  # noqa: E731
    m["tag_beta.ply"] = tagged_ply([tag(base[0], "0 0 1 1 0 2"), tag(base[1], "0 0 0 0 0 0"), tag(base[2], "0 0 0 0 0 0")]).encode()
    m["tag_negative_sigma.ply"] = tagged_ply([tag(base[0], "0 0 1 -1 0 0"), tag(base[1], "0 0 0 0 0 0"), tag(base[2], "0 0 0 0 0 0")]).encode()
    m["tag_theta.ply"] = tagged_ply([tag(base[0], "0 0 0 0 7 0"), tag(base[1], "0 0 0 0 0 0"), tag(base[2], "0 0 0 0 0 0")]).encode()
    m["tag_nan.ply"] = tagged_ply([tag(base[0], "nan 0 1 1 0 0"), tag(base[1], "0 0 0 0 0 0"), tag(base[2], "0 0 0 0 0 0")]).encode()
    m["tag_three_per_triangle.ply"] = tagged_ply([tag(b, "0 0 1 1 0 0") for b in base]).encode()
    m["tag_duplicate_sigma.ply"] = ply_ascii(["x", "y", "z", "sigma", "sigma"], [b + " 1 0" for b in base], ["3 0 1 2"]).encode()
    # STL
    m["truncated.stl"] = b"solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n"
    m["binary_count.stl"] = b"\0" * 80 + struct.pack("<I", 1000) + b"\0" * 50
    # Not meshes at all
    m["text.ply"] = b"hello\n"
    m["unknown.xyz"] = b"1 2 3\n"
    m["nul_bytes.off"] = b"\0" * 4096
    return m


def config_fixtures() -> dict[str, bytes]:
    c: dict[str, bytes] = {}
    c["empty.json"] = b""
    c["not_json.json"] = b"int_blocks: 2\n"
    c["array.json"] = b"[1, 2]\n"
    c["truncated.json"] = b'{"int_blocks": 2'
    c["unknown_key.json"] = b'{"int_blockz": 2}'
    c["wrong_type.json"] = b'{"int_blocks": "two"}'
    c["negative.json"] = b'{"int_blocks": -1}'
    c["zero.json"] = b'{"int_blocks": 0}'
    c["huge.json"] = b'{"int_blocks": 1e300}'
    c["fraction.json"] = b'{"int_blocks": 2.5}'
    c["nan_text.json"] = b'{"int_blocks": NaN}'
    c["duplicate_key.json"] = b'{"int_blocks": 2, "int_blocks": 3}'
    c["trailing.json"] = b'{"int_blocks": 2} x'
    c["two_documents.json"] = b'{"int_blocks": 2}\n{"int_blocks": 3}\n'
    c["bad_enum.json"] = b'{"normals": "cubic"}'
    c["nested.json"] = b'{"int_blocks": {"a": 1}}'
    c["null.json"] = b'{"int_blocks": null}'
    c["control_key.json"] = b'{"int\\u0010blocks": 2}'
    c["long_key.json"] = b'{"' + b"k" * 200000 + b'": 1}'
    c["deep.json"] = b"[" * 100000 + b"]" * 100000
    c["latin1.json"] = b'{"normals": "\xe9"}'
    c["bool.json"] = b'{"int_blocks": true}'
    c["schema_version.json"] = b'{"schema_version": "x"}'
    return c


def stats_fixtures(valid_stats: bytes | None) -> dict[str, bytes]:
    s: dict[str, bytes] = {}
    s["empty.json"] = b""
    s["object.json"] = b"{}"
    s["array.json"] = b"[]"
    s["truncated.json"] = b'{"schema_version": 1'
    s["wrong_tool.json"] = b'{"tool": 5, "schema_version": 1}'
    s["wrong_version_type.json"] = b'{"tool": "tessim", "schema_version": "one"}'
    s["future_version.json"] = b'{"tool": "tessim", "schema_version": 99999}'
    s["other_tool.json"] = b'{"tool": "other", "schema_version": 1}'
    s["duplicate.json"] = b'{"tool": "tessim", "tool": "tessim"}'
    s["trailing.json"] = b'{"tool": "tessim"} trailing'
    s["deep.json"] = b"[" * 100000 + b"]" * 100000
    s["binary.json"] = bytes(range(256))
    if valid_stats is not None:
        doc = json.loads(valid_stats)
        for key in [k for k in doc if k != "cpg_tag_cycles"][:6]:  # top-level sections removed in turn
            broken = dict(doc)
            del broken[key]
            s[f"without_{key}.json"] = json.dumps(broken).encode()
        s["truncated_real.json"] = valid_stats[: len(valid_stats) // 2]
        s["real_trailing.json"] = valid_stats + b"\n{}"
    return s


def image_fixtures() -> dict[str, bytes]:
    return {
        "empty.png": b"",
        "text.png": b"not an image\n",
        "truncated.png": b"\x89PNG\r\n\x1a\n\0\0\0\rIHDR",
        "huge_dims.png": b"\x89PNG\r\n\x1a\n\0\0\0\rIHDR" + struct.pack(">II", 0x7fffffff, 0x7fffffff) + b"\x08\x02\0\0\0",
    }


# ---------------------------------------------------------------------------------------------
# Cases

MESH_COMMANDS = [
    ["info"],
    ["tessellate", "-L", "2", "-o", "{work}/out.ply"],
    ["render", "-L", "2", "--size", "64x64", "-o", "{work}/out.png"],
    ["sim", "-L", "2", "--stats", "{work}/s.json", "-o", "{work}/out.ply"],
    ["cosim", "-L", "2", "--int-blocks", "2"],
    ["stpn-import", "-o", "{work}/out.ply"],
]

# Values no integer option takes, then what each option refuses beyond them.
BAD_INTEGERS = ["abc", "1.5", "1e999", "nan", "99999999999999999999", "2,", "+-2", "--", "1 2"]
BAD_REALS = ["abc", "nan", "inf", "-inf", "1e999", "1,2", "0x", "--", "1 2"]
BAD_ENUMS = ["bogus", "QUADRATIC ", "integer,pow2", "\x10", "x" * 100000]


def option_cases(mesh: str) -> list[Case]:
    png = ["-o", "{work}/o.png"]
    integer_options = [  # (command prefix, option, out-of-range values)
        (["tessellate", mesh, "-o", "{work}/o.ply"], "-L", ["0", "-1", "65"]),
        (["render", mesh] + png, "-L", ["0", "-1", "65"]),
        (["sim", mesh], "-L", ["0", "-1", "65"]),
        (["sim", mesh], "--int-blocks", ["0", "-1"]),
        (["sim", mesh], "--int-latency", ["0", "-1"]),
        (["sim", mesh], "--gpe-cycles", ["0", "-1"]),
        (["sim", mesh], "--chunks", ["0", "-1"]),
        (["sim", mesh, "--units", "2"], "--threads", ["0", "-1", "65"]),
        (["cosim", mesh], "--int-blocks", ["0", "-1", "999"]),
        (["cosim", mesh], "--random", ["0", "-1"]),
        (["cosim", mesh], "--seed", ["-1"]),
        (["render", mesh] + png, "--size", ["0x0", "-1x5", "5", "100000x100000", "64x"]),
        (["schema"], "--indent", ["50000", "1100", "-2"]),
        (["sim", mesh, "--trace", "{work}/t.json"], "--trace-window", ["5:2", "a:b", ":", "-1:3"]),
        (["cosim", mesh], "--reset-at", ["-1", "1,,2", ","]),
    ]
    cases: list[Case] = []
    for prefix, option, out_of_range in integer_options:
        for value in BAD_INTEGERS + out_of_range:
            cases.append(Case("option-integer", prefix + [option, value]))
    real_options = [
        (["sim", mesh], "--gpe-stall-prob", ["-0.1", "1.5"]),
        (["cosim", mesh], "--gpe-stall-prob", ["-0.1", "1.5"]),
        (["render", mesh] + png, "--azimuth", []),
        (["render", mesh] + png, "--elevation", ["91", "-91"]),
        (["render", mesh, "--color", "error-position"] + png, "--color-max", ["-1"]),
        (["stpn-import", mesh, "-o", "{work}/o.ply"], "--sigma", ["-1", "1001"]),
        (["stpn-import", mesh, "-o", "{work}/o.ply"], "--crease-angle", ["-5", "181"]),
    ]
    for prefix, option, out_of_range in real_options:
        for value in BAD_REALS + out_of_range:
            cases.append(Case("option-real", prefix + [option, value]))
    enum_options = [
        (["tessellate", mesh, "-o", "{work}/o.ply"], "--normals"),
        (["sim", mesh], "--normals"),
        (["sim", mesh], "--cpg-mapping"),
        (["render", mesh] + png, "--compare"),
        (["render", mesh] + png, "--color"),
        (["tessellate", mesh, "-o", "{work}/o.ply"], "--partitioning"),
        (["pattern", "--outer", "2,2,2", "--inner", "2"], "--partitioning"),
        (["pattern", "--outer", "2,2,2", "--inner", "2", "--partitioning", "integer"], "--winding"),
        (["cosim", "--random", "3"], "--partitioning"),
    ]
    for prefix, option in enum_options:
        for value in BAD_ENUMS:
            cases.append(Case("option-enum", prefix + [option, value]))
    return cases


# nan,1,1 / -1,1,1 / 0,0,0 cull every patch of the mesh: an empty run is refused everywhere.
FACTOR_TEXTS = ["1,2", "1,2,3,4", "a,b,c", "nan,1,1", "1,,1", "-1,1,1", "0,0,0", "1;2;3", ",,", "1,2,", "x" * 100000]
SILHOUETTE_TEXTS = ["", "eye", "eye=1,2", "eye=a,b,c", "eye=nan,0,5", "eye=inf,0,5", "eye=0,0,5,beta=0",
                    "eye=0,0,5,beta=-1", "eye=0,0,5,beta=nan", "eye=0,0,5,beta=inf", "eye=0,0,5,beta=", "camera",
                    "sideways", "eye=0,0,5,beta=1,2"]
CAMERA_TEXTS = ["", "eye=0,0,0,target=0,0,0,fov=60",
                "eye=0,0,5,target=0,0,0,fov=0", "eye=0,0,5,target=0,0,0,fov=180", "eye=a,b,c,target=0,0,0,fov=60",
                "eye=0,0,5,target=0,0,0,fov=60,zoom=2", "eye=0,0,5,eye=0,0,6,target=0,0,0,fov=60",
                "eye=0,0,5,target=0,0,0,fov=nan", "eye=nan,0,5,target=0,0,0,fov=60", "=,=", "eye"]


def factor_cases(mesh: str) -> list[Case]:
    cases: list[Case] = []
    for cmd in (["tessellate", mesh, "-o", "{work}/o.ply"], ["sim", mesh, "-o", "{work}/o.ply"],
                ["pattern", "--partitioning", "integer", "-o", "{work}/p.svg"]):
        for text in FACTOR_TEXTS:
            if cmd[0] == "pattern" and text in ("nan,1,1", "-1,1,1", "0,0,0"):
                continue  # the pattern of one culled patch is an answer, not an empty run
            extra = ["--partitioning", "integer"] if cmd[0] != "pattern" else []
            inner = ["--inner", "2"] if cmd[0] == "pattern" else []
            cases.append(Case("factors", cmd + extra + ["--outer", text] + inner))
        for inner in ["x", "1,2", "--"]:
            extra = ["--partitioning", "integer"] if cmd[0] != "pattern" else []
            cases.append(Case("factors", cmd + extra + ["--outer", "2,2,2", "--inner", inner]))
    for cmd in (["tessellate", mesh, "-o", "{work}/o.ply"], ["sim", mesh], ["render", mesh, "-o", "{work}/o.png"],
                ["cosim", mesh, "--int-blocks", "2"]):
        for text in CAMERA_TEXTS:
            cases.append(Case("camera", cmd + ["--adaptive", "screen", "--partitioning", "integer", "--camera", text]))
        cases.append(Case("factors", cmd + ["--adaptive", "sideways", "--partitioning", "integer"]))
        cases.append(Case("factors", cmd + ["--viewport", "640x480"]))
        cases.append(Case("factors", cmd + ["--pixels-per-segment", "8"]))
        cases.append(Case("factors", cmd + ["--partitioning", "integer", "--outer", "0,0,0"]))
    # Silhouettes: every command that takes --silhouette refuses bad eyes and widths.
    for cmd in (["tessellate", mesh, "-o", "{work}/o.ply"], ["render", mesh, "-o", "{work}/o.png"],
                ["info", mesh], ["sim", mesh, "-o", "{work}/o.ply"], ["cosim", mesh, "--int-blocks", "2"]):
        for text in SILHOUETTE_TEXTS:
            cases.append(Case("silhouette", cmd + ["--silhouette", text]))
    # The unit blends smooth edge ends only: a feature end is refused, naming its vertex; the blend
    # needs a build that takes alpha, and a mesh (--random draws alpha itself).
    for cmd in (["sim", "{data}/feature_end.ply", "-o", "{work}/o.ply"],
                ["sim", "{data}/feature_end.ply", "-o", "{work}/o.ply", "--alpha-bits", "4"]):
        cases.append(Case("silhouette", cmd + ["--silhouette", "eye=0,0,5"]))
    cases.append(Case("silhouette", ["cosim", mesh, "--int-blocks", "2", "--silhouette", "eye=0,0,5"]))
    # Displacement (float reference): non-finite, negative or overflowing settings, a kind that
    # does not exist, an amplitude without --displace.
    for cmd in (["tessellate", mesh, "-o", "{work}/o.ply"], ["render", mesh, "-o", "{work}/o.png"]):
        for extra in (["--displace", "sine", "--amplitude", "nan", "--frequency", "1"],
                      ["--displace", "sine", "--amplitude", "1", "--frequency", "-1"],
                      ["--displace", "sine", "--amplitude", "inf", "--frequency", "1"],
                      ["--displace", "wobble", "--amplitude", "1", "--frequency", "1"],
                      ["--amplitude", "1"],
                      ["--displace", "sine", "--amplitude", "1e300", "--frequency", "1e300"],
                      ["--displace", "noise", "--amplitude", "1", "--frequency", "-1"]):
            cases.append(Case("displace", cmd + extra))
    # The Nyquist rule (docs/patterns.md §9): without a displacement to sample, with a camera it
    # does not take (or without the one screen+nyquist needs), --samples-per-wavelength without a
    # nyquist rule or below 1 or NaN.
    sine = ["--displace", "sine", "--amplitude", "0.02", "--frequency", "60"]
    for cmd in (["tessellate", mesh, "-o", "{work}/o.ply"], ["render", mesh, "-o", "{work}/o.png"],
                ["sim", mesh, "-o", "{work}/o.ply"]):
        for extra in (["--adaptive", "nyquist"],
                      ["--adaptive", "nyquist", "--camera", "eye=0,0,3"] + sine,
                      ["--samples-per-wavelength", "8"] + sine,
                      ["--adaptive", "screen", "--samples-per-wavelength", "8", "--camera", "eye=0,0,3"] + sine,
                      ["--adaptive", "nyquist", "--samples-per-wavelength", "0.5"] + sine,
                      ["--adaptive", "nyquist", "--samples-per-wavelength", "nan"] + sine,
                      ["--adaptive", "screen+nyquist"] + sine):
            cases.append(Case("displace", cmd + extra))
    cases.append(Case("silhouette", ["cosim", "--random", "4", "--variant", "n3_lat3", "--silhouette", "eye=0,0,5"]))
    return cases


def output_cases(mesh: str) -> list[Case]:
    cases: list[Case] = []
    writers = [
        (["tessellate", mesh, "-L", "2"], "-o"),
        (["render", mesh, "-L", "2", "--size", "64x64"], "-o"),
        (["sim", mesh, "-L", "2"], "-o"),
        (["sim", mesh, "-L", "2"], "--stats"),
        (["sim", mesh, "-L", "2"], "--trace"),
        (["pattern", "--outer", "2,2,2", "--inner", "2", "--partitioning", "integer"], "-o"),
        (["stpn-import", mesh], "-o"),
        (["cosim", mesh, "-L", "1", "--int-blocks", "2"], "--wave"),
    ]
    for prefix, option in writers:
        suffix = {"--stats": ".json", "--trace": ".json", "--wave": ".fst"}.get(option, ".ply")
        if prefix[0] in ("render", "pattern"):
            suffix = ".png" if prefix[0] == "render" else ".svg"
        cases.append(Case("output", prefix + [option, "{work}/a_directory"], setup=["a_directory/"]))
        cases.append(Case("output", prefix + [option, "{work}/missing/dir/out" + suffix]))
        if option in ("-o", "--wave"):
            cases.append(Case("output", prefix + [option, "{work}/out.unknown_extension"]))
        cases.append(Case("output", prefix + [option, "{work}/a_file/out" + suffix], setup=["a_file"]))
    # Two outputs on one path
    cases.append(Case("output", ["sim", mesh, "-L", "2", "-o", "{work}/x.ply", "--stats", "{work}/x.ply"]))
    cases.append(Case("output", ["sim", mesh, "-L", "2", "--stats", "{work}/x.json", "--trace", "{work}/./x.json"]))
    cases.append(Case("output", ["sim", mesh, "-L", "2", "--stats", "-", "--trace", "-"]))
    # A failing later stage must not leave the earlier outputs
    cases.append(Case("output", ["sim", mesh, "-L", "2", "-o", "{work}/o.ply", "--stats", "{work}/missing/s.json"]))
    return cases


def ge_cases(mesh: str) -> list[Case]:
    """The geometry engine as a shader machine (docs/microarchitecture.md §12): evaluation gpe has
    no TE to trace, host control points need evaluation gpe, ALU lanes and special-function cost
    out of range, and the RTL has no evaluation gpe."""
    return [
        Case("ge", ["sim", mesh, "--evaluation", "gpe", "--trace", "{work}/t.json", "-o", "{work}/o.ply"]),
        Case("ge", ["sim", mesh, "--cpg-mapping", "host", "-o", "{work}/o.ply"]),
        Case("ge", ["sim", mesh, "--ge-alu-lanes", "0", "-o", "{work}/o.ply"]),
        Case("ge", ["sim", mesh, "--ge-sfu-cost", "65", "-o", "{work}/o.ply"]),
        Case("ge", ["cosim", mesh, "--evaluation", "gpe"]),
    ]


def system_cases(mesh: str) -> list[Case]:
    """A system of units (docs/microarchitecture.md §13): counts out of range, an unknown policy, a
    system with the GE-mapped CPG or evaluation on the GE, a trace of a system, and cosim of one."""
    return [
        Case("system", ["sim", mesh, "--units", "17", "-o", "{work}/o.ply"]),
        Case("system", ["sim", mesh, "--units", "2", "--ge-ports", "0", "-o", "{work}/o.ply"]),
        Case("system", ["sim", mesh, "--units", "2", "--reorder-slots", "1", "-o", "{work}/o.ply"]),
        Case("system", ["sim", mesh, "--units", "2", "--distribution", "random", "-o", "{work}/o.ply"]),
        Case("system", ["sim", mesh, "--units", "2", "--dispatch-batch", "65", "-o", "{work}/o.ply"]),
        Case("system", ["sim", mesh, "--units", "2", "--cpg-mapping", "gpe", "-o", "{work}/o.ply"]),
        Case("system", ["sim", mesh, "--units", "2", "--evaluation", "gpe", "-o", "{work}/o.ply"]),
        Case("system", ["sim", mesh, "--units", "2", "--trace", "{work}/t.json", "-o", "{work}/o.ply"]),
        Case("system", ["cosim", mesh, "--units", "2"]),
    ]


FULL_FS_SIZE = "256k"  # the tmpfs of a full-file-system case


def full_fs_cases(mesh: str) -> list[Case]:
    """Every writer on a full file system (docs/architecture.md, Bad input): with no space left,
    and with some left where the output is larger (a part of it would fit): exit 2, nothing left
    but the file that filled the disk. The waveform cases cover the FST writer's unchecked writes
    (a truncated recording) and its mapped files (SIGBUS)."""
    cases: list[Case] = []
    small = [
        ["tessellate", mesh, "-L", "32", "-o", "{work}/o.ply"],
        ["tessellate", mesh, "-L", "32", "--weld", "-o", "{work}/o.obj"],
        ["render", mesh, "-L", "2", "--size", "64x64", "-o", "{work}/o.png"],
        ["sim", mesh, "-L", "32", "-o", "{work}/o.ply"],
        ["sim", mesh, "-L", "32", "--stats", "{work}/s.json"],
        ["sim", mesh, "-L", "32", "--trace", "{work}/t.json"],
        ["sim", mesh, "-L", "8", "--units", "2", "--stats", "{work}/s.json"],
        ["pattern", "--outer", "3,2,2", "--inner", "2", "--partitioning", "integer", "-o", "{work}/p.svg"],
        ["pattern", "--outer", "3,2,2", "--inner", "2", "--partitioning", "integer", "-o", "{work}/p.png"],
        ["stpn-import", mesh, "-o", "{work}/s.ply"],
        ["report", "{data}/sample.json", "-o", "{work}/r.html"],
        ["power", mesh, "-L", "8", "--json", "{work}/p.json"],
    ]
    large = small[0:1] + small[3:6] + small[10:11]
    waves = [["cosim", mesh, "-L", "8", "--wave-window", "0:4500", "--wave", "{work}/w." + ext] for ext in ("fst", "vcd")]
    for args in small + waves:
        cases.append(Case("full_fs", args, full_fs=0))
    for args in large + waves:
        cases.append(Case("full_fs", args, full_fs=16))
    for args in waves:
        for free in (48, 128):
            cases.append(Case("full_fs", args, full_fs=free))
    return cases


def full_stdout_cases(mesh: str) -> list[Case]:
    """What a command prints to standard output, when it cannot be written (/dev/full): exit 2.
    (A file output written beside a summary that fails stays: it is complete, and the summary is
    checked when the process flushes standard output at its end.)"""
    return [Case("full_stdout", args, full_stdout=True) for args in [
        ["schema"],
        ["info", mesh],
        ["info", mesh, "--json"],
        ["compare", "{data}/sample.json", "{data}/sample.json"],
        ["compare", "{data}/sample.json", "{data}/sample.json", "--csv"],
        ["sim", mesh, "-L", "2"],
        ["sim", mesh, "-L", "2", "--stats", "-"],
        ["sim", mesh, "-L", "2", "-o", "-"],
        ["tessellate", mesh, "-L", "2", "-o", "-"],
        ["pattern", "--outer", "3,2,2", "--inner", "2", "--partitioning", "integer"],
        ["pattern", "--outer", "3,2,2", "--inner", "2", "--partitioning", "integer", "--json"],
        ["power", mesh, "-L", "4"],
        ["cosim", mesh, "-L", "1"],
    ]]


def misc_cases(mesh: str) -> list[Case]:
    cases = [
        Case("cli", ["no-such-command"]),
        # An empty value is a bad value, not "not given".
        Case("cli", ["sim", mesh, "--stats", ""]),
        Case("cli", ["sim", mesh, "-o", ""]),
        Case("cli", ["sim", mesh, "--trace", ""]),
        Case("cli", ["sim", mesh, "--config", ""]),
        Case("cli", ["tessellate", mesh, "-o", ""]),
        Case("cli", ["cosim", mesh, "--wave", ""]),
        Case("cli", ["cosim", mesh, "--coverage", ""]),
        Case("cli", ["report", "{data}/stats/object.json", "-o", ""]),
        Case("cli", ["cosim", "--random", "18446744073709551615"]),
        Case("cli", ["rtlbench", mesh, "--int", "5"]),
        Case("cli", ["info", mesh, "--silhouette", "eye=1e155,1e155,1e155"]),
        Case("cli", ["sim", mesh, "--units", "4", "--chunks", "2", "--stats", "{work}/s.json"]),
        Case("cli", ["sim", "--no-such-option"]),
        Case("cli", ["info"]),
        Case("cli", ["info", "{data}/does_not_exist.ply"]),
        Case("cli", ["info", "{data}"]),
        Case("cli", ["info", "/dev/zero"]),
        Case("cli", ["info", mesh, mesh]),
        Case("cli", ["tessellate", mesh]),
        Case("cli", ["render", mesh]),
        Case("cli", ["pattern"]),
        Case("cli", ["pattern", "--outer", "2,2,2"]),
        Case("cli", ["report"]),
        Case("cli", ["compare", "{data}/stats/object.json"]),
        Case("cli", ["sim", mesh, "--weld"]),
        Case("cli", ["cosim", "--random", "0"]),
        Case("cli", ["cosim", mesh, "--wave-window", "9:3", "--wave", "{work}/w.fst"]),
        Case("cli", ["render", mesh, "--caption", "x", "--no-caption", "-o", "{work}/o.png"]),
        Case("cli", ["sim", mesh, "--no-such-option", "1"]),
        Case("cli", ["info", "--json"]),
    ]
    return cases


# ---------------------------------------------------------------------------------------------
# Running

def write_fixtures(data: Path, stats_sample: bytes | None) -> None:
    for sub, files in (("meshes", mesh_fixtures()), ("configs", config_fixtures()),
                       ("stats", stats_fixtures(stats_sample)), ("images", image_fixtures())):
        (data / sub).mkdir(parents=True, exist_ok=True)
        for name, content in files.items():
            (data / sub / name).write_bytes(content)
    (data / "big.json").write_bytes(b'{"int_blocks": 2' + b" " * (300 << 20) + b"}")
    # A valid mesh with a crease through vertex 0 between the two faces of edge 0-1: with
    # --silhouette a feature end, which the unit's CPG does not blend (sim refuses it, naming vertex 0).
    (data / "feature_end.ply").write_bytes(ply_ascii(
        ["x", "y", "z", "dx", "dy", "dz", "sigma", "theta", "beta"],
        ["0 0 0 0 -1 1 1 0 0", "1 0 0 0 0 0 0 0 0", "0.5 1 0 0 0 0 0 0 0", "0.5 -0.5 1 0 0 0 0 0 0"],
        ["3 0 1 2", "3 1 0 3"]).encode())
    (data / "tagged.ply").write_bytes(tagged_ply(["0 0 0 0 0 1 1 0 0", "1 0 0 0 0 0 0 0 0", "0 1 0 0 0 0 0 0 0"]).encode())
    os.mkfifo(data / "fifo.json")


def build_cases(data: Path, full_fs: bool = True) -> list[Case]:
    mesh = str(CUBE)
    cases: list[Case] = []
    for name in sorted(os.listdir(data / "meshes")):
        for command in MESH_COMMANDS:
            cases.append(Case("mesh", [command[0], "{data}/meshes/" + name] + command[1:]))
    for name in sorted(os.listdir(data / "configs")):
        for command in (["sim", mesh], ["cosim", mesh, "-L", "1"], ["sim", mesh, "--chunks", "2"]):
            cases.append(Case("config", command + ["--config", "{data}/configs/" + name]))
    for special in ("/dev/zero", "{data}/big.json", "{data}/fifo.json", "{data}"):
        cases.append(Case("config", ["sim", mesh, "--config", special], timeout=20))
    for name in sorted(os.listdir(data / "stats")):
        stats = "{data}/stats/" + name
        cases.append(Case("stats", ["report", stats, "-o", "{work}/r.html"]))
        if name.startswith("without_"):
            continue  # compare diffs whatever sections the two files have
        cases.append(Case("stats", ["compare", stats, "{data}/sample.json"]))
        cases.append(Case("stats", ["compare", "{data}/sample.json", stats]))
        cases.append(Case("stats", ["compare", stats, stats, "--csv"]))
    for special in ("/dev/zero", "{data}/fifo.json", "{data}"):
        cases.append(Case("stats", ["report", special, "-o", "{work}/r.html"], timeout=20))
        cases.append(Case("stats", ["compare", special, "{data}/sample.json"], timeout=20))
    for name in sorted(os.listdir(data / "images")):
        cases.append(Case("image", ["report", "{data}/sample.json", "--image", "{data}/images/" + name, "-o", "{work}/r.html"]))
    for special in ("/dev/zero", "{data}/fifo.json", "{data}", "{data}/does_not_exist.png"):
        cases.append(Case("image", ["report", "{data}/sample.json", "--image", special, "-o", "{work}/r.html"], timeout=20))
    cases += option_cases(mesh) + factor_cases(mesh) + output_cases(mesh) + ge_cases(mesh) + system_cases(mesh) + misc_cases(mesh)
    if Path("/dev/full").exists():
        cases += full_stdout_cases(mesh)
    if full_fs:
        cases += full_fs_cases(mesh)
    return cases


def can_mount_tmpfs(where: Path) -> bool:
    """Whether a small tmpfs can be mounted here (root, and a kernel that lets it)."""
    if os.geteuid() != 0 or not shutil.which("mount"):
        return False
    where.mkdir(parents=True, exist_ok=True)
    if subprocess.run(["mount", "-t", "tmpfs", "-o", "size=" + FULL_FS_SIZE, "tmpfs", str(where)],
                      capture_output=True).returncode != 0:
        return False
    subprocess.run(["umount", "-l", str(where)], capture_output=True)
    return True


def fill(work: Path, free_kib: int) -> None:
    """Leaves free_kib KiB free on the file system of `work`: a file `fill` takes the rest."""
    st = os.statvfs(work)
    available = st.f_bavail * st.f_frsize
    with open(work / "fill", "wb") as f:
        f.write(b"\0" * max(0, available - free_kib * 1024))


def snapshot(work: Path) -> list[tuple[str, int]]:
    return sorted((str(p.relative_to(work)), p.lstat().st_size) for p in work.rglob("*"))


def prepare(work: Path, setup: list[str]) -> None:
    work.mkdir(parents=True)
    for item in setup:
        if item.endswith("/"):
            (work / item).mkdir(parents=True)
        else:
            (work / item).write_text("kept\n")


def run_case(tessim: str, data: Path, root: Path, index: int, case: Case) -> dict:
    work = root / f"case{index:04d}"
    mounted = False
    if case.full_fs is not None:
        work.mkdir(parents=True)
        subprocess.run(["mount", "-t", "tmpfs", "-o", "size=" + FULL_FS_SIZE, "tmpfs", str(work)], check=True)
        mounted = True
        for item in case.setup:
            (work / item).write_text("kept\n")
        fill(work, case.full_fs)
    else:
        prepare(work, case.setup)
    before = snapshot(work)
    args = [a.replace("{data}", str(data)).replace("{work}", str(work)) for a in case.args]
    env = dict(os.environ, ASAN_OPTIONS="detect_leaks=1:abort_on_error=0", UBSAN_OPTIONS="print_stacktrace=1")
    started = time.monotonic()
    problems: list[str] = []
    try:
        with open("/dev/full" if case.full_stdout else os.devnull, "wb") as full:
            p = subprocess.run([tessim] + args, cwd=work, stdin=subprocess.DEVNULL,
                               stdout=full if case.full_stdout else subprocess.PIPE, stderr=subprocess.PIPE,
                               timeout=case.timeout, env=env)
        status, out, err = p.returncode, p.stdout or b"", p.stderr
    except subprocess.TimeoutExpired as e:
        status, out, err = None, e.stdout or b"", e.stderr or b""
        problems.append(f"did not end within {case.timeout:g} s")
    seconds = time.monotonic() - started
    text = err.decode("utf-8", "replace")
    if status is not None and status != 2:
        problems.append(f"exit status {status}, not 2")
    if not text.startswith("tessim: error: "):
        problems.append("stderr does not begin with 'tessim: error: '")
    for mark in SANITIZER_MARKS:
        if mark in text:
            problems.append(f"stderr holds '{mark}'")
    if len(err) > MAX_MESSAGE:
        problems.append(f"{len(err)} bytes on stderr (limit {MAX_MESSAGE})")
    if any(b < 0x20 and b not in (0x0A, 0x09) for b in err):
        problems.append("raw control byte on stderr")
    after = snapshot(work)
    if after != before:
        problems.append(f"left behind: {sorted(set(after) - set(before))}")
    if mounted:
        subprocess.run(["umount", "-l", str(work)], check=False)
    shutil.rmtree(work, ignore_errors=True)
    first_line = text.splitlines()[0] if text else ""
    return {"group": case.group, "args": [a[:200] for a in args], "status": status, "seconds": round(seconds, 3),
            "message": first_line[:300], "stdout_bytes": len(out), "problems": problems}


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0], formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--tessim", required=True, help="the tessim binary (a sanitizer build for the full check)")
    ap.add_argument("--jobs", type=int, default=2, help="runs at a time (default 2)")
    ap.add_argument("--json", help="write one record per case to this file")
    ap.add_argument("--min-cases", type=int, default=800, help="fail when fewer cases are generated (default 800)")
    ap.add_argument("--only", help="run only the cases of this group")
    ap.add_argument("--count", action="store_true", help="print the number of cases and exit (runs nothing)")
    a = ap.parse_args()
    for required in (CUBE,):
        if not required.exists():
            print(f"bad_input_campaign: {required} is missing (install assimp-testmodels)", file=sys.stderr)
            return 1
    tessim = os.path.abspath(a.tessim)
    with tempfile.TemporaryDirectory(prefix="tessim-bad-input-") as tmp:
        data, root = Path(tmp) / "data", Path(tmp) / "runs"
        data.mkdir()
        root.mkdir()
        # A valid statistics file, the base of the stats cases.
        sample = data / "sample_stats.json"
        p = subprocess.run([tessim, "sim", str(CUBE), "-L", "2", "--stats", str(sample)], capture_output=True)
        if p.returncode != 0:
            print("bad_input_campaign: the valid run failed:\n" + p.stderr.decode(errors="replace"), file=sys.stderr)
            return 1
        write_fixtures(data, sample.read_bytes())
        shutil.copy(sample, data / "sample.json")
        full_fs = can_mount_tmpfs(Path(tmp) / "mount_check")
        if not full_fs:
            print("bad_input_campaign: full-file-system cases skipped: mounting a small tmpfs needs root",
                  file=sys.stderr)
        cases = build_cases(data, full_fs)
        if a.count:
            print(len(cases))
            return 0
        if a.only:
            cases = [c for c in cases if c.group == a.only]
        elif len(cases) < a.min_cases:
            print(f"bad_input_campaign: only {len(cases)} cases (need {a.min_cases})", file=sys.stderr)
            return 1
        started = time.monotonic()
        with concurrent.futures.ThreadPoolExecutor(max_workers=a.jobs) as pool:
            results = list(pool.map(lambda ic: run_case(tessim, data, root, ic[0], ic[1]), enumerate(cases)))
        elapsed = time.monotonic() - started
    failed = [r for r in results if r["problems"]]
    groups: dict[str, list[int]] = {}
    for r in results:
        g = groups.setdefault(r["group"], [0, 0])
        g[0] += 1
        g[1] += bool(r["problems"])
    for name, (count, bad) in sorted(groups.items()):
        print(f"  {name:16s} {count:4d} runs, {bad:3d} failed")
    for r in failed:
        print("FAIL tessim " + " ".join(repr(x) if (" " in x or not x) else x for x in r["args"]))
        for problem in r["problems"]:
            print(f"     {problem}")
        print(f"     stderr: {r['message']}")
    slowest = max(results, key=lambda r: r["seconds"])
    print(f"bad_input_campaign: {len(results)} runs, {len(failed)} failed, {elapsed:.1f} s "
          f"(slowest {slowest['seconds']:.2f} s: {' '.join(slowest['args'][:4])})")
    if a.json:
        Path(a.json).write_text(json.dumps(results, indent=1) + "\n")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
