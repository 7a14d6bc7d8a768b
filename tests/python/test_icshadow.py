"""test_icshadow.py: the Python package against the CLI, which runs the same C libraries.
Numbers are compared bit for bit (the CLI prints %.17g, which reads back exactly); images through
the EXR files the CLI writes. Environment: ICSHADOW_CLI (the icshadow binary), ICSHADOW_TMP (a
scratch folder). Run by tests/python/run.sh."""
import json
import os
import subprocess
import threading
import unittest

import numpy as np

import icshadow as ic

CLI = os.environ["ICSHADOW_CLI"]
TMP = os.environ["ICSHADOW_TMP"]
REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def cli(*args, stdin=None, check=True):
    r = subprocess.run([CLI, *args], input=stdin, capture_output=True, text=True)
    if check and r.returncode != 0:
        raise AssertionError(f"icshadow {' '.join(args)}: exit {r.returncode}: {r.stderr}")
    return r


def tmp(name):
    return os.path.join(TMP, name)


class Numerics(unittest.TestCase):
    FUNCS = {"ellipk": (ic.ellint_k, np.linspace(-3, 1, 401)),
             "ellipe": (ic.ellint_e, np.linspace(-3, 1, 401)),
             "ellipk_m1": (ic.ellint_k_m1, np.geomspace(1e-300, 4, 401)),
             "ellipe_m1": (ic.ellint_e_m1, np.geomspace(1e-300, 4, 401)),
             "varx": (ic.ellipse_varx, np.linspace(0, 3, 301)),
             "vx": (ic.ellipse_vx, np.linspace(0, 1, 301)),
             "vy": (ic.ellipse_vy, np.linspace(0, 1, 301)),
             "ratio": (ic.ellipse_ratio, np.linspace(0, 1, 301)),
             "ratio_to_t": (ic.ellipse_ratio_to_t, np.geomspace(1e-12, 1e12, 301))}

    def test_bit_equal_to_the_cli(self):
        for name, (f, x) in self.FUNCS.items():
            text = "\n".join(repr(float(v)) for v in x) + "\n"
            want = np.array([float(v) for v in cli("eval", name, stdin=text).stdout.split()])
            got = f(x)
            self.assertEqual(got.shape, x.shape, name)
            np.testing.assert_array_equal(got, want, err_msg=name)  # NaN == NaN here
            self.assertEqual(f(float(x[7])), want[7], name)  # a number in, a float out
            self.assertIsInstance(f(0.5), float)

    def test_srgb(self):
        x = np.linspace(0, 1, 11)
        got = ic.srgb(x)
        want = np.where(x <= 0.0031308, 12.92 * x, 1.055 * x ** (1 / 2.4) - 0.055)  # IEC 61966-2-1
        np.testing.assert_allclose(got, want, rtol=1e-12, atol=1e-15)

    def test_shapes_and_bad_arrays(self):
        m = np.linspace(0, 0.9, 12).reshape(3, 4)
        self.assertEqual(ic.ellint_k(m).shape, (3, 4))
        np.testing.assert_array_equal(ic.ellint_k(m[:, ::2]), ic.ellint_k(m[:, ::2].copy()))
        np.testing.assert_array_equal(ic.ellint_k(m.astype(np.float32)), ic.ellint_k(m.astype(np.float32).astype(float)))
        self.assertEqual(ic.ellint_k(np.array([])).shape, (0,))
        self.assertEqual(ic.ellint_k([1, 0])[1], ic.ellint_k(0.0))  # integers are numbers
        self.assertTrue(np.isnan(ic.ellint_k(np.nan)))
        for bad in (np.array([1j]), ["a"], np.array([True]), [object()]):
            with self.assertRaises(TypeError):
                ic.ellint_k(bad)

    def test_ellipse_kernel(self):
        k = ic.ellipse_kernel(1.0, 0.25, 30.0, 8)
        self.assertEqual(k.xy.shape, (8, 2))
        cov = k.xy.T @ k.xy / 8
        self.assertAlmostEqual(k.angle_deg, 30.0)
        # averaged over offsets the taps have the covariance; at one offset close to it
        self.assertLess(abs(np.trace(cov) - 1.25), 0.05)
        self.assertEqual(ic.ellipse_kernel(0, 0, 0, 4).xy.shape, (1, 2))  # a point light: 1 tap
        with self.assertRaisesRegex(ic.Error, "negative"):
            ic.ellipse_kernel(-1, 1)
        with self.assertRaisesRegex(ic.Error, "out of range"):
            ic.ellipse_kernel(1, 1, 0, 10**9)


