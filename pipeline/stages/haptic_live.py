"""A live scene while it changes: `haptic_sim serve` driven over a pipe by this process, a client
pacing one tip position per frame in wall-clock time, while the tool sweeps across the organ's
upper surface (several region changes), presses up and down, and the model makes scheduled cuts
(one beside the tool, one far from it). The same session is served once per region-building
scheme (`regions.build`: "background", the region built beside the frames; "inline", the
previous scheme, built inside the frame), and the whole model replays the same frames offline,
the reference for the force error.

Pipeline stage (mark it "exclusive": true):
    {"python": "pipeline.stages.haptic_live", "exclusive": true,
     "config": {"scene": {a haptic_sim config with "model": {"mesh": "@mesh", ...} and "regions"},
                "path": {"start": [x, y], "end": [x, y], "depth": m, "press_depth": m, "press_period": s},
                "cuts": [{"time": s, "where": "tool" | "far", "length": m, "depth": m}],
                "seconds": 15, "rate": 1000, "builds": ["background", "inline"]}}

The tip follows the upper surface (the highest boundary node within 1 cm in plan, smoothed) from
`start` to `end` over the session, `depth` below it plus a press of `press_depth` every
`press_period`. A cut "tool" is a vertical blade 1.5 cm beside the tip at its time, "far" one at
the boundary node farthest from the path. The client keeps the schedule (frame k sent at
t0 + k / rate, at once if the previous answer came late) and records per frame the round trip and
the instant each answer arrived; os.getloadavg() is recorded before and after each served run.
"""
TOOLS = ("haptic_sim",)

import json
import os
import subprocess
import tempfile
import time
from pathlib import Path

import numpy as np

from pipeline.artifacts import read_artifact, write_artifact
from pipeline.bench import cpu_description
from pipeline.paths import ROOT
from pipeline.stages.paced_client import finish_serve, start_serve, wait_until
from pipeline.stages.stability_common import read_payload, tool_hashes, tool_path

SCHEMA = "haptic_live"
TOOL = "pipeline.stages.haptic_live"


class LiveConfigError(ValueError):
    pass


def surface_path(X, surface, cfg, frames, rate):
    """Tip positions per frame: along the upper surface from start to end, pressed."""
    top = X[surface]
    start, end = np.array(cfg["start"], float), np.array(cfg["end"], float)
    samples = []
    for s in np.linspace(0.0, 1.0, 41):
        xy = start + s * (end - start)
        near = np.linalg.norm(top[:, :2] - xy, axis=1) < 0.01
        if not near.any():
            raise LiveConfigError(f"/path: no boundary node within 1 cm (in plan) of {xy.tolist()}")
        samples.append(np.array([xy[0], xy[1], top[near, 2].max()]))
    samples = np.array(samples)
    # Smoothed (a moving average over 5 samples) so that the path does not follow every facet.
    kernel = np.ones(5) / 5
    padded = np.vstack([samples[:1].repeat(2, 0), samples, samples[-1:].repeat(2, 0)])
    smooth = np.column_stack([np.convolve(padded[:, c], kernel, mode="valid") for c in range(3)])
    t = np.arange(frames) / rate
    s = np.clip(t / t[-1], 0, 1) * (len(smooth) - 1)
    base = np.column_stack([np.interp(s, np.arange(len(smooth)), smooth[:, c]) for c in range(3)])
    ramp = np.minimum(t / 0.3, 1.0)
    depth = cfg["depth"] * ramp + cfg["press_depth"] * np.sin(np.pi * t / cfg["press_period"]) ** 2
    base[:, 2] -= depth
    return base


def blade(X, surface, centre, length, depth):
    """A vertical blade edge from `depth` below to 1 cm above the surface at `centre`, drawn
    `length` along x."""
    top = X[surface]
    z = top[np.argmin(np.linalg.norm(top[:, :2] - centre[:2], axis=1)), 2]
    a = [centre[0] - length / 2, centre[1], z - depth]
    b = [centre[0] - length / 2, centre[1], z + 0.01]
    return {"from": [a, b], "to": [[a[0] + length, a[1], a[2]], [b[0] + length, b[1], b[2]]]}


