"""The weft Python module against the weft command: the same pixels, the
same parameter tables, the same metrics and the same one-line errors.

    PYTHONPATH=build/bin WEFT=build/bin/weft /usr/bin/python3 -m unittest test_module   (ctest: python_module)
"""
import os
import signal
import subprocess
import tempfile
import threading
import unittest

import numpy as np
import OpenImageIO as oiio

import weft

WEFT = os.environ.get("WEFT", "weft")
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SMOKE = os.path.join(ROOT, "data", "smoke_small.vdb")
CORNELL = os.path.join(ROOT, "scenes", "cornell.json")


def read_exr(path):
    buf = oiio.ImageBuf(path)
    return buf.get_pixels(oiio.FLOAT), list(buf.spec().channelnames)


def cli(*args):
    return subprocess.run([WEFT] + list(args), capture_output=True, text=True)


class SameAsTheCommand(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()

    def tearDown(self):
        self.tmp.cleanup()

    def cli_render(self, scene, *args):
        # A new name each time: OpenImageIO's cache would hand back an earlier file's pixels.
        out = tempfile.mktemp(suffix=".exr", dir=self.tmp.name)
        done = cli("render", scene, "-o", out, *args)
        self.assertEqual(done.returncode, 0, done.stderr)
        return read_exr(out)

    def test_pixels_are_the_cli_exr_bit_for_bit(self):
        cases = [(SMOKE, "volume.raymarch", {"step": "0.7"}, (48, 40), 1),
                 (SMOKE, "volume.adaptive3d", {}, (40, 40), 1),
                 (CORNELL, "mesh.pathtrace", {}, (32, 24), 4)]
        for scene, technique, params, (w, h), spp in cases:
            sets = sum((["--set", "%s=%s" % kv] for kv in params.items()), [])
            expected, names = self.cli_render(scene, "--technique", technique, "--res", "%dx%d" % (w, h),
                                              "--spp", str(spp), "--seed", "5", *sets)
            r = weft.load_scene(scene).render(technique=technique, params=params, res=(w, h), spp=spp, seed=5)
            self.assertEqual(r.pixels.dtype, np.float32)
            self.assertEqual(r.pixels.shape, (h, w, len(r.channels)))
            self.assertEqual(r.channels, names)
            self.assertTrue(np.array_equal(r.pixels, expected), technique)
            self.assertGreater(r.counters["image.samples" if "image.samples" in r.counters else "volume.samples"], 0)
            self.assertIn("render", r.timings)

    def test_a_scene_renders_many_times_without_reloading(self):
        s = weft.load_scene(SMOKE)
        a = s.render(res=(24, 24), threads=1)
        b = s.render(res=(24, 24), threads=2)
        self.assertEqual(b.timings["load"], 0.0)
        self.assertTrue(np.array_equal(a.pixels, b.pixels))  # any thread count, the same image

    def test_renders_in_two_python_threads_equal_one(self):
        s = weft.load_scene(SMOKE)
        alone = s.render(res=(32, 32), threads=1).pixels
        results = [None, None]

        def work(i):
            results[i] = s.render(res=(32, 32), threads=1).pixels
        threads = [threading.Thread(target=work, args=(i,)) for i in range(2)]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
        for r in results:
            self.assertTrue(np.array_equal(r, alone))

    def test_help_is_weft_help(self):
        names = weft.techniques()
        self.assertIn("volume.raymarch", names)
        for name in names:
            self.assertEqual(weft.help(name), cli("help", name).stdout, name)

    def test_errors_are_the_cli_messages(self):
        done = cli("render", SMOKE, "--technique", "volume.raymarch", "--set", "step=-1", "-o", os.path.join(self.tmp.name, "x.exr"))
        self.assertNotEqual(done.returncode, 0)
        message = done.stderr.strip().splitlines()[-1].replace("weft: error: ", "", 1)
        with self.assertRaises(weft.Error) as caught:
            weft.load_scene(SMOKE).render(technique="volume.raymarch", params={"step": -1})
        self.assertEqual(str(caught.exception), message)
        with self.assertRaisesRegex(weft.Error, "no such file"):
            weft.load_scene(os.path.join(self.tmp.name, "missing.json"))
        with self.assertRaisesRegex(weft.Error, "unknown technique|no technique"):
            weft.help("volume.nothing")

    def test_diff_is_weft_diff(self):
        a, b = os.path.join(self.tmp.name, "a.exr"), os.path.join(self.tmp.name, "b.exr")
        self.assertEqual(cli("render", SMOKE, "--res", "32x32", "--set", "step=2", "-o", a).returncode, 0)
        self.assertEqual(cli("render", SMOKE, "--res", "32x32", "--set", "step=0.5", "-o", b).returncode, 0)
        rows = {line.split()[0]: line.split()[1:] for line in cli("diff", a, b).stdout.splitlines()[1:-1]}
        d = weft.diff(a, b)
        self.assertAlmostEqual(d["all"]["rmse"], float(rows["all"][0]), delta=1e-6 * float(rows["all"][0]) + 1e-12)
        self.assertAlmostEqual(d["channels"]["R"]["ssim"], float(rows["R"][3]), places=5)
        self.assertGreater(d["all"]["rmse"], 0)
        pixels, _ = read_exr(a)
        self.assertEqual(weft.diff(pixels, pixels)["all"]["rmse"], 0.0)  # arrays as well as paths
        r = weft.load_scene(SMOKE).render(res=(32, 32), params={"step": 2})
        self.assertEqual(weft.diff(r, a)["all"]["rmse"], 0.0)

    def test_check_is_weft_check(self):
        good, cut, gone = (os.path.join(self.tmp.name, n) for n in ("good.exr", "cut.exr", "gone.exr"))
        for path in (good, cut):
            self.assertEqual(cli("render", SMOKE, "--res", "16x16", "-o", path).returncode, 0)
        with open(cut, "r+b") as f:
            f.truncate(os.path.getsize(cut) // 2)
        paths = [good, cut, gone]
        by_module = weft.check(paths)
        by_command = dict(reversed(line.split("\t", 1)) for line in cli("check", *paths).stdout.splitlines())
        self.assertEqual(by_module, by_command)
        self.assertEqual(by_module[good], "ok")
        self.assertEqual(by_module[gone], "missing")
        self.assertTrue(by_module[cut].startswith("corrupt: "), by_module[cut])

    def test_a_dict_is_a_scene_file(self):
        scene = {"volumes": [{"file": "smoke_small.vdb"}], "render": {"technique": "volume.raymarch"}}
        s = weft.load_scene(scene, base_dir=os.path.join(ROOT, "data"))
        folder = os.path.dirname(s.path)
        self.assertTrue(os.path.isdir(folder))
        from_dict = s.render(res=(24, 24)).pixels
        self.assertTrue(np.array_equal(from_dict, weft.load_scene(SMOKE).render(res=(24, 24)).pixels))
        self.assertEqual(scene["volumes"][0]["file"], "smoke_small.vdb")  # the caller's dict is not changed
        del s
        self.assertFalse(os.path.exists(folder))
        with self.assertRaisesRegex(weft.Error, "smoke_small.vdb"):
            weft.load_scene(scene, base_dir=self.tmp.name)  # relative to a folder without it


    def test_bad_values_are_refused_in_weft_words(self):
        scene = {"volumes": [{"file": "smoke_small.vdb", "translate": [0, float("nan"), 0]}]}
        with self.assertRaises(weft.Error) as caught:
            weft.load_scene(scene, base_dir=os.path.join(ROOT, "data"))
        self.assertIn("scene['volumes'][0]['translate'][1] is nan", str(caught.exception))
        with self.assertRaises(weft.Error) as caught:
            weft.load_scene({"volumes": [{"procedural": "sphere", "scael": 2}]})
        self.assertIn("the scene dict: unknown key 'scael'", str(caught.exception))
        self.assertNotIn("weft-scene-", str(caught.exception))
        empty = np.zeros((0, 0, 4), np.float32)
        with self.assertRaisesRegex(weft.Error, r"empty \(0x0\)"):
            weft.diff(empty, empty)
        s = weft.load_scene(SMOKE)
        for seed in (2**53 + 1, 2**63):
            with self.assertRaisesRegex(weft.Error, "outside"):
                s.render(res=(8, 8), seed=seed)
        self.assertEqual(s.render(res=(8, 8), seed=2**53).pixels.shape[:2], (8, 8))


    def test_ctrl_c_cancels_a_render_and_raises(self):
        # SIGALRM raising KeyboardInterrupt stands for Ctrl-C. The render asked
        # for takes minutes; it must stop part way, not run to its end and
        # raise after (how soon it stops is bench/cancel_latency.py's).
        def interrupt(signum, frame):
            raise KeyboardInterrupt
        previous = signal.signal(signal.SIGALRM, interrupt)
        s = weft.load_scene(SMOKE)
        fractions = []
        try:
            signal.setitimer(signal.ITIMER_REAL, 0.3)
            with self.assertRaises(KeyboardInterrupt):
                s.render(res=(512, 512), spp=1024, params={"step": 0.05},
                         progress=lambda name, fraction: fractions.append(fraction))
            self.assertLess(max(fractions, default=0.0), 1.0)
        finally:
            signal.setitimer(signal.ITIMER_REAL, 0)
            signal.signal(signal.SIGALRM, previous)
        self.assertEqual(s.render(res=(8, 8)).pixels.shape[:2], (8, 8))  # the scene renders on

    def test_progress_callback_sees_each_pass_end_and_can_cancel(self):
        s = weft.load_scene(SMOKE)
        seen = []
        s.render(res=(64, 48), progress=lambda name, fraction: seen.append((name, fraction)))
        self.assertTrue(seen)
        self.assertTrue(all(0.0 <= f <= 1.0 for _, f in seen))
        self.assertEqual(seen[-1][1], 1.0)
        self.assertTrue(issubclass(weft.Cancelled, weft.Error))
        calls = []
        def stop(name, fraction):  # False stops the render at its first report
            calls.append(fraction)
            return False
        with self.assertRaises(weft.Cancelled):
            s.render(res=(512, 512), spp=1024, params={"step": 0.05}, progress=stop)
        self.assertNotIn(1.0, calls)  # stopped part way

        def fails(name, fraction):
            raise ValueError("from the callback")
        with self.assertRaisesRegex(ValueError, "from the callback"):
            s.render(res=(512, 512), spp=1024, params={"step": 0.05}, progress=fails)
        self.assertEqual(s.render(res=(8, 8)).pixels.shape[:2], (8, 8))  # the scene renders on


if __name__ == "__main__":
    unittest.main()