class Isolines(unittest.TestCase):
    LIGHTS = {"gauss:0.3,1": lambda: ic.Light1D.gauss(0.3, 1), "box:-1,2": lambda: ic.Light1D.box(-1, 2),
              "mix:0.8,0,0.2;0.2,2,1": lambda: ic.Light1D.mix([0.8, 0.2], [0, 2], [0.2, 1])}

    def test_bit_equal_to_the_cli(self):
        for spec, make in self.LIGHTS.items():
            light = make()
            for model, extra, kw in (("correct", [], {}), ("clt", ["--d1", "1"], {"d1": 1}),
                                     ("iterative", ["--d1", "1", "--slab", "0.05"], {"d1": 1, "slab": 0.05})):
                for s, d in ((0.1, 0.5), (0.5, 1.0), (0.9, 2.0)):
                    want = float(cli("isoline", "--light", spec, "--level", str(s), "--distance", str(d),
                                     "--model", model, *extra).stdout)
                    self.assertEqual(ic.isoline(light, s, d, model, **kw), want, (spec, model, s, d))

    def test_bad_input(self):
        g = ic.Light1D.gauss(0, 1)
        with self.assertRaisesRegex(ic.Error, "integer number of slabs"):
            ic.isoline(g, 0.5, 1.0, "iterative", d1=1, slab=0.3)
        with self.assertRaisesRegex(ic.Error, r"= 10000000 must be an integer number of slabs \(at most 1e6\)"):
            ic.isoline(g, 0.5, 1e4, "iterative", d1=1, slab=0.001)  # (the work budget: cli_isoline_work_budget)
        with self.assertRaisesRegex(ValueError, "needs d1"):
            ic.isoline(g, 0.5, 1.0, "clt")
        with self.assertRaisesRegex(ValueError, r"level must be in \(0, 1\)"):
            ic.isoline(g, 1.5, 1.0)
        with self.assertRaises(ic.Error):
            ic.Light1D.box(2, 1)
        with self.assertRaisesRegex(ValueError, "three lists of one length"):
            ic.Light1D.mix([1], [0, 1], [1])


class Luts(unittest.TestCase):
    def test_headers_equal_the_cli(self):
        for lang in ("c", "glsl", "opencl"):
            self.assertEqual(ic.lut_header(32, lang), cli("lut", "--size", "32", "--lang", lang).stdout, lang)

    def test_tables(self):
        s, g = ic.lut(64)
        self.assertEqual(s.shape, (64,))
        self.assertAlmostEqual(s[0], 2 ** -0.5, 12)  # s(0) = lim t / w = 1 / sqrt(2)
        for bad in (3, 65537, -1):
            with self.assertRaisesRegex(ic.Error, "out of range"):
                ic.lut(bad)
        with self.assertRaisesRegex(ValueError, "unknown value 'hlsl'"):
            ic.lut_header(32, "hlsl")


