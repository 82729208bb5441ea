"""haptic_sim serve against what a device bridge, a second process or the system does to it,
through real pipes, sockets and signals (cpp/apps/haptic_sim.md, "The protocol"): every message
gets one answer and a bad one does not end the session; t comes back as it was sent; the force
the device is sent never passes the configured limit; the answers' reader or the visual
stream's reader leaving, SIGTERM and SIGINT end the session with its record written and a
documented exit code; a second UDP sender is ignored and counted; the visual stream obeys the
output rules and a failed run leaves none of it."""
import json
import os
import resource
import signal
import socket
import subprocess
import time

import pytest

from conftest import run_tool, tool, write_json

EXIT_CLIENT_LEFT, EXIT_STOPPED = 4, 5


@pytest.fixture
def scene(tmp_path):
    """A 3 x 3 x 2-cell block, a press on its top, and a config writer."""
    write_json(tmp_path / "m.json", {"source": {"kind": "cuboid", "cells": [3, 3, 2], "size": [0.03, 0.03, 0.02]}})
    assert run_tool("mesher", "--config", tmp_path / "m.json", "--out", tmp_path / "mesh.json").returncode == 0

    def config(probe=None, **extra):
        c = {"model": {"mesh": str(tmp_path / "mesh.json"), "material": {"E": 5000, "nu": 0.35, "density": 1000},
                       "damping": {"alpha": 20}, "boundary": {"fixed": [{"set": "bottom"}]}},
             "frames": 100, "probe": {"stiffness": 100, **(probe or {})},
             "input": {"kind": "press", "start": [0.015, 0.015, 0.02], "direction": [0, 0, -1],
                       "depth": 0.004, "ramp_time": 0.05}}
        c.update(extra)
        return write_json(tmp_path / "h.json", c)

    return tmp_path, config


def line(k, depth=0.003):
    return f"{1764350000 + k * 1e-3:.6f} 0.015 0.015 {0.02 - depth * min(k / 50, 1):.9f}"


def payload(path):
    return json.loads(path.read_text())["payload"]


def serve(tmp, **kw):
    return subprocess.Popen([str(tool("haptic_sim")), "serve", "--config", tmp / "h.json", "--out", tmp / "serve.json"],
                            text=True, **kw)


def test_every_message_is_answered_and_bad_ones_do_not_end_the_session(scene):
    tmp, config = scene
    config()
    messages = [line(1), "", "# a comment", "\0" + line(2)[1:], "9" * 100000, line(2).replace("0.015", "nan", 1),
                line(3), line(2), line(4).replace("0.015 0.015", "15 15"), line(5), "end", line(6)]
    r = subprocess.run([str(tool("haptic_sim")), "serve", "--config", tmp / "h.json", "--out", tmp / "serve.json"],
                       input="\n".join(messages) + "\n", capture_output=True, text=True, timeout=60)
    assert r.returncode == 0, r.stderr
    answers = r.stdout.splitlines()
    # One answer per message up to "end" (which closes the session and is not answered).
    assert len(answers) == 10, answers
    kinds = ["force", "#", "#", "error", "error", "error", "force", "error", "error", "force"]
    assert ["#" if a == "#" else "error" if a.startswith("error ") else "force" for a in answers] == kinds
    assert "stdin:4: expected text" in answers[3] and "NUL byte" in answers[3]
    assert "stdin:5: expected a message of at most 512 bytes, got 100000 bytes" in answers[4]
    assert len(answers[4]) < 200  # a short excerpt, not the 100 kB line
    assert "finite" in answers[5] and "times must increase" in answers[7]
    assert "stdin:9" in answers[8] and "(metres)" in answers[8]
    # t comes back byte for byte: an epoch-seconds clock round-trips.
    assert answers[0].split()[0] == line(1).split()[0] and answers[9].split()[0] == line(5).split()[0]
    s = payload(tmp / "serve.json")
    assert s["frames"] == 3 and s["time"][-1] == pytest.approx(float(line(5).split()[0]), abs=1e-6)
    session = s["session"]
    assert (session["ended_by"], session["exit_code"], session["messages"]) == ("end", 0, 11)
    assert (session["comments"], session["errors"], session["oversized"]) == (2, 5, 1)
    assert len(session["error_messages"]) == 5


