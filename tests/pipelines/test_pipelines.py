"""Tests of the pipeline scripts (pipelines/): frame ranges and names, the
sbatch scripts of submit_slurm.py (dry run, and its task lines run here),
resume.py on a folder with missing, corrupt and truncated frames, sweep.py's
CSV. WEFT names the weft binary (ctest sets it)."""

import csv
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
PIPELINES = os.path.join(ROOT, "pipelines")
sys.path.insert(0, PIPELINES)
import weftpipe  # noqa: E402

WEFT = os.environ.get("WEFT", os.path.join(ROOT, "build", "bin", "weft"))
PY = sys.executable


def script(name, *args, cwd=None):
    return subprocess.run([PY, os.path.join(PIPELINES, name)] + list(args), capture_output=True, text=True, cwd=cwd,
                          env=dict(os.environ, WEFT=WEFT))


def weft(*args, cwd=None):
    return subprocess.run([WEFT] + list(args), capture_output=True, text=True, cwd=cwd)


class FrameNames(unittest.TestCase):
    def test_ranges_match_weft(self):
        self.assertEqual(weftpipe.parse_frames("1001-1010x3"), [1001, 1004, 1007, 1010])
        self.assertEqual(weftpipe.parse_frames("1,3,5-7"), [1, 3, 5, 6, 7])
        self.assertEqual(weftpipe.parse_frames("-5--3"), [-5, -4, -3])
        self.assertEqual(weftpipe.parse_frames("5-1x2"), [5, 3, 1])
        for bad in ["", "1-", "1-5x0", "1,,2", "a", "1-3,2"]:
            with self.assertRaises(weftpipe.PipelineError):
                weftpipe.parse_frames(bad)

    def test_padding_matches_weft(self):
        for name, frame in [("o.#.exr", 42), ("o.@@@.exr", 7), ("o.##.exr", 3), ("o.#.exr", -5), ("o.%03d.exr", 9)]:
            ours = weftpipe.expand(name, frame)
            with tempfile.TemporaryDirectory() as d:
                r = weft("render", "builtin:sphere", "--res", "4x4", "--frames", str(frame), "-o", os.path.join(d, name))
                self.assertEqual(r.returncode, 0, r.stderr)
                self.assertEqual(os.listdir(d), [ours])

    def test_array_spec(self):
        self.assertEqual(weftpipe.slurm_array_spec(list(range(1001, 1101, 2))), "1001-1099:2")
        self.assertEqual(weftpipe.slurm_array_spec([1, 3, 5, 6, 7, 8, 9]), "1-5:2,6-9")
        self.assertEqual(weftpipe.slurm_array_spec([2, 4, 5]), "2,4-5")
        self.assertEqual(weftpipe.slurm_array_spec([1, 2, 4, 6, 7]), "1-2,4,6-7")
        self.assertEqual(weftpipe.slurm_array_spec([7]), "7")