class Lights(unittest.TestCase):
    def test_round_trip_and_the_cli_format(self):
        lights = [ic.Light(np.array([0.1, -0.3]), np.array([[0.02, 0.005], [0.005, 0.01]]),
                           np.array([1.0, 0.9, 0.8]), 2.5),
                  ic.Light(np.array([0.0, 0.0]), np.eye(2) * 1e-3)]
        path = tmp("two.json")
        ic.write_lights(path, lights)
        back = ic.read_lights(path)
        for a, b in zip(lights, back):
            np.testing.assert_array_equal(a.mean, b.mean)
            np.testing.assert_array_equal(a.cov, b.cov)
            np.testing.assert_array_equal(a.color, b.color)
            self.assertEqual(a.weight, b.weight)
        with open(path) as f:
            self.assertEqual(json.load(f)["lights"][0]["weight"], 2.5)
        umask = os.umask(0o022)
        try:
            ic.write_lights(path, lights)
            self.assertEqual(os.stat(path).st_mode & 0o777, 0o644)  # as a new file, not mkstemp's 0600
        finally:
            os.umask(umask)
        with self.assertRaisesRegex(ValueError, r"lights\[0\]: a NaN or infinite value"):
            ic.lights_json([ic.Light(np.array([np.nan, 0.0]), np.eye(2))])

    def test_errors_carry_the_library_message(self):
        with self.assertRaisesRegex(ic.Error, "nonexistent.json: cannot open lights file"):
            ic.read_lights(tmp("nonexistent.json"))
        bad = tmp("bad.json")
        with open(bad, "w") as f:
            f.write('{"lights": [{"mean": [0, 0], "cov": [[1, 0], [0, -1]]}]}')
        with self.assertRaisesRegex(ic.Error, r"bad.json: lights\[0\]"):
            ic.read_lights(bad)

    def test_fit_equals_the_cli(self):
        env = tmp("env.exr")
        cli("make-env", "--lights", "0.2,0.1,0.02,0.01,30", "--size", "128x64", "-o", env)
        out = tmp("fit_cli.json")
        cli("fit-light", env, "--lights", "2", "-o", out)
        lights, rep = ic.fit_light(env, lights=2)
        self.assertEqual(ic.lights_json(lights), open(out).read())
        chans, _ = ic.read_exr(env)
        arr = np.stack([chans[c] for c in "RGB"], -1)
        lights2, rep2 = ic.fit_light(arr[:, ::1], lights=2)
        self.assertEqual(ic.lights_json(lights2), open(out).read())
        self.assertEqual(rep, rep2)
        self.assertIn("l1", rep)

    def test_fit_auto_equals_the_cli(self):
        env = tmp("sky.exr")  # three lights over a sky (tests/cli/lightfit_auto.sh's sky map)
        spec = ("0.2771,0.3447,0.0095,0.0476,55.2994,0.9095,0.6895,0.5246,0.5798:"
                "0.4211,-0.5810,0.0174,0.0173,-48.2847,1.8773,0.3854,0.7815,0.7366:"
                "-0.6648,-0.5302,0.0056,0.0066,56.4572,1.8205,0.7776,0.8258,0.5824")
        cli("make-env", "--lights", spec, "--sky", "0.02,0.03,0.05", "--size", "128x64", "-o", env)
        out = tmp("auto_cli.json")
        err = cli("fit-light", env, "--lights", "auto:6", "-o", out).stderr
        lights, rep = ic.fit_light(env, lights="auto:6")
        self.assertIn(f"auto: K = {rep['k']},", err)
        self.assertEqual(ic.lights_json(lights), open(out).read())
        self.assertEqual(len(rep["fits"]), 6)
        self.assertEqual(rep["l1"], rep["fits"][rep["k"] - 1]["l1"])
        with self.assertRaisesRegex(ValueError, "auto:KMAX"):
            ic.fit_light(env, lights="auto:99")

    def test_fit_bad_maps(self):
        good = np.ones((8, 16, 3), np.float32)
        nan = good.copy()
        nan[2, 3, 1] = np.nan
        with self.assertRaisesRegex(ValueError, "NaN"):
            ic.fit_light(nan)
        with self.assertRaisesRegex(ValueError, "expected shape"):
            ic.fit_light(np.ones((8, 16)))
        with self.assertRaises((ValueError, ic.Error)):
            ic.fit_light(np.ones((0, 0, 3)))
        with self.assertRaises(TypeError):
            ic.fit_light(np.full((8, 16, 3), "x"))
        with self.assertRaisesRegex(ValueError, r"lights: expected 1\.\.\d+, got 1000000"):
            ic.fit_light(good, lights=10**6)
        with self.assertRaisesRegex(ic.Error, "cannot open"):
            ic.fit_light(tmp("missing.exr"))


