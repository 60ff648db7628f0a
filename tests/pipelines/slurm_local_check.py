"""Integration test: a 4-frame, 2-tile render on a single-node Slurm cluster
started on localhost (scripts/slurm-local.sh) equals the same frames
rendered on this machine, bit for bit (weft diff RMSE 0 and weft check ok).
Alongside, an untiled array over a VDB sequence whose frame 2 is not a VDB:
that task fails with its error in its log while frames 1 and 3 render.
One frame is then deleted and resume.py resubmits just that frame.
Fails, with the reason, when the cluster cannot start. WEFT names the weft binary."""

import csv
import os
import shutil
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
WEFT = os.environ.get("WEFT", os.path.join(ROOT, "build", "bin", "weft"))
SCENE = """{"volumes": [{"procedural": "cloud", "resolution": 32}],
 "camera": {"keys": [{"frame": 1, "eye": [0, 0.3, 2.2], "target": [0, 0, 0]},
                     {"frame": 4, "eye": [1.2, 0.5, 1.8], "target": [0, 0, 0]}]},
 "render": {"resolution": [40, 31], "spp": 2, "params": {"jitter": true}}}
"""
TIMEOUT_S = 45


def fail(msg):
    print("slurm_local_check: FAIL: " + msg, file=sys.stderr)
    sys.exit(1)


def run(cmd, env=None, cwd=None):
    return subprocess.run(cmd, capture_output=True, text=True, env=env, cwd=cwd)


def wait_for(job_ids, env, logs):
    deadline = time.time() + TIMEOUT_S
    while time.time() < deadline:
        q = run(["squeue", "-h", "-j", ",".join(job_ids), "-o", "%i %T %r"], env)
        if q.returncode == 0 and not q.stdout.strip():
            return
        time.sleep(0.5)
    fail("jobs %s not done after %d s; squeue: %s; logs: %s" % (job_ids, TIMEOUT_S, q.stdout.strip(), os.listdir(logs)))


def submit(script, args, env, cwd):
    r = run([sys.executable, os.path.join(ROOT, "pipelines", script)] + args, env, cwd)
    if r.returncode != 0:
        fail("%s: %s" % (script, r.stderr.strip() or r.stdout.strip()))
    return [l for l in r.stdout.splitlines() if l.strip().isdigit()]


def check_frames(d, env):
    frames = [os.path.join(d, "farm", "f.%04d.exr" % f) for f in range(1, 5)]
    r = run([WEFT, "check"] + frames)
    if r.returncode != 0:
        logs = "".join(open(os.path.join(d, "logs", n)).read() for n in sorted(os.listdir(os.path.join(d, "logs")))
                       if n.endswith(".log"))
        fail("farm frames incomplete:\n%s\ntask logs:\n%s" % (r.stdout, logs[-3000:]))
    for f in range(1, 5):
        diff = run([WEFT, "diff", frames[f - 1], os.path.join(d, "ref", "f.%04d.exr" % f), "--fail", "0", "--threshold", "0"])
        if diff.returncode != 0:
            fail("frame %d differs from the single-machine render:\n%s" % (f, diff.stdout + diff.stderr))


def check_bad_frame(d):
    seq = run([WEFT, "check"] + [os.path.join(d, "seq", "out.%04d.exr" % f) for f in (1, 2, 3)]).stdout.split("\n")
    if [l.split("\t")[0] for l in seq[:3]] != ["ok", "missing", "ok"]:
        fail("the VDB sequence should give frames 1 and 3 and no frame 2: %r" % seq)
    logs = {n.rsplit("_", 1)[1]: open(os.path.join(d, "badlogs", n)).read() for n in os.listdir(os.path.join(d, "badlogs"))
            if n.endswith(".log")}
    if "weft: error:" not in logs.get("2.log", "") or "smoke.0002.vdb" not in logs.get("2.log", ""):
        fail("frame 2's task log should hold its error naming the file: %r" % logs.get("2.log"))
    if logs.get("1.log", "x") or logs.get("3.log", "x"):
        fail("frames 1 and 3 should render silently: %r" % logs)


SWEEP = ["builtin:sphere", "--res", "12x8", "--technique", "volume.raymarch", "--vary", "step=0.5,1", "--vary", "jitter=false,true",
         "--reference", "auto", "--no-plot"]


