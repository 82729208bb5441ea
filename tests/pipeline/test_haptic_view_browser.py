"""haptic_sim view's page in Debian's Chromium, headless, driven over the DevTools protocol by
puppeteer-core (tests/browser/view_page.mjs): the pointer presses the block and a blade drag
cuts it. Skipped, with the reason, only where Chromium, Node or the page's npm packages are not
installed (pipeline/setup.sh installs Chromium; the build installs the npm packages)."""
import os
import shutil
import subprocess

import pytest

from conftest import BIN, ROOT
from view_scene import ViewProcess, block_config


def browser_tools():
    chromium = shutil.which("chromium") or shutil.which("chromium-browser")
    node = shutil.which("node")
    web = BIN.parent / "web"
    if not chromium:
        pytest.skip("Chromium is not installed (pipeline/setup.sh installs Debian's chromium)")
    if not node:
        pytest.skip("Node.js is not installed")
    if not (web / "node_modules" / "puppeteer-core").is_dir():
        pytest.skip(f"{web}/node_modules/puppeteer-core is missing (the build's view_web target installs it)")
    return chromium, node, web


def test_the_pointer_presses_and_cuts_the_block_in_a_real_browser(tmp_path):
    chromium, node, web = browser_tools()
    view = ViewProcess(block_config(tmp_path), "--out", tmp_path / "view.json")
    shots = os.environ.get("VIEW_SCREENSHOTS", str(tmp_path))
    try:
        env = dict(os.environ, VIEW_URL=view.url, CHROMIUM=chromium, WEB_DIR=str(web), OUT_DIR=shots,
                   PREFIX="view_block")
        r = subprocess.run([node, str(ROOT / "tests" / "browser" / "view_page.mjs")], env=env,
                           capture_output=True, text=True, timeout=180)
        assert r.returncode == 0, r.stdout + r.stderr
        for name in ["rest", "press", "cut"]:
            assert os.path.getsize(os.path.join(shots, f"view_block_{name}.png")) > 1000
        view.proc.send_signal(2)
        rc, err = view.wait()
        assert rc == 0, err
    finally:
        view.kill()