class Renders(unittest.TestCase):
    def test_renderer_keeps_frames_equal(self):
        # frames of several sizes and models in turn on one Renderer: each the bits (AOVs
        # included) of a render on a new renderer; closed, it refuses to render
        frames = [dict(resolution=(64, 48)), dict(resolution=(96, 72)),
                  dict(resolution=(64, 48), model="patel"), dict(resolution=(32, 24))]
        with ic.Renderer(threads=2) as r:
            self.assertEqual(r.backend, "cpu")
            for f in frames:
                mine = r.render(aovs=["visibility", "depth"], **f)
                new = ic.render(aovs=["visibility", "depth"], threads=2, **f)
                np.testing.assert_array_equal(mine.rgba, new.rgba, err_msg=str(f))
                self.assertEqual(sorted(mine.aovs), sorted(new.aovs))
                for name in new.aovs:
                    np.testing.assert_array_equal(mine[name], new[name], err_msg=f"{f} {name}")
                self.assertEqual(mine.summary["model"], new.summary["model"])
        with self.assertRaisesRegex(ValueError, "closed"):
            r.render()
        r.close()  # twice: nothing more
        with self.assertRaisesRegex(ValueError, "only the Monte-Carlo reference takes a stop"):
            ic.Renderer(backend="cpu", spp=4)
        with self.assertRaisesRegex(ic.Error, "nosuch"):
            ic.Renderer(backend="nosuch")

    def test_render_equals_the_cli(self):
        exr = tmp("default.exr")
        summary = json.loads(cli("render", "--resolution", "64x48", "--aov", "visibility,depth",
                                 "--threads", "1", "-o", exr).stdout)
        r = ic.render(resolution=(64, 48), aovs=["visibility", "depth"], threads=1)
        chans, info = ic.read_exr(exr)
        self.assertEqual(r.rgba.shape, (48, 64, 4))
        self.assertEqual(r.rgba.dtype, np.float32)
        np.testing.assert_array_equal(r.rgba, np.stack([chans[c] for c in "RGBA"], -1))
        for name, a in r.aovs.items():
            np.testing.assert_array_equal(a, chans[name], err_msg=name)
        self.assertEqual(sorted(set(summary) - {"exr"}), sorted(r.summary))
        for k in ("scene", "backend", "resolution", "slabs", "kernel", "model", "aovs", "memory_bytes"):
            self.assertEqual(r.summary[k], summary[k], k)
        self.assertEqual(info["slabs"], r.summary["slabs"])
        # written by the package: the same pixels, the summary inside, the CLI's compare reads it
        mine = tmp("mine.exr")
        r.write_exr(mine)
        chans2, info2 = ic.read_exr(mine)
        self.assertEqual(sorted(chans2), sorted(chans))
        for name in chans:
            np.testing.assert_array_equal(chans2[name], chans[name], err_msg=name)
        self.assertEqual(info2, r.summary)
        c = json.loads(cli("render", "--resolution", "64x48", "--threads", "1", "--compare", mine).stdout)
        self.assertEqual(c["compare"]["rmse"], 0)
        self.assertEqual(c["compare"]["reference_backend"], "cpu")
        png = tmp("mine.png")
        r.write_png(png)
        cli("render", "--resolution", "64x48", "--threads", "1", "--png", tmp("cli.png"))
        self.assertEqual(open(png, "rb").read(), open(tmp("cli.png"), "rb").read())
        with self.assertRaisesRegex(ValueError, "one \\(height, width\\) array"):
            ic.write_exr(tmp("x.exr"), {"R": np.zeros((2, 2)), "G": np.zeros((3, 2))})
        with self.assertRaisesRegex(ic.Error, "NaN"):
            ic.write_exr(tmp("x.exr"), {"R": np.full((2, 2), np.nan)})
        self.assertFalse(os.path.exists(tmp("x.exr")))

    def test_overrides_and_scenes(self):
        disk = os.path.join(REPO, "scenes", "disk.json")
        a = ic.render(disk, resolution=(32, 32))
        self.assertEqual(a.summary["scene"], disk)
        b = ic.render(disk, resolution=(32, 32), model="solid", samples=4)
        self.assertEqual((b.summary["model"], b.summary["samples"]), ("solid", 4))
        c = ic.render(json.load(open(disk)), resolution=(32, 32))  # a dict
        np.testing.assert_array_equal(a.rgba, c.rgba)
        p = ic.plan(disk, resolution=(32, 32))
        self.assertEqual(p["resolution"], [32, 32])
        self.assertEqual(p["slabs"], a.summary["slabs"])
        self.assertEqual(ic.default_scene()["render"]["kernel"], ic.render(resolution=(8, 8)).summary["kernel"])

    def test_errors_carry_the_cli_message(self):
        bad = tmp("bad_scene.json")
        with open(bad, "w") as f:
            f.write('{"camera": {"eye": [0, 0, 2],,}}\n')
        err = cli("render", bad, "-o", tmp("never.exr"), check=False).stderr.strip()
        with self.assertRaises(ic.Error) as e:
            ic.render(bad)
        self.assertEqual("icshadow render: " + str(e.exception), err)
        with self.assertRaisesRegex(ic.Error, 'default: render.model: unknown value "fast"'):
            ic.render(resolution=(8, 8), model="fast")
        with self.assertRaisesRegex(ic.Error, 'default: render: unknown key "bogus" \(expected slab_spacing'):
            ic.plan(bogus=1)
        with self.assertRaisesRegex(ic.Error, "no backend named 'vulkan'"):
            ic.render(resolution=(8, 8), backend="vulkan")
        with self.assertRaisesRegex(ValueError, "unknown 'normals'"):
            ic.render(resolution=(8, 8), aovs=["normals"])
        with self.assertRaises(ValueError):
            ic.render(resolution=(0, 8))
        with self.assertRaises(TypeError):
            ic.render(42)
        with self.assertRaisesRegex(ValueError, "only the Monte-Carlo reference takes a stop"):
            ic.render(resolution=(8, 8), spp=4)
        with self.assertRaisesRegex(ValueError, "threads: expected 0"):
            ic.render(resolution=(8, 8), threads=-3)
        with self.assertRaisesRegex(ic.Error, "exceeds 16384 per axis"):
            ic.render(resolution=(10 ** 6, 10))
        with self.assertRaisesRegex(ic.Error, "samples per pixel must be in"):
            ic.render(resolution=(8, 8), backend="mc", spp=-1)
        with self.assertRaisesRegex(ic.Error, "not a regular file"):
            ic.read_lights("/dev/null")
        with self.assertRaisesRegex(FileNotFoundError, "does not exist"):
            ic.write_lights(tmp("no/such/folder/x.json"), [])

    def test_compare_with_the_reference(self):
        ref = ic.render(resolution=(32, 24), backend="mc", spp=8, aovs=["stderr"])
        self.assertEqual(ref.summary["spp"], 8)
        r = ic.render(resolution=(32, 24))
        c = ic.compare(r, ref)
        self.assertGreater(c["rmse"], 0)
        self.assertLessEqual(c["rmse_beyond_noise"], c["rmse"])
        self.assertGreaterEqual(c["max_error"], c["rmse"])
        self.assertEqual(ic.compare(r, r)["rmse"], 0)
        # the CLI's --compare on the same pair of files: the same numbers
        a, b = tmp("r.exr"), tmp("ref.exr")
        cli("render", "--resolution", "32x24", "-o", a)
        cli("render", "--resolution", "32x24", "--backend", "mc", "--spp", "8", "--aov", "stderr", "-o", b)
        want = json.loads(cli("render", "--resolution", "32x24", "--compare", b).stdout)["compare"]
        got = ic.compare(a_render := ic.render(resolution=(32, 24)), b)
        for k in ("reference_backend", "reference_spp", "ms_reference", "reference_device"):
            self.assertEqual(got[k], want[k], k)
        for k in ("rmse", "max_error", "max_at", "psnr_db"):  # ics_image_diff_rgb's own numbers
            self.assertEqual(got[k], want[k], k)
        for k in ("reference_noise", "rmse_beyond_noise"):  # numpy sums in another order
            self.assertLess(abs(got[k] - want[k]), 1e-12 * want[k], k)
        with self.assertRaisesRegex(ValueError, "the reference is 8x8"):
            ic.compare(a_render, np.zeros((8, 8, 3)))

    def test_render_releases_the_gil(self):
        done, count = threading.Event(), 0
        t = threading.Thread(target=lambda: (ic.render(resolution=(320, 240), threads=1), done.set()))
        t.start()
        while not done.is_set():
            count += 1
        t.join()
        # with the GIL held for the C render this loop would stall for the whole frame
        self.assertGreater(count, 1000)

    def test_backends(self):
        table = {b["name"]: b for b in ic.backends()}
        self.assertIn("cpu", table)
        self.assertIn("mc", table)
        self.assertEqual(table["cpu"]["options"], [])

    def test_backend_options(self):
        table = {b["name"]: b for b in ic.backends()}
        if "gl" not in table:
            self.skipTest("no gl backend in this build")
        opts = {o["name"]: o for o in table["gl"]["options"]}
        self.assertEqual(opts["gl.context"]["values"], "auto|egl|osmesa")
        self.assertEqual(opts["gl.context"]["env"], "ICS_GL_CONTEXT")
        # checked whatever backend runs, with the library's messages
        with self.assertRaisesRegex(ic.Error, r"backend gl has no option 'lod' \(it takes context, ldi\)"):
            ic.render(resolution=(8, 8), backend="cpu", backend_options={"gl.lod": "1"})
        with self.assertRaisesRegex(ic.Error, "gl.context: expected auto, egl or osmesa, got 'vulkan'"):
            ic.render(resolution=(8, 8), backend="cpu", backend_options={"gl.context": "vulkan"})
        with self.assertRaisesRegex(ic.Error, "no backend named 'vk'"):
            ic.render(resolution=(8, 8), backend_options={"vk.x": "1"})
        r = ic.render(resolution=(8, 8), backend="cpu", backend_options={"gl.context": "osmesa"})
        self.assertEqual(r.summary["backend"], "cpu")


if __name__ == "__main__":
    unittest.main(verbosity=2)