class SubmitDryRun(unittest.TestCase):
    def test_tiled_run_prints_tile_arrays_and_a_dependent_merge_array(self):
        r = script("submit_slurm.py", "--frames", "1001-1004", "--tiles", "2", "-o", "out/shot.#.exr", "--name", "shot",
                   "--logs", "logs", "--cpus-per-task", "2", "--dry-run", "--", "scene.json", "--res", "64x48")
        self.assertEqual(r.returncode, 0, r.stderr)
        out = r.stdout
        self.assertEqual(out.count("#!/bin/bash"), 3)
        self.assertEqual(out.count("#SBATCH --array=1001-1004\n"), 3)
        self.assertIn("#SBATCH --output=logs/shot.t1of2_%A_%a.log", out)
        self.assertIn("#SBATCH --output=logs/shot.merge_%A_%a.log", out)
        self.assertIn("#SBATCH --dependency=aftercorr:<job id of shot.t1of2>:<job id of shot.t2of2>", out)
        self.assertIn("render scene.json --res 64x48 --frames \"$frame\" -o 'out/tiles/shot.#.t2of2.exr' --tile 2/2", out)
        self.assertIn("merge 'out/tiles/shot.#.t1of2.exr' 'out/tiles/shot.#.t2of2.exr' --frame \"$frame\" -o 'out/shot.#.exr'", out)
        self.assertEqual(out.count("#SBATCH --kill-on-invalid-dep=yes"), 1)

    def test_untiled_run_is_one_array_and_its_task_line_renders_the_frame(self):
        with tempfile.TemporaryDirectory() as d:
            r = script("submit_slurm.py", "--frames", "3,5-6", "-o", "f.@@.exr", "--logs", "logs", "--max-running", "2",
                       "--dry-run", "--weft", WEFT, "--", "builtin:sphere", "--res", "8x8", cwd=d)
            self.assertEqual(r.returncode, 0, r.stderr)
            self.assertEqual(r.stdout.count("#!/bin/bash"), 1)
            self.assertIn("#SBATCH --array=3,5-6%2", r.stdout)
            body = r.stdout.split("\n", 1)[1]  # the script after its "# ----" title
            run = subprocess.run(["bash", "-c", body], cwd=d, capture_output=True, text=True,
                                 env=dict(os.environ, SLURM_ARRAY_TASK_ID="5", SLURM_CPUS_PER_TASK="1"))
            self.assertEqual(run.returncode, 0, run.stderr)
            self.assertEqual(sorted(os.listdir(d)), ["f.05.exr"])

    def test_negative_frames_and_frames_past_max_array_size_are_offset_indices(self):
        for frames, extra, array, index, made in [("-2--1,1", [], "0-1,3", "3", "f.0001.exr"),
                                                  ("1001-1005x2", ["--max-array-size", "1001"], "0-4:2", "2", "f.1003.exr")]:
            with tempfile.TemporaryDirectory() as d:
                r = script("submit_slurm.py", "--frames=" + frames, "-o", "f.#.exr", "--dry-run", "--weft", WEFT, *extra,
                           "--", "builtin:sphere", "--res", "8x8", cwd=d)
                self.assertEqual(r.returncode, 0, r.stderr)
                self.assertIn("#SBATCH --array=%s\n" % array, r.stdout)
                body = r.stdout.split("\n", 1)[1]
                run = subprocess.run(["bash", "-c", body], cwd=d, capture_output=True, text=True,
                                     env=dict(os.environ, SLURM_ARRAY_TASK_ID=index, SLURM_CPUS_PER_TASK="1"))
                self.assertEqual(run.returncode, 0, run.stderr)
                self.assertEqual(sorted(os.listdir(d)), [made])
        with tempfile.TemporaryDirectory() as d:  # the negative frame's name: the sign counts in the width
            r = script("submit_slurm.py", "--frames=-2", "-o", "f.#.exr", "--dry-run", "--weft", WEFT, "--", "builtin:sphere",
                       "--res", "8x8", cwd=d)
            run = subprocess.run(["bash", "-c", r.stdout.split("\n", 1)[1]], cwd=d, capture_output=True, text=True,
                                 env=dict(os.environ, SLURM_ARRAY_TASK_ID="0", SLURM_CPUS_PER_TASK="1"))
            self.assertEqual(run.returncode, 0, run.stderr)
            self.assertEqual(sorted(os.listdir(d)), ["f.-002.exr"])

    def test_ranges_wider_than_max_array_size_and_names_without_a_frame_are_refused(self):
        r = script("submit_slurm.py", "--frames", "1-20", "-o", "o.#.exr", "--dry-run", "--max-array-size", "10", "--",
                   "builtin:cloud")
        self.assertEqual(r.returncode, 1)
        self.assertIn("frames 1 to 20 span more than MaxArraySize 10", r.stderr)
        self.assertEqual(r.stderr.count("\n"), 1, r.stderr)
        r = script("submit_slurm.py", "--frames", "1-2", "-o", "o.exr", "--dry-run", "--", "builtin:cloud")
        self.assertIn("has no frame number", r.stderr)