def test_the_force_sent_never_passes_the_limit_in_run_and_serve(scene):
    tmp, config = scene
    free = config()
    assert run_tool("haptic_sim", "run", "--config", free, "--out", tmp / "free.json").returncode == 0
    asked = [sum(x * x for x in f) ** 0.5 for f in payload(tmp / "free.json")["force"]]
    limit, step = 0.3 * max(asked), 0.01
    config(probe={"max_force": limit, "max_force_step": step})
    assert run_tool("haptic_sim", "run", "--config", tmp / "h.json", "--out", tmp / "run.json").returncode == 0
    lines = [line(k) for k in range(1, 101)]
    r = subprocess.run([str(tool("haptic_sim")), "serve", "--config", tmp / "h.json", "--out", tmp / "serve.json"],
                       input="\n".join(lines) + "\n", capture_output=True, text=True, timeout=60)
    assert r.returncode == 0, r.stderr
    answered = [[float(x) for x in a.split()[1:]] for a in r.stdout.splitlines()]
    for name, forces in (("run", payload(tmp / "run.json")["force"]), ("serve", answered)):
        norms = [sum(x * x for x in f) ** 0.5 for f in forces]
        assert max(norms) <= limit * (1 + 1e-12), name
        assert max(norms) == pytest.approx(limit, rel=1e-9), name  # the press reaches the limit
        steps = [sum((a - b) ** 2 for a, b in zip(f, g)) ** 0.5 for f, g in zip(forces[1:], forces)]
        assert max(steps) <= step * (1 + 1e-9), name
    safety = payload(tmp / "serve.json")["device_safety"]
    assert safety["max_force"] == limit and safety["clamped_frames"] > 0
    assert safety["clamps"][-1]["sent"] == pytest.approx(answered[safety["clamps"][-1]["frame"] - 1], rel=1e-15)


