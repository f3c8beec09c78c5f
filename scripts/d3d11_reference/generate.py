#!/usr/bin/python3
"""Reference data of the D3D11 triangle-domain pattern from Microsoft's reference tessellator,
as Mesa's draw module runs it on llvmpipe (OpenGL tessellation, transform feedback of
gl_TessCoord, reference.c): per patch the number of triangles and an FNV-1a hash of their
corners' 16.16 (u, v), in order. tests/sim/d3d11_walk_test.cpp checks both implementations of
the pattern against it.

    /usr/bin/python3 scripts/d3d11_reference/generate.py > tests/data/d3d11_reference.txt
"""
import math, os, random, struct, subprocess, sys, tempfile

def bits(x):
    return struct.unpack("<I", struct.pack("<f", x))[0]

def f32(x):
    return struct.unpack("<f", struct.pack("<f", x))[0]

SPACING = {"integer": "equal_spacing", "pow2": "equal_spacing",
           "fractional_odd": "fractional_odd_spacing", "fractional_even": "fractional_even_spacing"}

def pow2_up(x):
    # the hull-shader helper's rounding of pow2 factors, before the fixed-function stage
    if not (x > 0) or math.isinf(x):
        return x
    x = min(64.0, max(1.0, x))
    return float(2 ** math.ceil(math.log2(x)))

def cases(part, rng):
    out = []
    special = [1.0, 1.0 + 2**-16, 1.0 + 2**-17, 2.0, 2.0 + 2**-16, 3.0, 4.0 - 2**-16, 62.5, 63.0, 63.5, 64.0, 65.0]
    for L in range(1, 65):
        out.append((float(L),) * 4)
    for i in range(120):
        f = [rng.uniform(0.5, 66.0) for _ in range(4)]
        if i % 4 == 0:
            f[3] = 1.0
        out.append(tuple(f32(x) for x in f))
    for i in range(120):
        f = []
        for _ in range(4):
            k = rng.randint(1, 64)
            f.append(f32(k + rng.choice([-2**-16, -2**-17, 0.0, 2**-17, 2**-16, 1.5 * 2**-16, -0.001, 0.001, 0.5])))
        out.append(tuple(f))
    for i in range(60):
        out.append(tuple(f32(rng.choice(special)) for _ in range(4)))
    for bad in [0.0, -1.0, float("nan"), float("inf")]:
        out.append((bad, 4.0, 4.0, 4.0))
        out.append((3.0, 5.5, 7.0, bad))
    return out

def main():
    tmp = tempfile.mkdtemp()
    glref = os.path.join(tmp, "reference")
    subprocess.run(["cc", "-O1", os.path.join(os.path.dirname(os.path.abspath(__file__)), "reference.c"),
                    "-o", glref, "-lEGL", "-lGL"], check=True)
    rng = random.Random(2012)
    print("# D3D11 triangle-domain patterns of Microsoft's reference tessellator (as shipped in Mesa 22.3.6,")
    print("# run by its draw module on llvmpipe through OpenGL tessellation and transform feedback).")
    print("# Per patch: partitioning, winding, outer factors e0 e1 e2 and inner factor (float bits, hex),")
    print("# triangles, and the FNV-1a 64 hash of the triangles' corners in order, each corner's 16.16")
    print("# u then v as little-endian uint32. OpenGL has no pow2 spacing: pow2 patches were run as")
    print("# integer on their factors rounded up to powers of two (the hull-shader helper's rounding).")
    print("# Made by scripts/d3d11_reference/generate.py.")
    for part in ["integer", "pow2", "fractional_odd", "fractional_even"]:
        cs = cases(part, rng)
        for winding in ["ccw", "cw"]:
            sel = [c for i, c in enumerate(cs) if (i % 2 == 0) == (winding == "ccw") or i < 64]
            # GL's ccw is tessim's: positive area in the (u, v) plane (D3D11 calls it triangle_cw)
            gl_winding = winding
            fed = [tuple(pow2_up(x) for x in c[:3]) + (pow2_up(c[3]),) if part == "pow2" else c for c in sel]
            stdin = "".join("%08x %08x %08x %08x\n" % tuple(bits(x) for x in f) for f in fed)
            res = subprocess.run([glref, SPACING[part], gl_winding], input=stdin, capture_output=True, text=True, check=True)
            lines = res.stdout.splitlines()
            assert len(lines) == len(sel)
            for c, line in zip(sel, lines):
                words = line.split()
                n = int(words[4])
                h = 0xcbf29ce484222325
                for corner in words[5:]:
                    u, v = (int(x, 16) for x in corner.split(","))
                    for b in struct.pack("<II", u, v):
                        h = ((h ^ b) * 0x100000001b3) & 0xffffffffffffffff
                print("%s %s %08x %08x %08x %08x %d %016x" % ((part, winding) + tuple(bits(x) for x in c) + (n, h)))

main()
