"""haptic_sim serve against what an adversarial device bridge, a second process and the system do
to it -> "stability_haptic_serve" v1: for every class (bad lines, a reader that leaves, stop
signals, a second UDP sender, an oversized datagram, a silent client, an absurd tip position, an
epoch-seconds clock, the visual stream's reader leaving, a stream naming the config) the exit
code, whether the artifact was written, how many messages were answered, and what the artifact
or the answer says. tests/pipeline/test_haptic_serve_hardening.py asserts the same behaviour;
this stage records it for results/stability/.

Config: {"mesh": tet_mesh artifact, "max_force": N (the limit the force class configures)}
"""
TOOLS = ("haptic_sim",)

import json
import os
import signal
import socket
import subprocess
import tempfile
import time
from pathlib import Path

from pipeline.artifacts import write_artifact
from pipeline.paths import ROOT
from pipeline.stages.stability_common import tool_hashes, tool_path

SCHEMA = "stability_haptic_serve"
TOOL = "pipeline.stages.stability_haptic_serve"


def tip(k, depth=0.003):
    """Line k of a press on the block's top centre, t on an epoch-seconds clock."""
    return f"{1764350000 + k * 1e-3:.6f} 0.015 0.015 {0.02 - depth * min(k / 50, 1):.9f}"