def test_a_reader_that_leaves_ends_the_session_with_its_record(scene):
    tmp, config = scene
    config()
    server = serve(tmp, stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    for k in range(1, 11):
        server.stdin.write(line(k) + "\n")
        server.stdin.flush()
        assert server.stdout.readline().startswith(line(k).split()[0])
    server.stdout.close()  # the bridge stops reading its answers
    try:
        for k in range(11, 2000):
            server.stdin.write(line(k) + "\n")
            server.stdin.flush()
    except BrokenPipeError:
        pass
    assert server.wait(timeout=30) == EXIT_CLIENT_LEFT, server.stderr.read()
    s = payload(tmp / "serve.json")
    assert s["session"]["ended_by"] == "client_left" and s["frames"] >= 10


@pytest.mark.parametrize("sig, name", [(signal.SIGTERM, "SIGTERM"), (signal.SIGINT, "SIGINT")])
def test_a_stop_signal_mid_session_writes_the_record(scene, sig, name):
    tmp, config = scene
    config(realtime={"source": "stdin", "announce": True})
    server = serve(tmp, stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    assert server.stderr.readline().strip() == "haptic_sim: ready"
    for k in range(1, 8):
        server.stdin.write(line(k) + "\n")
        server.stdin.flush()
        server.stdout.readline()
    server.send_signal(sig)  # the server waits for line 8
    assert server.wait(timeout=30) == EXIT_STOPPED, server.stderr.read()
    s = payload(tmp / "serve.json")
    assert s["frames"] == 7 and s["session"]["ended_by"] == name and s["session"]["exit_code"] == EXIT_STOPPED


def udp_server(tmp, config, **realtime):
    config(realtime={"source": "udp", "port": 0, "idle_timeout": 5, **realtime})
    server = serve(tmp, stderr=subprocess.PIPE)
    announce = server.stderr.readline()
    assert "listening on udp 127.0.0.1:" in announce, announce
    return server, ("127.0.0.1", int(announce.rsplit(":", 1)[1]))


def client():
    c = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    c.bind(("127.0.0.1", 0))
    c.settimeout(10)
    return c


def test_udp_session_belongs_to_its_first_peer(scene):
    tmp, config = scene
    server, address = udp_server(tmp, config)
    try:
        bridge, intruder = client(), client()
        bridge.sendto(line(1).encode(), address)
        assert bridge.recv(1024).decode().startswith(line(1).split()[0])
        intruder.sendto(b"1 0.015 0.015 0.01", address)  # would move the tool
        intruder.sendto(b"end", address)                  # a stale datagram would end the session
        for k in range(2, 6):
            bridge.sendto(line(k).encode(), address)
            assert bridge.recv(1024).decode().startswith(line(k).split()[0])
        intruder.settimeout(0.2)
        with pytest.raises(socket.timeout):
            intruder.recv(1024)  # never answered
        bridge.sendto(b"x" * 600, address)  # a datagram over the cap: refused, not cut
        assert b"got 600 bytes" in bridge.recv(1024)
        bridge.sendto(b"end", address)
        assert server.wait(timeout=30) == 0, server.stderr.read()
    finally:
        server.kill()
    session = payload(tmp / "serve.json")["session"]
    assert payload(tmp / "serve.json")["frames"] == 5
    assert session["other_peer_datagrams"] == 2 and session["other_peers"] == [f"127.0.0.1:{intruder.getsockname()[1]}"]
    assert session["peer"] == f"127.0.0.1:{bridge.getsockname()[1]}" and session["oversized"] == 1


def test_udp_client_silent_past_the_idle_timeout_ends_with_its_record(scene):
    tmp, config = scene
    server, address = udp_server(tmp, config, idle_timeout=1.0)
    bridge = client()
    for k in range(1, 6):
        bridge.sendto(line(k).encode(), address)
        bridge.recv(1024)
    assert server.wait(timeout=30) == EXIT_CLIENT_LEFT, server.stderr.read()
    s = payload(tmp / "serve.json")
    assert s["frames"] == 5 and s["session"]["ended_by"] == "idle_timeout"


@pytest.mark.parametrize("timeout", [1e-7, 1e9])
def test_idle_timeout_out_of_range_is_refused(scene, timeout):
    tmp, config = scene
    config(realtime={"source": "udp", "idle_timeout": timeout})
    r = run_tool("haptic_sim", "serve", "--config", tmp / "h.json", "--out", tmp / "serve.json")
    assert r.returncode == 2 and "/realtime/idle_timeout" in r.stderr and "[0.001, 86400]" in r.stderr, r.stderr


def test_max_frames_beyond_the_range_is_refused(scene):
    tmp, config = scene
    config(realtime={"source": "stdin", "max_frames": 10 ** 15})
    r = run_tool("haptic_sim", "serve", "--config", tmp / "h.json", "--out", tmp / "serve.json")
    assert r.returncode == 2 and "/realtime/max_frames" in r.stderr, r.stderr


def test_the_visual_streams_reader_leaving_does_not_end_the_run(scene):
    tmp, config = scene
    fifo = tmp / "surface.fifo"
    os.mkfifo(fifo)
    config(realtime={"source": "stdin", "visual": {"path": str(fifo), "every": 1}})
    server = serve(tmp, stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    reader = os.open(fifo, os.O_RDONLY)  # the server's open of the pipe waits for its reader
    os.read(reader, 64)
    os.close(reader)  # the renderer leaves
    out, err = server.communicate("\n".join(line(k) for k in range(1, 41)) + "\n", timeout=60)
    assert server.returncode == 0, err
    assert len(out.splitlines()) == 40
    visual = payload(tmp / "serve.json")["session"]["visual"]
    assert visual["stopped_because"] == "the reader left" and visual["stopped_at_frame"] >= 1
    assert fifo.exists()


@pytest.mark.parametrize("target", ["config", "mesh", "device"])
def test_the_visual_stream_obeys_the_output_rules(scene, target):
    tmp, config = scene
    path = {"config": tmp / "h.json", "mesh": tmp / "mesh.json", "device": "/dev/null"}[target]
    config(realtime={"source": "stdin", "visual": {"path": str(path)}})
    before = open(path, "rb").read() if target != "device" else None
    r = subprocess.run([str(tool("haptic_sim")), "serve", "--config", tmp / "h.json", "--out", tmp / "serve.json"],
                       input=line(1) + "\n", capture_output=True, text=True, timeout=60)
    assert r.returncode == 2 and "/realtime/visual/path" in r.stderr, r.stderr
    if before is not None:
        assert open(path, "rb").read() == before
    assert not (tmp / "serve.json").exists()


def test_a_run_failing_at_the_file_size_limit_leaves_no_stream_and_no_temporary(scene):
    """SIGXFSZ is ignored: the artifact's write fails past the limit with an error, the partial
    visual stream and the temporary are removed, and an earlier stream of the same name is back."""
    tmp, config = scene
    stream = tmp / "surface.bin"
    stream.write_bytes(b"an earlier run's stream")
    config(realtime={"source": "stdin", "visual": {"path": str(stream), "every": 1000}})
    limit = 20000  # above the stream's header, below the artifact of 300 frames

    def cap():
        resource.setrlimit(resource.RLIMIT_FSIZE, (limit, limit))

    r = subprocess.run([str(tool("haptic_sim")), "serve", "--config", tmp / "h.json", "--out", tmp / "serve.json"],
                       input="\n".join(line(k) for k in range(1, 301)) + "\n", capture_output=True, text=True,
                       timeout=60, preexec_fn=cap)
    assert r.returncode in (1, 2) and r.returncode > 0, r.stderr
    assert len([l for l in r.stderr.splitlines() if "error" in l]) == 1, r.stderr
    assert stream.read_bytes() == b"an earlier run's stream"
    assert sorted(p.name for p in tmp.iterdir()) == ["h.json", "m.json", "mesh.json", "surface.bin"]