class Resume(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix="weft-resume-")
        self.out = os.path.join(self.dir, "f.#.exr")
        r = weft("render", "builtin:sphere", "--res", "8x8", "--frames", "1-6", "-o", self.out)
        self.assertEqual(r.returncode, 0, r.stderr)
        os.remove(weftpipe.expand(self.out, 2))                       # missing
        with open(weftpipe.expand(self.out, 4), "r+b") as f:          # truncated
            f.truncate(os.path.getsize(f.name) // 2)
        r = weft("render", "builtin:sphere", "--res", "8x8", "exposure", "0", "write", weftpipe.expand(self.out, 5))
        self.assertEqual(r.returncode, 0, r.stderr)
        shutil.copy(weftpipe.expand(self.out, 5), weftpipe.expand(self.out, 5) + ".keep")
        subprocess.run(["oiiotool", weftpipe.expand(self.out, 5) + ".keep", "--eraseattrib", "weft:complete", "-o",
                        weftpipe.expand(self.out, 5)], check=True)
        os.remove(weftpipe.expand(self.out, 5) + ".keep")
        open(os.path.join(self.dir, ".f.0003.weft-tmp-99999.exr"), "w").close()  # left by a killed task

    def tearDown(self):
        shutil.rmtree(self.dir)

    def stamps(self):
        return {f: os.stat(weftpipe.expand(self.out, f)).st_mtime_ns for f in range(1, 7)
                if os.path.exists(weftpipe.expand(self.out, f))}

    def resume(self, *extra):
        return script("resume.py", "--frames", "1-6", "-o", self.out, "--logs", os.path.join(self.dir, "logs"), *extra,
                      "--", "builtin:sphere", "--res", "8x8")

    def test_finds_missing_truncated_and_unmarked_frames(self):
        r = self.resume("--dry-run")
        self.assertEqual(r.returncode, 0, r.stderr)
        lines = r.stdout.splitlines()
        self.assertEqual([l.split(":")[0] for l in lines if l.startswith("frame ")], ["frame 2", "frame 4", "frame 5"])
        self.assertIn("frame 2: missing", lines)
        self.assertTrue(any(l.startswith("frame 4: corrupt") for l in lines))
        self.assertIn("frame 5: corrupt: no weft:complete attribute", lines)
        self.assertIn("resume: 3 of 6 frames to render", lines)
        self.assertTrue(any(l.startswith("resume: 1 temporary files from interrupted writes") for l in lines), lines)
        self.assertIn("#SBATCH --array=2,4-5", r.stdout)

    @unittest.skipIf(os.environ.get("WEFT_PYTHON_MODULE") == "0", "this build has no Python module (a sanitized build)")
    def test_the_module_and_the_command_say_the_same_of_each_frame(self):
        self.assertIsNotNone(weftpipe.weft_module(WEFT), "the weft module beside %s does not load" % WEFT)
        paths = [weftpipe.expand(self.out, f) for f in range(1, 7)]
        by_module = weftpipe.frame_status(WEFT, paths)
        self.assertEqual(by_module, weftpipe._frame_status_from_command(WEFT, paths))
        self.assertEqual([by_module[p].split(":")[0] for p in paths], ["ok", "missing", "ok", "corrupt", "corrupt", "ok"])

    def test_renders_only_the_frames_that_are_not_complete(self):
        before = self.stamps()
        r = self.resume("--local")
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        after = self.stamps()
        for f in (1, 3, 6):
            self.assertEqual(after[f], before[f], "frame %d was rendered again" % f)
        for f in (2, 4, 5):
            self.assertNotEqual(after.get(f), before.get(f), "frame %d was not rendered" % f)
        self.assertEqual(sorted(os.listdir(os.path.join(self.dir, "logs"))), ["weft_2.log", "weft_4.log", "weft_5.log"])
        again = self.resume("--local")
        self.assertIn("resume: 0 of 6 frames to render", again.stdout)

    def test_tiled_resume_renders_and_merges_the_missing_frames(self):
        r = self.resume("--local", "--tiles", "3")
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        check = weft("check", *[weftpipe.expand(self.out, f) for f in range(1, 7)])
        self.assertEqual(check.returncode, 0, check.stdout)
        ref = os.path.join(self.dir, "ref.exr")
        weft("render", "builtin:sphere", "--res", "8x8", "-o", ref)
        diff = weft("diff", weftpipe.expand(self.out, 2), ref, "--fail", "0")
        self.assertEqual(diff.returncode, 0, diff.stdout)


class Sweep(unittest.TestCase):
    SWEEP = ["builtin:sphere", "--res", "8x6", "--technique", "volume.raymarch", "--vary", "step=0.5,1", "--vary", "spp=1,2",
             "--reference", "auto", "--no-plot"]

    def test_local_tasks_merge_into_the_sweeps_tables(self):
        with tempfile.TemporaryDirectory() as d:
            r = script("sweep.py", "--local", "-o", d, "--", *self.SWEEP)
            self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
            with open(os.path.join(d, "sweep.csv")) as f:
                rows = list(csv.DictReader(f))
            self.assertEqual([(x["step"], x["spp"]) for x in rows], [("0.5", "1"), ("0.5", "2"), ("1", "1"), ("1", "2")])
            for x in rows:
                self.assertEqual(int(x["counters.rays.camera"]), 48 * int(x["spp"]))
                self.assertGreaterEqual(float(x["rmse"]), 0)
            samples = {(x["step"], x["spp"]): int(x["samples"]) for x in rows}
            self.assertGreater(samples[("0.5", "1")], samples[("1", "1")])
            self.assertEqual(len(os.listdir(os.path.join(d, "runs"))), 4)

    def test_slurm_jobs_are_chained(self):
        with tempfile.TemporaryDirectory() as d:
            r = script("sweep.py", "--dry-run", "--max-running", "2", "-o", d, "--", *self.SWEEP)
            self.assertEqual(r.returncode, 0, r.stderr)
            self.assertIn("--prepare", r.stdout)
            self.assertIn("#SBATCH --array=1-4%2", r.stdout)
            self.assertIn('--run "$SLURM_ARRAY_TASK_ID"', r.stdout)
            self.assertIn("#SBATCH --dependency=afterok:RUNS", r.stdout)
            self.assertIn("sweep --merge -o", r.stdout)

    def test_a_bad_vary_fails_before_anything_is_submitted(self):
        with tempfile.TemporaryDirectory() as d:
            out = os.path.join(d, "s")
            r = script("sweep.py", "--dry-run", "-o", out, "--", "builtin:sphere", "--vary", "step=0.5,-1", "--reference", "auto")
            self.assertEqual(r.returncode, 1)
            self.assertIn("step", r.stderr)
            self.assertEqual(len(r.stderr.strip().splitlines()), 1, r.stderr)
            self.assertFalse(os.path.exists(out))


if __name__ == "__main__":
    unittest.main()
