"""The Python module against the C++ it binds: shapes and types of its arrays, the float
reference's counts and corners, the cycle model's cycles and statistics against `tessim sim`,
and configuration errors as the command line reports them.

Run by ctest (python_module) as /usr/bin/python3 -m unittest with PYTHONPATH=<build>/python and
TESSIM_BINARY=<build>/bin/tessim.
"""

import json
import os
import pathlib
import re
import subprocess
import tempfile
import unittest

import numpy as np

import tessim

MESH = "/usr/share/assimp/models/PLY/Wuson.ply"
TESSIM = os.environ.get("TESSIM_BINARY", "tessim")


def vertices_per_patch(L):
    return (L + 1) * (L + 2) // 2


class MeshTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.mesh = tessim.load_mesh(MESH)

    def test_arrays(self):
        m = self.mesh
        V, T = m.vertex_count, m.triangle_count
        self.assertEqual((V, T), (2117, 3732))  # tessim info: welded vertices of Wuson
        self.assertEqual(m.positions.shape, (V, 3))
        self.assertEqual(m.normals.shape, (V, 3))
        self.assertEqual(m.triangles.shape, (T, 3))
        self.assertEqual(m.positions.dtype, np.float64)
        self.assertEqual(m.normals.dtype, np.float64)
        self.assertEqual(m.triangles.dtype, np.uint32)
        self.assertEqual(m.source, MESH)
        np.testing.assert_allclose(np.linalg.norm(m.normals, axis=1), 1.0, atol=1e-12)
        self.assertLess(int(m.triangles.max()), V)

    def test_views_share_the_mesh(self):
        # Views of the C++ vectors, not copies; read-only, so the mesh keeps load_mesh's invariants.
        a, b = self.mesh.positions, self.mesh.positions
        self.assertTrue(np.shares_memory(a, b))
        self.assertFalse(a.flags.writeable)
        with self.assertRaises(ValueError):
            a[0, 0] = 1.0
        # The array keeps its mesh alive.
        p = tessim.load_mesh(MESH).positions
        np.testing.assert_array_equal(p, self.mesh.positions)

    def test_missing_file_names_it(self):
        path = "/nonexistent/dir/no-such-mesh.ply"
        with self.assertRaises(tessim.InputError) as caught:
            tessim.load_mesh(path)
        self.assertIn(path, str(caught.exception))
        self.assertIsInstance(caught.exception, ValueError)

    def test_path_like(self):
        self.assertEqual(tessim.load_mesh(pathlib.Path(MESH)).triangle_count, self.mesh.triangle_count)

    def test_path_that_is_not_utf8(self):
        # A Linux file name is any bytes: opened as the command line opens it, from bytes or from
        # the str os.fsdecode makes of them; its source and messages never fail to decode.
        with tempfile.TemporaryDirectory() as tmp:
            raw = os.fsencode(tmp) + b"/c\xe9be.off"
            with open("/usr/share/assimp/models/OFF/Cube.off", "rb") as src, open(raw, "wb") as dst:
                dst.write(src.read())
            for path in (raw, os.fsdecode(raw)):
                mesh = tessim.load_mesh(path)
                self.assertEqual(mesh.triangle_count, 12)
                self.assertEqual(os.fsencode(mesh.source), raw)
                self.assertIn("c\\udce9be.off", repr(mesh))
            missing = os.fsencode(tmp) + b"/miss\xe9.off"
            with self.assertRaises(tessim.InputError) as caught:
                tessim.load_mesh(missing)
            self.assertIn(tmp + "/miss\\xe9.off: file: does not exist", str(caught.exception))

    def test_version_is_the_package_version(self):
        # The version `tessim --version` prints ("tessim 0.1.0 (git describe)"), not a git hash.
        out = subprocess.run([TESSIM, "--version"], capture_output=True, text=True, check=True).stdout
        self.assertEqual(out.split()[1], tessim.__version__)
        self.assertRegex(tessim.__version__, r"^\d+\.\d+\.\d+$")


class TessellateTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.mesh = tessim.load_mesh(MESH)

    def test_counts_and_types(self):
        T = self.mesh.triangle_count
        for L in (1, 4, 7):
            with self.subTest(L=L):
                p, n, t = tessim.tessellate(self.mesh, L=L)
                V = T * vertices_per_patch(L)
                self.assertEqual(p.shape, (V, 3))
                self.assertEqual(n.shape, (V, 3))
                self.assertEqual(t.shape, (T * L * L, 3))
                self.assertEqual((p.dtype, n.dtype, t.dtype), (np.float64, np.float64, np.uint32))
                self.assertTrue(p.flags.c_contiguous and p.flags.writeable)
                self.assertEqual(int(t.max()), V - 1)
                np.testing.assert_allclose(np.linalg.norm(n, axis=1), 1.0, atol=1e-12)

    def test_patch_corners_are_the_input_vertices(self):
        # Pattern order: (j, k) = (0, 0), (L, 0) and (0, L) are the first, (L+1)-th and last vertex
        # of a patch, and PN triangles interpolate their corners.
        L = 5
        p, n, _ = tessim.tessellate(self.mesh, L=L, normals="linear")
        per = vertices_per_patch(L)
        tri = self.mesh.triangles.astype(np.int64)
        patches = p.reshape(-1, per, 3)
        for corner, local in ((0, 0), (1, L), (2, per - 1)):
            np.testing.assert_allclose(patches[:, local], self.mesh.positions[tri[:, corner]], rtol=0, atol=1e-12)
            np.testing.assert_allclose(n.reshape(-1, per, 3)[:, local], self.mesh.normals[tri[:, corner]], atol=1e-12)

    def test_bad_arguments(self):
        with self.assertRaisesRegex(ValueError, "tessellation factor: 0 is outside 1..64"):
            tessim.tessellate(self.mesh, L=0)
        with self.assertRaisesRegex(ValueError, "normals: 'smooth' is not one of quadratic, reflect, linear, derivative"):
            tessim.tessellate(self.mesh, L=2, normals="smooth")
        # True is an int in Python; as a tessellation factor it is a mistake, not L = 1.
        for bad in (True, 2.0, "4"):
            with self.assertRaisesRegex(ValueError, "L: .* is not an integer"):
                tessim.tessellate(self.mesh, L=bad)


class ConfigTest(unittest.TestCase):
    def test_keys_and_defaults_are_the_schema(self):
        params = tessim.schema()["parameters"]
        cfg = tessim.Config()
        self.assertEqual(cfg.keys(), [p["key"] for p in params])
        for p in params:
            self.assertEqual(cfg[p["key"]], p["default"], p["key"])
            self.assertEqual(getattr(cfg, p["key"]), p["default"], p["key"])

    def test_dict_keywords_and_replace(self):
        a = tessim.Config({"int_blocks": 3, "normals": "reflect"}, tess_factor=6)
        b = tessim.Config(int_blocks=3, normals="reflect", tess_factor=6)
        self.assertEqual(a, b)
        self.assertEqual(a.to_dict()["tess_factor"], 6)
        self.assertEqual(tessim.Config(a.to_dict()), a)
        self.assertEqual(tessim.Config(a), a)
        c = a.replace(int_blocks=4)
        self.assertEqual((c.int_blocks, a.int_blocks, c.tess_factor), (4, 3, 6))
        self.assertEqual(repr(b), "tessim.Config(tess_factor=6, normals='reflect', int_blocks=3)")
        self.assertEqual(tessim.Config(seed=np.uint64(2**64 - 1)).seed, 2**64 - 1)

    def test_errors_name_the_key(self):
        cases = [
            ({"int_blockz": 2}, "configuration: int_blockz: unknown configuration key"),
            ({"int_blocks": 33}, "configuration: int_blocks: value 33 out of range [1, 32]"),
            ({"gpe_stall_prob": 1.5}, "configuration: gpe_stall_prob: value 1.5 out of range [0.0, 0.99]"),
            ({"int_blocks": "2"}, "configuration: int_blocks: expected an integer"),
            ({"int_blocks": 2.0}, "configuration: int_blocks: expected an integer"),
            ({"int_blocks": True}, "configuration: int_blocks: expected an integer"),
            ({"seed": -1}, "configuration: seed: expected a non-negative integer"),
            ({"cpg_mapping": "fast"}, "configuration: cpg_mapping: 'fast' is not one of dedicated, gpe"),
            ({"normals": "derivative"}, "configuration: normals: 'derivative' is available in the float reference only"),
            ({"coord_int_bits": 8, "coord_frac_bits": 26},
             "configuration: coord_int_bits + coord_frac_bits: coordinate width 35 exceeds 32 bits"),
        ]
        for params, message in cases:
            with self.subTest(params=params):
                with self.assertRaisesRegex(ValueError, "^" + re.escape(message)):
                    tessim.Config(**params)
                with self.assertRaisesRegex(ValueError, "^" + re.escape(message)):
                    tessim.Config(params)

    def test_same_message_as_a_config_file(self):
        # The CLI's message for the same bad key in a --config file differs only in the source.
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "cfg.json")
            with open(path, "w") as f:
                json.dump({"te_contexts": 17}, f)
            cli = subprocess.run([TESSIM, "sim", MESH, "--config", path], capture_output=True, text=True)
            self.assertEqual(cli.returncode, 2)
            with self.assertRaises(ValueError) as caught:
                tessim.Config(te_contexts=17)
            self.assertEqual(cli.stderr.strip(), "tessim: error: " + str(caught.exception).replace("configuration", path, 1))

    def test_wrong_container(self):
        with self.assertRaises(TypeError):
            tessim.Config([("int_blocks", 2)])


class SimulateTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.mesh = tessim.load_mesh(MESH)

    def cli(self, *args):
        with tempfile.TemporaryDirectory() as d:
            stats_path = os.path.join(d, "stats.json")
            out = subprocess.run([TESSIM, "sim", MESH, *args, "--stats", stats_path], check=True,
                                 capture_output=True, text=True).stdout
            with open(stats_path) as f:
                return out, json.load(f)

    def test_tags_below_the_fixed_point_resolution_warn(self):
        # A crease vector of 1e-7 reaches the unit as zero: said with the count, as `tessim sim` does.
        ply = ("ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
               "property double dx\nproperty double dy\nproperty double dz\nproperty double sigma\n"
               "property double theta\nproperty double beta\nelement face 4\n"
               "property list uchar int vertex_indices\nend_header\n"
               "0 0 1 0 0 1e-7 0 0 0\n1 0 0 0 0 0 0 0 0\n0 1 0 0 0 0 0 0 0\n-1 -1 -1 0 0 0 0 0 0\n"
               "3 0 1 2\n3 0 2 3\n3 0 3 1\n3 1 3 2\n")
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "tiny.ply")
            with open(path, "w") as f:
                f.write(ply)
            mesh = tessim.load_mesh(path)
            with self.assertWarnsRegex(UserWarning, r"tiny.ply: tags: 1 vertices carry a crease vector or tension "
                                                    r"below the fixed-point resolution"):
                tessim.simulate(mesh, cpg_tags=1, outputs=False)

    def test_cycles_and_statistics_match_the_cli(self):
        runs = [
            ({"tess_factor": 2, "int_blocks": 3}, ["-L", "2", "--int-blocks", "3"]),
            ({"tess_factor": 3, "gpe_cycles": 2, "gpe_stall_prob": 0.25, "seed": 7, "normals": "reflect"},
             ["--tess-factor", "3", "--gpe-cycles", "2", "--stall", "0.25", "--seed", "7", "--normals", "reflect"]),
        ]
        for params, args in runs:
            with self.subTest(params=params):
                r = tessim.simulate(self.mesh, tessim.Config(**params), outputs=False)
                out, stats = self.cli(*args)
                cycles = int(re.search(r"^result\s+(\d+) cycles\s+(\d+) vertices", out, re.M).group(1))
                self.assertEqual(r.cycles, cycles)
                self.assertEqual(r.summary.splitlines()[:3], out.splitlines()[:3])
                for s in (stats, r.stats):
                    del s["wall_seconds"], s["tool"]  # the one figure that differs between runs, and the build
                self.assertEqual(r.stats, stats)
                self.assertEqual(r.vertices, self.mesh.triangle_count * vertices_per_patch(params["tess_factor"]))
                self.assertIsNone(r.positions)

    def test_keywords_and_dict(self):
        a = tessim.simulate(self.mesh, {"tess_factor": 2}, outputs=False, int_blocks=1)
        b = tessim.simulate(self.mesh, tessim.Config(tess_factor=2, int_blocks=1), outputs=False)
        self.assertEqual((a.cycles, a.config), (b.cycles, b.config))
        with self.assertRaisesRegex(ValueError, "^configuration: int_latency: value 0 out of range"):
            tessim.simulate(self.mesh, int_latency=0)

    def test_outputs(self):
        L = 3
        r = tessim.simulate(self.mesh, tess_factor=L)
        V = self.mesh.triangle_count * vertices_per_patch(L)
        self.assertEqual(r.vertices, V)
        for name, dtype in (("positions", np.float64), ("normals", np.float64), ("positions_fx", np.int64),
                            ("normals_fx", np.int64)):
            a = getattr(r, name)
            self.assertEqual((a.shape, a.dtype), ((V, 3), dtype), name)
        self.assertEqual(r.triangles.shape, (self.mesh.triangle_count * L * L, 3))
        self.assertEqual(r.triangles.dtype, np.uint32)
        # The same topology as the float reference, and positions within the fixed-point error of
        # it (Q3.20 over the mesh's half-extent: far below 1e-4 of the model's size).
        p, n, t = tessim.tessellate(self.mesh, L=L)
        np.testing.assert_array_equal(r.triangles, t)
        extent = np.ptp(self.mesh.positions, axis=0).max()
        self.assertLess(np.abs(r.positions - p).max(), 1e-4 * extent)
        self.assertGreater(np.einsum("ij,ij->i", r.normals, n).min(), 0.999)
        # The fixed-point fields are what the unit outputs: Q3.20 coordinates of the unit cube.
        self.assertLessEqual(np.abs(r.positions_fx).max(), 1 << 20)
        self.assertGreater(np.abs(r.positions_fx).max(), 1 << 19)

    def test_errors_statistics(self):
        r = tessim.simulate(self.mesh, tess_factor=2, outputs=False, errors=True)
        self.assertIn("errors", r.stats)
        self.assertNotIn("errors", tessim.simulate(self.mesh, tess_factor=2, outputs=False).stats)


if __name__ == "__main__":
    unittest.main()