class Scene:
    def __init__(self, folder, mesh, max_force):
        self.folder, self.mesh, self.max_force = Path(folder), mesh, max_force

    def config(self, realtime=None, probe=None):
        c = {"model": {"mesh": str(ROOT / self.mesh), "material": {"E": 5000, "nu": 0.35, "density": 1000},
                       "damping": {"alpha": 20}, "boundary": {"fixed": [{"set": "bottom"}]}},
             "probe": {"stiffness": 100, **(probe or {})},
             "input": {"kind": "press", "start": [0.015, 0.015, 0.02], "direction": [0, 0, -1], "depth": 0.004,
                       "ramp_time": 0.05},
             "realtime": realtime or {"source": "stdin"}}
        path = self.folder / "scene.json"
        path.write_text(json.dumps(c))
        return path

    def start(self, announced=True, **config):
        """The server, its artifact's path and its first stderr line ("" when `announced` is
        False: a server opening a named pipe announces only once the pipe's reader came)."""
        out = self.folder / "served.json"
        if out.exists():
            out.unlink()
        cfg = self.config(**config)
        proc = subprocess.Popen([str(tool_path("haptic_sim")), "serve", "--config", str(cfg), "--out", str(out)],
                                stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        return proc, out, proc.stderr.readline() if announced else ""

    def served(self, proc, out, messages, answers, detail):
        code = proc.wait(timeout=60)
        session = json.loads(out.read_text())["payload"] if out.exists() else None
        # Without an artifact, the server's last stderr line says why (communicate has read it).
        err = "" if proc.stderr.closed else proc.stderr.read()
        return {"exit": code, "artifact": session is not None, "messages": messages, "answers": answers,
                "detail": detail(session) if session else (err.strip().splitlines() or [""])[-1][-200:]}


def bad_lines(s):
    lines = [tip(1), "", "# note", "\0" + tip(2)[1:], "9" * 100000, tip(2).replace("0.015", "nan", 1), tip(3), tip(2),
             tip(4).replace("0.015 0.015", "15 15"), tip(5), "end"]
    proc, out, _ = s.start()
    answers, _ = proc.communicate("\n".join(lines) + "\n", timeout=60)
    return s.served(proc, out, len(lines) - 1, len(answers.splitlines()),
                    lambda p: f"{p['frames']} frames, {p['session']['errors']} errors, {p['session']['comments']} comments, "
                              f"longest answer {max(len(a) for a in answers.splitlines())} bytes")


def paced(s, frames):
    """A server started on stdin and `frames` lines sent one by one, each answer awaited."""
    proc, out, _ = s.start()
    for k in range(1, frames + 1):
        proc.stdin.write(tip(k) + "\n")
        proc.stdin.flush()
        proc.stdout.readline()
    return proc, out


def reader_leaves(s):
    proc, out = paced(s, 10)
    proc.stdout.close()
    sent = 10
    try:
        for k in range(11, 2000):
            proc.stdin.write(tip(k) + "\n")
            proc.stdin.flush()
            sent += 1
    except BrokenPipeError:
        pass
    return s.served(proc, out, sent, 10, lambda p: f"ended by {p['session']['ended_by']} after {p['frames']} frames, "
                                                   f"{p['session']['undelivered_frames']} of them undelivered")


def stop_signal(sig):
    def scenario(s):
        proc, out = paced(s, 7)
        proc.send_signal(sig)
        return s.served(proc, out, 7, 7, lambda p: f"ended by {p['session']['ended_by']} after {p['frames']} frames")
    return scenario


def udp(s, idle=5.0):
    proc, out, announce = s.start(realtime={"source": "udp", "idle_timeout": idle})
    address = ("127.0.0.1", int(announce.rsplit(":", 1)[1]))
    bridge = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    bridge.settimeout(10)
    return proc, out, address, bridge


def second_sender(s):
    proc, out, address, bridge = udp(s)
    intruder = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    intruder.settimeout(0.2)
    answers = 0
    for k in range(1, 6):
        bridge.sendto(tip(k).encode(), address)
        bridge.recv(1024)
        answers += 1
        if k == 1:
            intruder.sendto(b"1 0.015 0.015 -1", address)
            intruder.sendto(b"end", address)
    try:
        intruder.recv(1024)
        answered = "answered"
    except socket.timeout:
        answered = "not answered"
    bridge.sendto(b"end", address)
    return s.served(proc, out, 5, answers,
                    lambda p: f"{p['frames']} frames; the other sender {answered}, "
                              f"{p['session']['other_peer_datagrams']} of its datagrams counted")


def oversized_datagram(s):
    proc, out, address, bridge = udp(s)
    bridge.sendto(tip(1).encode(), address)
    bridge.recv(1024)
    bridge.sendto(b"7" * 600, address)
    answer = bridge.recv(4096).decode()
    bridge.sendto(b"end", address)
    return s.served(proc, out, 2, 2, lambda p: answer.strip()[:90] + "...")


def silent_client(s):
    proc, out, address, bridge = udp(s, idle=0.5)
    for k in range(1, 6):
        bridge.sendto(tip(k).encode(), address)
        bridge.recv(1024)
    return s.served(proc, out, 5, 5, lambda p: f"ended by {p['session']['ended_by']} after {p['frames']} frames")


def absurd_tip(s):
    """A tip 1 km away asks for a force no device may render; a stiff press asks for more than the
    configured limit: the answers are refused and clamped."""
    proc, out, _ = s.start(probe={"max_force": s.max_force, "stiffness": 2000})
    lines = [tip(1), "0.0015 1000 0.015 0.02"] + [tip(k, depth=0.01) for k in range(2, 81)]
    answers, _ = proc.communicate("\n".join(lines) + "\n", timeout=60)
    forces = [[float(x) for x in a.split()[1:]] for a in answers.splitlines() if not a.startswith(("error", "#"))]
    peak = max(sum(x * x for x in f) ** 0.5 for f in forces)
    return s.served(proc, out, len(lines), len(answers.splitlines()),
                    lambda p: f"peak force sent {peak:.4g} N (limit {s.max_force:g} N), "
                              f"{p['device_safety']['clamped_frames']} frames clamped, {p['session']['errors']} refused")


def epoch_clock(s):
    proc, out, _ = s.start()
    lines = [tip(k) for k in range(1, 21)]
    answers, _ = proc.communicate("\n".join(lines) + "\n", timeout=60)
    echoed = sum(a.split()[0] == l.split()[0] for a, l in zip(answers.splitlines(), lines))
    return s.served(proc, out, len(lines), len(answers.splitlines()),
                    lambda p: f"t echoed byte for byte in {echoed} of {len(lines)} answers")


def visual_reader_leaves(s):
    fifo = s.folder / "surface.fifo"
    if not fifo.exists():
        os.mkfifo(fifo)
    proc, out, _ = s.start(announced=False, realtime={"source": "stdin", "visual": {"path": str(fifo), "every": 1}})
    reader = os.open(fifo, os.O_RDONLY)
    os.read(reader, 64)
    os.close(reader)
    answers, _ = proc.communicate("\n".join(tip(k) for k in range(1, 41)) + "\n", timeout=60)
    return s.served(proc, out, 40, len(answers.splitlines()),
                    lambda p: f"stream stopped at frame {p['session']['visual']['stopped_at_frame']}: "
                              f"{p['session']['visual']['stopped_because']}; the session went on")


def stream_names_config(s):
    cfg = s.folder / "scene.json"
    # The refusal comes before any announcement: the first stderr line is the error.
    proc, out, first = s.start(realtime={"source": "stdin", "visual": {"path": str(cfg)}})
    proc.communicate(tip(1) + "\n", timeout=60)
    kept = json.loads(cfg.read_text())["realtime"]["visual"]["path"] == str(cfg)
    row = s.served(proc, out, 1, 0, lambda p: "")
    row["detail"] = ("config kept" if kept else "config replaced") + "; " + first.strip().replace(str(s.folder) + "/", "")
    return row


CLASSES = [
    ("bad lines", "a NUL-led line, a 100 kB line, NaN, a repeated t, millimetres, blank and # lines among frames", bad_lines),
    ("reader leaves", "the bridge closes its end of the answers' pipe and keeps writing", reader_leaves),
    ("SIGTERM", "SIGTERM while the server waits for the next line", stop_signal(signal.SIGTERM)),
    ("SIGINT", "SIGINT while the server waits for the next line", stop_signal(signal.SIGINT)),
    ("second UDP sender", "another process sends a frame 1 m deep and \"end\" mid-session", second_sender),
    ("oversized datagram", "a 600-byte datagram (the cap is 512)", oversized_datagram),
    ("silent UDP client", "the client stops without \"end\" (idle_timeout 0.5 s)", silent_client),
    ("force limit", "a tip 1 km away, then a 2000 N/m spring pressed 1 cm deep", absurd_tip),
    ("epoch-seconds t", "t = 1764350000.001000 ... sent as the bridge's clock", epoch_clock),
    ("visual reader leaves", "the renderer reads the stream's header and closes the pipe", visual_reader_leaves),
    ("stream names the config", "realtime.visual.path is the run's own config", stream_names_config),
]


def run(ctx):
    rows = []
    with tempfile.TemporaryDirectory(prefix="haptic_serve_") as tmp:
        scene = Scene(tmp, ctx.config["mesh"], ctx.config.get("max_force", 1.0))
        for name, what, scenario in CLASSES:
            start = time.perf_counter()
            row = scenario(scene)
            rows.append({"class": name, "what": what, **row, "seconds": time.perf_counter() - start})
    write_artifact(ctx.out_path, SCHEMA, 1, TOOL, ctx.config, {"rows": rows, "tools": tool_hashes(TOOLS)})
