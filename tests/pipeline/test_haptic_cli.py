"""haptic_sim's real-time loop as a device bridge drives it, through real pipes and a real UDP
socket on loopback: it answers every frame, frame for frame, with the forces the offline run of
the same positions computes (to round-off: the offline run interpolates the recorded file); bad config input ends in exit 2 with one line and no
artifact. What a bad device line, a client gone, a second sender or a signal do:
test_haptic_serve_hardening.py."""
import json
import socket
import subprocess
import time

import pytest

from conftest import run_tool, tool, write_json

FRAMES = 200


@pytest.fixture
def scene(tmp_path):
    """A 6 x 6 x 3-cell block pressed and released by a recorded trajectory, and its config."""
    write_json(tmp_path / "m.json", {"source": {"kind": "cuboid", "cells": [6, 6, 3], "size": [0.06, 0.06, 0.03]}})
    assert run_tool("mesher", "--config", tmp_path / "m.json", "--out", tmp_path / "mesh.json").returncode == 0
    lines = [f"{k * 1e-3:.4f} 0.03 0.03 {0.03 - 0.004 * min(k / 100, 1):.9f}" for k in range(FRAMES)]
    (tmp_path / "path.txt").write_text("\n".join(lines) + "\n")

    def config(**extra):
        c = {"model": {"mesh": str(tmp_path / "mesh.json"), "material": {"E": 5000, "nu": 0.35, "density": 1000},
                       "damping": {"alpha": 20}, "boundary": {"fixed": [{"set": "bottom"}]}},
             "frames": FRAMES, "probe": {"stiffness": 100},
             "input": {"kind": "recorded", "path": str(tmp_path / "path.txt")}}
        c.update(extra)
        return write_json(tmp_path / "h.json", c)

    return tmp_path, lines, config


def payload(path):
    return json.loads(path.read_text())["payload"]


def test_stdin_answers_each_line_with_the_offline_runs_force(scene):
    tmp, lines, config = scene
    config()
    offline = run_tool("haptic_sim", "run", "--config", tmp / "h.json", "--out", tmp / "run.json")
    assert offline.returncode == 0, offline.stderr
    served = subprocess.run([str(tool("haptic_sim")), "serve", "--config", tmp / "h.json", "--out", tmp / "serve.json"],
                            input="\n".join(lines) + "\n", capture_output=True, text=True)
    assert served.returncode == 0, served.stderr
    answers = served.stdout.splitlines()
    assert len(answers) == FRAMES
    forces = payload(tmp / "run.json")["force"]
    for line, answer, f in zip(lines, answers, forces):
        t, *force = answer.split()
        assert float(t) == pytest.approx(float(line.split()[0]), abs=1e-12)
        # The offline run interpolates the file at k x frame step, which lands on each sample
        # time only to round-off: the same force to round-off.
        assert [float(x) for x in force] == pytest.approx(f, rel=1e-9, abs=1e-12)
    assert max(abs(f[2]) for f in forces) > 0.05  # the press is felt
    assert payload(tmp / "serve.json")["frames"] == FRAMES


def test_udp_client_on_loopback_frame_for_frame(scene):
    tmp, lines, config = scene
    config(realtime={"source": "udp", "port": 0, "idle_timeout": 5})
    offline = run_tool("haptic_sim", "run", "--config", tmp / "h.json", "--out", tmp / "run.json")
    assert offline.returncode == 0, offline.stderr
    server = subprocess.Popen([str(tool("haptic_sim")), "serve", "--config", tmp / "h.json", "--out", tmp / "serve.json"],
                              stderr=subprocess.PIPE, text=True)
    try:
        announce = server.stderr.readline()
        assert "listening on udp 127.0.0.1:" in announce, announce
        port = int(announce.rsplit(":", 1)[1])
        client = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        client.settimeout(10)
        answers = []
        for line in lines:  # paced by the answers, as a device bridge at 1 kHz would be
            client.sendto(line.encode(), ("127.0.0.1", port))
            answers.append(client.recv(512).decode())
        client.sendto(b"end", ("127.0.0.1", port))
        assert server.wait(timeout=30) == 0, server.stderr.read()
    finally:
        server.kill()
    forces = payload(tmp / "run.json")["force"]
    got = [[float(x) for x in a.split()[1:]] for a in answers]
    for g, f in zip(got, forces):
        assert g == pytest.approx(f, rel=1e-9, abs=1e-12)
    assert len(got) == FRAMES
    served = payload(tmp / "serve.json")
    assert served["frames"] == FRAMES and served["mode"] == "serve"
    assert served["timing"]["frame_seconds_max"] > 0


def test_recorded_file_with_nan_is_refused_by_line(scene):
    tmp, lines, config = scene
    (tmp / "path.txt").write_text(lines[0] + "\n0.001 0.03 nan 0.03\n")
    config()
    r = run_tool("haptic_sim", "run", "--config", tmp / "h.json", "--out", tmp / "run.json")
    assert r.returncode == 2 and "path.txt:2: expected a finite number" in r.stderr, r.stderr
    assert not (tmp / "run.json").exists()


