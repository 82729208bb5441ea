"""What a device bridge does to `haptic_sim serve` over a pipe, shared by the stages that drive
it in wall-clock time: start it and wait for "haptic_sim: ready", keep a frame's due instant, and
end the session (the served artifact, or the server's last error line)."""
import os
import subprocess
import time

from pipeline.artifacts import read_artifact
from pipeline.paths import ROOT
from pipeline.stages.stability_common import tool_path


def start_serve(cfg_path, out_path):
    """`haptic_sim serve` on a pipe, returned once it says it is set up (as a bridge waits)."""
    proc = subprocess.Popen([str(tool_path("haptic_sim")), "serve", "--config", str(cfg_path), "--out", str(out_path)],
                            cwd=ROOT, stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True, bufsize=1, env=dict(os.environ, OMP_NUM_THREADS="1"))
    ready = proc.stderr.readline()
    if "haptic_sim: ready" not in ready:
        proc.kill()
        raise RuntimeError(f"haptic_sim serve did not get ready: {ready.strip() or proc.stderr.read().strip()}")
    return proc


def wait_until(due):
    """Sleeps most of the wait to `due` (time.perf_counter()), spins the last 0.2 ms."""
    while True:
        ahead = due - time.perf_counter()
        if ahead <= 0:
            return
        if ahead > 2e-4:
            time.sleep(ahead - 2e-4)


def finish_serve(proc, out_path):
    """Closes the session and returns the served artifact's payload."""
    proc.stdin.close()
    err = proc.stderr.read()
    code = proc.wait()
    if code != 0:
        lines = [l for l in err.splitlines() if l.strip()]
        raise RuntimeError(f"haptic_sim serve failed (exit {code}): {lines[-1] if lines else 'no message'}")
    return read_artifact(out_path)["payload"]
