"""A small live scene for haptic_sim view's tests: the 6 x 6 x 3-cell block of the haptic tests,
pressed from its top by a pushing probe, started on a free loopback port."""
import json
import re
import subprocess
import time
import urllib.request

from conftest import run_tool, tool, write_json

TOP = [0.03, 0.03, 0.03]


def block_config(tmp_path, **extra):
    write_json(tmp_path / "m.json", {"source": {"kind": "cuboid", "cells": [6, 6, 3], "size": [0.06, 0.06, 0.03]}})
    assert run_tool("mesher", "--config", tmp_path / "m.json", "--out", tmp_path / "mesh.json").returncode == 0
    c = {"model": {"mesh": str(tmp_path / "mesh.json"), "material": {"E": 5000, "nu": 0.35, "density": 1000},
                   "damping": {"alpha": 20}, "boundary": {"fixed": [{"set": "bottom"}]}},
         "frames": 1000, "probe": {"stiffness": 100, "contact": "push"},
         "input": {"kind": "press", "start": [0.03, 0.03, 0.035], "direction": [0, 0, -1], "depth": 0.001, "ramp_time": 1}}
    c.update(extra)
    return write_json(tmp_path / "h.json", c)


class ViewProcess:
    """`haptic_sim view` on a free port; the port read from its announcement."""

    def __init__(self, config, *args):
        self.proc = subprocess.Popen([str(tool("haptic_sim")), "view", "--config", str(config), "--port", "0", *map(str, args)],
                                     stderr=subprocess.PIPE, text=True)
        line = self.proc.stderr.readline()
        match = re.search(r"view on http://127\.0\.0\.1:(\d+)/", line)
        if not match:
            self.proc.kill()
            raise AssertionError(f"no announcement: {line}{self.proc.stderr.read()}")
        self.port = int(match.group(1))
        self.url = f"http://127.0.0.1:{self.port}/"
        self.ws_url = f"ws://127.0.0.1:{self.port}/"

    def get(self, path):
        with urllib.request.urlopen(self.url.rstrip("/") + path, timeout=10) as r:
            return r.status, r.read()

    def wait(self, timeout=30):
        rc = self.proc.wait(timeout=timeout)
        return rc, self.proc.stderr.read()

    def kill(self):
        if self.proc.poll() is None:
            self.proc.kill()
            self.proc.wait()


def payload(path):
    return json.loads(path.read_text())["payload"]
