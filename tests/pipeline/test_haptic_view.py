"""haptic_sim view's live scene over a real WebSocket on loopback: a device bridge (the C++
example) drives it with samples at 100 Hz that the scene interpolates to its 1 kHz frames; the
recorded session replays through `haptic_sim run` with the same forces bit for bit; bad input on
the socket (garbage, a huge message, a second client) is answered on that connection while the
frames go on; the page and three.js are served from the build tree and nothing outside it."""
import json
import subprocess
import time

import pytest

from conftest import run_tool, tool, write_json
from view_scene import TOP, ViewProcess, block_config, payload

websocket = pytest.importorskip("websocket", reason="python3-websocket (Debian) is needed for the socket tests")

RATE = 100       # Hz, the bridge's samples
RAMP = 0.3       # s to the full depth
DEPTH = 0.004    # m below the top


def press_lines():
    """The tip from 1 mm above the top to DEPTH below it and held, at RATE."""
    lines = []
    for k in range(int(0.6 * RATE)):
        t = k / RATE
        z = TOP[2] + 0.001 - (DEPTH + 0.001) * min(t / RAMP, 1)
        lines.append(f"{t:.6f} {TOP[0]} {TOP[1]} {z:.9f}")
    return lines


def test_a_bridge_session_replays_through_run_bit_for_bit(tmp_path):
    config = block_config(tmp_path)
    view = ViewProcess(config, "--record", tmp_path / "session.txt", "--out", tmp_path / "view.json")
    try:
        bridge = subprocess.run([str(tool("view_bridge")), "--port", str(view.port), "--hold", "0.3"],
                                input="\n".join(press_lines()) + "\n", capture_output=True, text=True, timeout=60)
        assert bridge.returncode == 0, bridge.stderr
        rc, err = view.wait()
        assert rc == 0, err
    finally:
        view.kill()
    live = payload(tmp_path / "view.json")
    assert live["mode"] == "view"
    frames = live["frames"]
    assert frames > 500  # the bridge's 0.9 s at 1 kHz
    fz = [f[2] for f in live["force"]]
    assert max(fz) > 0.1, "the press is felt (N, on the tool: upwards)"
    # The bridge saw the force through the states, rising with the press.
    states = [[float(x) for x in line.split()] for line in bridge.stdout.splitlines()]
    assert len(states) > 10
    assert max(s[3] for s in states) > 0.1
    # The tip of every frame is interpolated between the bridge's samples, not held from one to
    # the next: during the ramp most frames move by a fraction of one sample's step.
    z = [p[2] for p in live["probe"]]
    steps = [abs(b - a) for a, b in zip(z, z[1:]) if abs(b - a) > 0]
    sample_step = (DEPTH + 0.001) / (RAMP * RATE)
    assert len(steps) > 100
    assert sum(s < 0.5 * sample_step for s in steps) > 0.8 * len(steps)
    # Replayed offline from the recorded trajectory: the same forces, bit for bit.
    c = json.loads(config.read_text())
    c["input"] = {"kind": "recorded", "path": str(tmp_path / "session.txt")}
    c["frames"] = frames
    write_json(tmp_path / "replay.json", c)
    replay = run_tool("haptic_sim", "run", "--config", tmp_path / "replay.json", "--out", tmp_path / "run.json")
    assert replay.returncode == 0, replay.stderr
    offline = payload(tmp_path / "run.json")
    assert offline["probe"] == live["probe"]
    assert offline["force"] == live["force"]


def receive_json(ws, kind, timeout=10):
    deadline = time.time() + timeout
    while time.time() < deadline:
        ws.settimeout(max(0.1, deadline - time.time()))
        op, data = ws.recv_data()
        if op == websocket.ABNF.OPCODE_TEXT:
            m = json.loads(data)
            if m["type"] == kind:
                return m
    raise AssertionError(f"no {kind} message in {timeout} s")