def check_sweep(d):
    """The farm sweep's tables equal a one-process sweep's, times aside."""
    one = run([WEFT, "sweep"] + SWEEP + ["-o", os.path.join(d, "sweep-one")])
    if one.returncode != 0:
        fail("one-process sweep: " + one.stderr)

    def rows(folder):
        with open(os.path.join(d, folder, "sweep.csv")) as f:
            return [{k: v for k, v in r.items() if not k.endswith("_ms") and k != "front_time"} for r in csv.DictReader(f)]
    if not os.path.exists(os.path.join(d, "sweep-farm", "sweep.csv")):
        fail("the farm sweep wrote no sweep.csv; logs: %r" % os.listdir(os.path.join(d, "sweeplogs")))
    if rows("sweep-farm") != rows("sweep-one"):
        fail("the farm sweep's table differs from the one-process sweep's")


def main():
    d = tempfile.mkdtemp(prefix="weft-slurm-test-")
    os.chmod(d, 0o755)  # munged runs as user munge and must reach its folder inside
    cluster = os.path.join(d, "cluster")
    started = False
    try:
        start = run(["bash", os.path.join(ROOT, "scripts", "slurm-local.sh"), "start", cluster])
        if start.returncode != 0:
            fail("the local Slurm cluster did not start: " + (start.stderr.strip() or start.stdout.strip()))
        started = True
        env = dict(os.environ, SLURM_CONF=os.path.join(cluster, "slurm.conf"), WEFT=WEFT)
        with open(os.path.join(d, "scene.json"), "w") as f:
            f.write(SCENE)
        os.makedirs(os.path.join(d, "ref"))
        ref = run([WEFT, "render", "scene.json", "--frames", "1-4", "-o", "ref/f.#.exr"], cwd=d)
        if ref.returncode != 0:
            fail("reference render: " + ref.stderr)
        common = ["--frames", "1-4", "-o", "farm/f.#.exr", "--tiles", "2", "--logs", "logs", "--name", "test",
                  "--", "scene.json"]
        ids = submit("submit_slurm.py", common, env, d)
        if len(ids) != 3:
            fail("expected 3 job ids (2 tile arrays, 1 merge array), got %r" % ids)
        os.makedirs(os.path.join(d, "seq"))
        for f in (1, 3):
            shutil.copy(os.path.join(ROOT, "data", "smoke_small.vdb"), os.path.join(d, "seq", "smoke.%04d.vdb" % f))
        with open(os.path.join(d, "seq", "smoke.0002.vdb"), "w") as f:
            f.write("not a vdb")
        bad_ids = submit("submit_slurm.py", ["--frames", "1-3", "-o", "seq/out.#.exr", "--logs", "badlogs", "--name", "seq",
                                             "--", "seq/smoke.#.vdb", "--res", "16x16"], env, d)
        sweep_ids = submit("sweep.py", ["-o", "sweep-farm", "--logs", "sweeplogs", "--"] + SWEEP, env, d)
        if len(sweep_ids) != 3:
            fail("expected 3 sweep job ids (prepare, runs, merge), got %r" % sweep_ids)
        wait_for(ids + bad_ids + sweep_ids, env, os.path.join(d, "logs"))
        check_frames(d, env)
        check_bad_frame(d)
        check_sweep(d)
        logs = sorted(n for n in os.listdir(os.path.join(d, "logs")) if n.endswith(".log"))
        if len(logs) != 12:
            fail("expected 12 task logs (4 frames x 2 tiles + 4 merges), got %r" % logs)
        # A lost frame: resume finds it and resubmits only that frame.
        os.remove(os.path.join(d, "farm", "f.0003.exr"))
        ids = submit("resume.py", common, env, d)
        wait_for(ids, env, os.path.join(d, "logs"))
        check_frames(d, env)
        new_logs = sorted(n for n in os.listdir(os.path.join(d, "logs")) if n.endswith(".log") and n not in logs)
        if len(new_logs) != 3 or not all(n.endswith("_3.log") for n in new_logs):
            fail("resume should run frame 3 only (2 tiles + merge), ran %r" % new_logs)
        print("slurm_local_check: ok (4 frames x 2 tiles on Slurm == local renders; resume redid frame 3 only; "
              "a 4-run sweep as prepare, array and merge == the one-process sweep)")
    finally:
        if started:
            stop = run(["bash", os.path.join(ROOT, "scripts", "slurm-local.sh"), "stop", cluster])
            if stop.returncode != 0:
                print("slurm_local_check: stopping the cluster: " + stop.stderr, file=sys.stderr)
        shutil.rmtree(d, ignore_errors=True)


if __name__ == "__main__":
    main()
