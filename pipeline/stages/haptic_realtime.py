"""The real-time loop as a device drives it: `haptic_sim serve` fed one tip position per frame
at the haptic rate by a paced client on a real pipe (stdin/stdout), for a wall-clock duration.
Per frame the client records the round trip (position sent -> force received), the latency a
device bridge sees; the served artifact gives the compute time per frame beside it.

Pipeline stage (mark it "exclusive": true):
    {"python": "pipeline.stages.haptic_realtime", "exclusive": true,
     "config": {"scene": {... a haptic_sim config with "model": {"mesh": "@mesh", ...} ...},
                "press": {"start": [x, y, z], "depth": m, "ramp_time": s},
                "seconds": 60, "rate": 1000}}

The client presses straight down (-z) from the boundary node nearest to `start` to `depth` over
`ramp_time`, then holds. It keeps the schedule: frame k is sent at t0 + k / rate, or at once if the
previous answer came late, so late frames show as such. The artifact ("haptic_realtime" v1) keeps
every round trip (s), the served payload's timing and regions blocks, the CPU, the binary's
sha256 and the "machine" block of pipeline.stages.machine_load (load, CPU steal and a calibration
kernel around the run; a disturbed run is served once more, then flagged).
"""
TOOLS = ("haptic_sim",)

import json
import tempfile
import time
from pathlib import Path

import numpy as np

from pipeline.artifacts import write_artifact
from pipeline.bench import cpu_description
from pipeline.stages.machine_load import measure
from pipeline.stages.paced_client import finish_serve, start_serve, wait_until
from pipeline.stages.stability_common import read_payload, tool_hashes

SCHEMA = "haptic_realtime"
TOOL = "pipeline.stages.haptic_realtime"


class RealtimeConfigError(ValueError):
    pass


def run(ctx):
    cfg = ctx.config
    seconds, rate = cfg.get("seconds", 60), cfg.get("rate", 1000)
    if not (isinstance(seconds, (int, float)) and 0 < seconds <= 600):
        raise RealtimeConfigError("/seconds: expected a duration in (0, 600] s")
    if not (isinstance(rate, (int, float)) and 1 <= rate <= 10000):
        raise RealtimeConfigError("/rate: expected a frame rate in [1, 10000] Hz")
    press = cfg["press"]
    mesh = read_payload(cfg["scene"]["model"]["mesh"])
    X = np.array(mesh["nodes"])
    surface = np.unique(np.array(mesh["boundary"]).ravel())
    origin = X[surface[np.argmin(np.linalg.norm(X[surface] - np.array(press["start"]), axis=1))]]
    frames = int(round(seconds * rate))
    scene = dict(cfg["scene"], realtime={"source": "stdin", "max_frames": 0, "announce": True})
    (round_trip, served), machine = measure(lambda: _serve(scene, origin, frames, rate, press), ctx.log)
    payload = {"frames": frames, "rate": rate, "seconds": seconds, "round_trip_seconds": round_trip.tolist(),
               "timing": served["timing"], "regions": served["regions"], "solver": served["solver"],
               "model": served["model"], "substeps": served["substeps"], "events": len(served["events"]),
               "peak_force": float(np.linalg.norm(np.array(served["force"]), axis=1).max()),
               "cpu": cpu_description(), "tools": tool_hashes(TOOLS), "machine": machine}
    write_artifact(ctx.out_path, SCHEMA, 1, TOOL, cfg, payload, inputs=[cfg["scene"]["model"]["mesh"]])


def _serve(scene, origin, frames, rate, press):
    """One served run: (round trip per frame in s, the served artifact's payload)."""
    round_trip = np.zeros(frames)
    with tempfile.TemporaryDirectory(prefix="haptic_realtime_") as tmp:
        cfg_path, out_path = Path(tmp) / "scene.json", Path(tmp) / "served.json"
        cfg_path.write_text(json.dumps(scene))
        # The device's clock starts once the scene says it is set up (model, and the region at
        # the press's start), as a bridge would wait for it.
        proc = start_serve(cfg_path, out_path)
        period = 1.0 / rate
        start = time.perf_counter()
        for k in range(frames):
            wait_until(start + k * period)
            t = (k + 1) * period
            depth = press["depth"] * min(t / press["ramp_time"], 1.0)
            sent = time.perf_counter()
            proc.stdin.write(f"{t:.6f} {origin[0]:.9g} {origin[1]:.9g} {origin[2] - depth:.9g}\n")
            proc.stdin.flush()
            answer = proc.stdout.readline()
            round_trip[k] = time.perf_counter() - sent
            if not answer:
                break
        served = finish_serve(proc, out_path)
    return round_trip, served