def test_bad_input_is_answered_on_its_connection_and_the_scene_goes_on(tmp_path):
    view = ViewProcess(block_config(tmp_path))
    try:
        driver = websocket.create_connection(view.ws_url, timeout=10)
        hello = receive_json(driver, "hello")
        assert hello["protocol"] == 1 and hello["name"] == "softsim-view"
        first = receive_json(driver, "state")["frame"]
        for bad, expected in [("nonsense", "expected a JSON object"),
                              ('{"type": "sample", "t": "now", "p": [0, 0, 0]}', "/t"),
                              ('{"type": "sample", "t": 1, "p": [0, 0, null]}', "/p/2"),
                              ('{"type": "sample", "t": 2, "p": [0, 0, 0], "blade": true, "edge": [0, 0, 50]}', "/edge"),
                              ('{"type": "hello", "protocol": 7}', "/protocol"),
                              ('{"type": "fly"}', "/type")]:
            driver.send(bad)
            assert expected in receive_json(driver, "error")["message"], bad
        driver.send('{"type": "sample", "t": 5, "p": [0.03, 0.03, 0.04]}')
        driver.send('{"type": "sample", "t": 4, "p": [0.03, 0.03, 0.04]}')
        assert "times must increase" in receive_json(driver, "error")["message"]
        # A second client is told that another one drives, and closed; the first goes on.
        second = websocket.create_connection(view.ws_url, timeout=10)
        assert "one client at a time" in receive_json(second, "error")["message"]
        with pytest.raises(websocket.WebSocketConnectionClosedException):
            for _ in range(10):
                second.recv()
        assert receive_json(driver, "state")["frame"] > first
        # A huge message closes its connection with "too big" (1009)...
        driver.send("x" * 100_000)
        closed = None
        for _ in range(1000):
            frame = driver.recv_frame()  # raw frames: the close is read, not answered
            if frame.opcode == websocket.ABNF.OPCODE_CLOSE:
                closed = int.from_bytes(frame.data[:2], "big")
                break
        assert closed == 1009
        # A page of another site may not open the socket.
        with pytest.raises(websocket.WebSocketBadStatusException) as refused:
            websocket.create_connection(view.ws_url, timeout=10, origin="http://elsewhere.example")
        assert refused.value.status_code == 403
        # ... and the scene went on: a new client drives it, its frames further on.
        third = websocket.create_connection(view.ws_url, timeout=10)
        later = receive_json(third, "state")["frame"]
        assert later > first
        third.send('{"type": "stop"}')
        rc, err = view.wait()
        assert rc == 0, err
    finally:
        view.kill()


def test_the_page_and_three_js_come_from_the_build_tree_only(tmp_path):
    view = ViewProcess(block_config(tmp_path))
    try:
        status, page = view.get("/")
        assert status == 200 and b'"three": "/three/build/three.module.js"' in page
        assert b"http://" not in page and b"https://" not in page  # nothing fetched from elsewhere
        status, module = view.get("/three/build/three.module.js")
        assert status == 200 and len(module) > 100_000
        for path in ["/../CMakeLists.txt", "/three/../../CMakeCache.txt", "/.hidden", "/nothing.js"]:
            with pytest.raises(Exception) as e:
                view.get(path)
            assert getattr(e.value, "code", None) in (400, 404), path
        view.proc.send_signal(2)  # SIGINT ends the session like "stop"
        rc, err = view.wait()
        assert rc == 0, err
    finally:
        view.kill()


def test_view_options_are_checked(tmp_path):
    config = block_config(tmp_path)
    for args, expected in [(["--port", "x"], "--port"), (["--port", "70000"], "--port"),
                           (["--latency", "5"], "--latency"), (["--record"], "--record")]:
        r = run_tool("haptic_sim", "view", "--config", config, *args)
        assert r.returncode == 2 and expected in r.stderr, r.stderr
        assert len(r.stderr.strip().splitlines()) == 1