def test_static_model_and_model_probe_are_refused(scene):
    tmp, _, config = scene
    c = json.loads(config().read_text())
    c["model"]["solver"] = {"kind": "static"}
    write_json(tmp / "h.json", c)
    r = run_tool("haptic_sim", "run", "--config", tmp / "h.json", "--out", tmp / "run.json")
    assert r.returncode == 2 and "/model/solver" in r.stderr and "explicit" in r.stderr, r.stderr


def read_surface_stream(path):
    """The visual stream: its header, node indices and pictures (t, positions N x 3)."""
    import numpy as np
    data = path.read_bytes()
    end = data.index(b"\n")
    name, version, word, count = data[:end].decode().split()
    assert (name, version, word) == ("softsim_surface", "1", "nodes")
    n = int(count)
    nodes = np.frombuffer(data, dtype=np.int32, count=n, offset=end + 1)
    offset, pictures = end + 1 + 4 * n, []
    while offset < len(data):
        t = np.frombuffer(data, dtype=np.float64, count=1, offset=offset)[0]
        x = np.frombuffer(data, dtype=np.float32, count=3 * n, offset=offset + 8).reshape(n, 3)
        pictures.append((t, x))
        offset += 8 + 12 * n
    assert offset == len(data)
    return nodes, pictures


def test_the_visual_stream_carries_the_deformed_surface_at_its_own_rate(scene):
    import numpy as np
    tmp, lines, config = scene
    config(realtime={"source": "stdin", "visual": {"path": str(tmp / "surface.bin"), "every": 20}})
    served = subprocess.run([str(tool("haptic_sim")), "serve", "--config", tmp / "h.json", "--out", tmp / "serve.json"],
                            input="\n".join(lines) + "\n", capture_output=True, text=True)
    assert served.returncode == 0, served.stderr
    assert len(served.stdout.splitlines()) == FRAMES  # every frame still answered
    nodes, pictures = read_surface_stream(tmp / "surface.bin")
    mesh = json.loads((tmp / "mesh.json").read_text())["payload"]
    rest = np.array(mesh["nodes"])[nodes]
    assert sorted(set(np.array(mesh["boundary"]).ravel())) == list(nodes)
    assert len(pictures) == FRAMES // 20
    assert [t for t, _ in pictures] == pytest.approx([float(lines[20 * k - 1].split()[0]) for k in range(1, 11)])
    # The surface is pressed under the tip (0.03, 0.03) by up to 4 mm and stays put far from it.
    t, x = pictures[-1]
    moved = np.linalg.norm(x - rest, axis=1)
    under = np.argmin(np.linalg.norm(rest[:, :2] - [0.03, 0.03], axis=1) + 10 * abs(rest[:, 2] - 0.03))
    assert 0.001 < moved[under] < 0.0045
    assert moved[np.linalg.norm(rest[:, :2] - [0.03, 0.03], axis=1) > 0.025].max() < 0.2 * moved[under]


def test_served_regions_answer_with_the_offline_regions_forces(scene):
    tmp, lines, config = scene
    config(regions={"radius": 0.015, "coupling": "condensed", "secondary_every": 5})
    offline = run_tool("haptic_sim", "run", "--config", tmp / "h.json", "--out", tmp / "run.json")
    assert offline.returncode == 0, offline.stderr
    served = subprocess.run([str(tool("haptic_sim")), "serve", "--config", tmp / "h.json", "--out", tmp / "serve.json"],
                            input="\n".join(lines) + "\n", capture_output=True, text=True)
    assert served.returncode == 0, served.stderr
    forces = payload(tmp / "run.json")["force"]
    answers = [[float(x) for x in a.split()[1:]] for a in served.stdout.splitlines()]
    # serve, like run, builds the region at the input's start before the first frame: the same region.
    import numpy as np
    np.testing.assert_allclose(answers, forces, rtol=1e-9, atol=1e-12)
    regions = payload(tmp / "serve.json")["regions"]
    assert regions["coupling"] == "condensed" and regions["primary"]["interface_nodes"] > 0
    assert payload(tmp / "serve.json")["solver"] == "regions"


def test_serve_announces_ready_after_the_region_is_built_and_before_reading(scene):
    """With realtime.announce the bridge learns when the scene is set up (the region at the
    input's start built): the announcement comes before any line is sent, every line is then
    answered, and the run keeps the one region built before it."""
    tmp, lines, config = scene
    config(regions={"radius": 0.015, "coupling": "condensed", "secondary_every": 5},
           realtime={"source": "stdin", "announce": True})
    server = subprocess.Popen([str(tool("haptic_sim")), "serve", "--config", tmp / "h.json", "--out", tmp / "serve.json"],
                              stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        assert server.stderr.readline().strip() == "haptic_sim: ready"
        out, err = server.communicate("\n".join(lines) + "\n", timeout=60)
    finally:
        server.kill()
    assert server.returncode == 0, err
    assert len(out.splitlines()) == FRAMES
    regions = payload(tmp / "serve.json")["regions"]
    assert regions["builds"] == 1
