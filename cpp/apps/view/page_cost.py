"""What a page attached to haptic_sim view costs its physics loop: the same scene run for the same
number of frames with no client, with the C++ bridge (cpp/apps/examples/view_bridge.cpp: samples
at 60 Hz and states at up to 60 Hz over the socket, nothing drawn) and with the page open in
headless Chromium (pointer over the organ, not pressing: the same work per frame), alternated,
each run's frame compute times from its artifact. Writes a Markdown table (stdout, or --out).
  /usr/bin/python3 cpp/apps/view/page_cost.py --config scene.json --frames 15000 --repeats 2 --out table.md
"""
import argparse
import json
import os
import platform
import re
import shutil
import statistics
import subprocess
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[3]
BIN = ROOT / "build" / "bin"


def hover_lines(config, frames):
    """The tip held 5 mm above the input's start point, at 60 Hz, for the run's duration."""
    start = json.loads(Path(config).read_text())["input"]["start"]
    return "".join(f"{k / 60:.6f} {start[0]} {start[1]} {start[2] + 0.005}\n" for k in range(int(frames / 1000 * 60)))


def run(config, frames, page, work):
    out = work / "view.json"
    view = subprocess.Popen([str(BIN / "haptic_sim"), "view", "--config", str(config), "--port", "0",
                             "--frames", str(frames), "--out", str(out)], stderr=subprocess.PIPE, text=True)
    port = int(re.search(r":(\d+)/", view.stderr.readline()).group(1))
    client = None
    if page == "bridge":
        client = subprocess.Popen([str(BIN / "view_bridge"), "--port", str(port), "--leave", "--hold", "2"],
                                  stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
        client.stdin.write(hover_lines(config, frames))
        client.stdin.close()
    elif page:
        env = dict(os.environ, VIEW_URL=f"http://127.0.0.1:{port}/", CHROMIUM=shutil.which("chromium"),
                   WEB_DIR=str(ROOT / "build" / "web"))
        client = subprocess.Popen(["node", str(ROOT / "tests" / "browser" / "view_idle.mjs")], env=env,
                                  stdout=subprocess.PIPE, text=True)
    rc = view.wait()
    err = view.stderr.read()
    states = None
    if page == "bridge":
        states = len(client.stdout.read().splitlines())
        client.wait(timeout=60)
    elif client:
        states = json.loads(client.communicate(timeout=60)[0].strip().splitlines()[-1])["states"]
    assert rc == 0, err
    p = json.loads(out.read_text())["payload"]
    t = p["timing"]
    return {"page": page, "mean": t.get("frame_seconds_mean"), "p50": t["frame_seconds_p50"],
            "p99": t["frame_seconds_p99"], "max": t["frame_seconds_max"], "misses": t["deadline_misses"],
            "frames": p["frames"], "states": states}


def scene_words(config, frames):
    """The scene in words, read from the config the runs used."""
    c = json.loads(Path(config).read_text())
    m, probe = c["model"], c.get("probe", {})
    mat = m.get("material", {})
    regions = "linked regions" if "regions" in c else "the whole model"
    return (f"Scene `{config}`: mesh `{m['mesh']}`, material {mat.get('model', 'neo_hookean_paper')} "
            f"E = {mat.get('E')} Pa, ν = {mat.get('nu')}, {regions}, probe spring {probe.get('stiffness')} N/m "
            f"({probe.get('contact', 'grasp')}); {frames} frames at 1 kHz per run, the tip held 5 mm off the "
            "surface (the same work every frame); clients in turn: none, the C++ device bridge (`view_bridge`: "
            "samples at 60 Hz, states at up to 60 Hz, nothing drawn) and the page in headless Chromium "
            "(software rendering). Frame compute time: the wall time of `HapticScene::frame` alone.")


def reading(rows, name):
    """What the table says: each client's median p50 and p99 against no client's."""
    base = [r for r in rows if r["page"] is False]
    p50 = statistics.median(r["p50"] for r in base)
    p99 = statistics.median(r["p99"] for r in base)
    out = ["**Reading.** Against no client:"]
    for page in ("bridge", True):
        sel = [r for r in rows if r["page"] == page]
        q50 = statistics.median(r["p50"] for r in sel)
        q99 = statistics.median(r["p99"] for r in sel)
        out.append(f"with the {name[page]} the median frame is {q50 / p50:.2f}× and the 99th percentile "
                   f"{q99 / p99:.2f}×;")
    out.append("the loop never waits for a client (nothing in the frame touches the socket or the page), so a "
               "difference is the client's processes competing for the cores.")
    return " ".join(out)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--config", required=True)
    ap.add_argument("--frames", type=int, default=15000)
    ap.add_argument("--repeats", type=int, default=2)
    ap.add_argument("--out")
    a = ap.parse_args()
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for _ in range(a.repeats):
            for page in (False, "bridge", True):
                rows.append(run(a.config, a.frames, page, Path(tmp)))
    cpu = next((l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name")), platform.machine())
    load = open("/proc/loadavg").read().split()[:3]
    cores = os.cpu_count() or 1
    # The runs themselves keep up to about one core busy (the scene, and the client's process).
    state = "a busy machine" if float(load[0]) > cores else "a quiet machine"
    lines = ["# What a page costs the haptic loop (haptic_sim view)", "", scene_words(a.config, a.frames), "",
             f"CPU: {cpu}, {cores} cores; load average after the runs {' '.join(load)} ({state}).",
             "", "| run | client | frames | compute mean (ms) | p50 (ms) | p99 (ms) | max (ms) | deadline misses | states received |",
             "| --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
    name = {False: "none", "bridge": "bridge (C++)", True: "page (Chromium)"}
    for i, r in enumerate(rows):
        lines.append(f"| {i + 1} | {name[r['page']]} | {r['frames']} | {1e3 * r['mean']:.3f} | {1e3 * r['p50']:.3f} | "
                     f"{1e3 * r['p99']:.3f} | {1e3 * r['max']:.2f} | {r['misses']} | {r['states'] if r['page'] else '-'} |")
    for page in (False, "bridge", True):
        sel = [r for r in rows if r["page"] == page]
        lines.append(f"\nClient {name[page]}: median of the runs' p50 "
                     f"{1e3 * statistics.median(r['p50'] for r in sel):.3f} ms, p99 {1e3 * statistics.median(r['p99'] for r in sel):.3f} ms.")
    lines.append("\n" + reading(rows, name))
    text = "\n".join(lines) + "\n"
    if a.out:
        Path(a.out).write_text(text)
    print(text)


if __name__ == "__main__":
    main()
