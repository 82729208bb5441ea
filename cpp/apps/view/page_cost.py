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
    lines = [f"CPU: {cpu}, {os.cpu_count()} cores; load average after the runs {' '.join(load)} (a shared, busy machine).",
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
    text = "\n".join(lines) + "\n"
    if a.out:
        Path(a.out).write_text(text)
    print(text)


if __name__ == "__main__":
    main()