def serve(scene, positions, rate):
    frames = len(positions)
    round_trip, answered_at, forces = np.zeros(frames), np.zeros(frames), np.full((frames, 3), np.nan)
    with tempfile.TemporaryDirectory(prefix="haptic_live_") as tmp:
        cfg_path, out_path = Path(tmp) / "scene.json", Path(tmp) / "served.json"
        cfg_path.write_text(json.dumps(dict(scene, realtime={"source": "stdin", "max_frames": 0, "announce": True})))
        setup_start = time.perf_counter()
        proc = start_serve(cfg_path, out_path)
        setup_seconds = time.perf_counter() - setup_start
        load_before = os.getloadavg()
        period = 1.0 / rate
        start = time.perf_counter()
        for k in range(frames):
            wait_until(start + k * period)
            p = positions[k]
            sent = time.perf_counter()
            proc.stdin.write(f"{(k + 1) * period:.6f} {p[0]:.9g} {p[1]:.9g} {p[2]:.9g}\n")
            proc.stdin.flush()
            answer = proc.stdout.readline()
            now = time.perf_counter()
            round_trip[k], answered_at[k] = now - sent, now - start
            if not answer:
                break
            forces[k] = [float(v) for v in answer.split()[1:4]]
        load_after = os.getloadavg()
        served = finish_serve(proc, out_path)
    return {"round_trip_seconds": round_trip.tolist(), "answered_at_seconds": answered_at.tolist(),
            "force": forces.tolist(), "setup_seconds_to_ready": setup_seconds,
            "load_before": list(load_before), "load_after": list(load_after),
            "timing": served["timing"], "regions": served["regions"], "events": served["events"],
            "cuts": served["cuts"], "substeps": served["substeps"]}


def run(ctx):
    cfg = ctx.config
    seconds, rate = cfg.get("seconds", 15), cfg.get("rate", 1000)
    if not (isinstance(seconds, (int, float)) and 0 < seconds <= 120):
        raise LiveConfigError("/seconds: expected a duration in (0, 120] s")
    if not (isinstance(rate, (int, float)) and 1 <= rate <= 10000):
        raise LiveConfigError("/rate: expected a frame rate in [1, 10000] Hz")
    mesh = read_payload(cfg["scene"]["model"]["mesh"])
    X = np.array(mesh["nodes"])
    surface = np.unique(np.array(mesh["boundary"]).ravel())
    frames = int(round(seconds * rate))
    positions = surface_path(X, surface, cfg["path"], frames, rate)
    cuts = []
    for c in cfg.get("cuts", []):
        k = min(int(round(c["time"] * rate)), frames - 1)
        if c["where"] == "tool":
            centre = positions[k] + np.array([0.0, 0.015, 0.0])
        else:
            d = np.min(np.linalg.norm(X[surface][:, None, :2] - positions[None, ::100, :2], axis=2), axis=1)
            centre = X[surface[np.argmax(d)]]
        cuts.append(dict(blade(X, surface, centre, c["length"], c["depth"]), time=c["time"], mode="remove"))
    scene = json.loads(json.dumps(cfg["scene"]))
    scene["model"]["cuts"] = cuts
    scene["frames"] = frames
    runs = {}
    for build in cfg.get("builds", ["background", "inline"]):
        s = json.loads(json.dumps(scene))
        s["regions"]["build"] = build
        s["input"] = {"kind": "press", "start": positions[0].tolist(), "direction": [0, 0, -1], "depth": cfg["path"]["depth"],
                      "ramp_time": 0.3}  # the served input's start: where the region is prepared
        runs[build] = serve(s, positions, rate)
    # The whole model replays the same frames offline (the recorded positions, frame k at k / rate).
    with tempfile.TemporaryDirectory(prefix="haptic_live_whole_") as tmp:
        path_file = Path(tmp) / "path.txt"
        path_file.write_text("".join(f"{k / rate:.9g} {p[0]:.9g} {p[1]:.9g} {p[2]:.9g}\n" for k, p in enumerate(positions)))
        whole = json.loads(json.dumps(scene))
        whole.pop("regions", None)
        whole["input"] = {"kind": "recorded", "path": str(path_file)}
        cfg_path, out_path = Path(tmp) / "whole.json", Path(tmp) / "whole_out.json"
        cfg_path.write_text(json.dumps(whole))
        t0 = time.perf_counter()
        done = subprocess.run([str(tool_path("haptic_sim")), "run", "--config", str(cfg_path), "--out", str(out_path)],
                              cwd=ROOT, capture_output=True, text=True, env=dict(os.environ, OMP_NUM_THREADS="1"))
        if done.returncode != 0:
            raise RuntimeError(f"haptic_sim run (whole model) failed: {done.stderr.strip().splitlines()[-1:]}")
        w = read_artifact(out_path)["payload"]
        whole_run = {"force": w["force"], "events": w["events"], "cuts": w["cuts"], "timing": w["timing"],
                     "seconds": time.perf_counter() - t0}
    payload = {"frames": frames, "rate": rate, "seconds": seconds, "positions": positions.tolist(), "cuts": cuts,
               "served": runs, "whole": whole_run, "cpu": cpu_description(), "cores": os.cpu_count(),
               "tools": tool_hashes(TOOLS)}
    write_artifact(ctx.out_path, SCHEMA, 1, TOOL, cfg, payload, inputs=[cfg["scene"]["model"]["mesh"]])
