"""Long computations release the GIL: another Python thread keeps running meanwhile."""
import threading
import time

import pytest

from conftest import import_softsim

softsim = import_softsim()


def largest_pause_while(call):
    """Runs call() in a thread while this thread ticks every millisecond -> (the longest gap
    between ticks during the call, the call's duration). Holding the GIL for the whole call
    would stop the ticks for about its duration."""
    span = {}

    def worker():
        span["start"] = time.monotonic()
        call()
        span["end"] = time.monotonic()

    thread = threading.Thread(target=worker)
    ticks = []
    thread.start()
    while thread.is_alive():
        ticks.append(time.monotonic())
        time.sleep(0.001)
    thread.join()
    inside = [span["start"]] + [t for t in ticks if span["start"] < t < span["end"]] + [span["end"]]
    return max(b - a for a, b in zip(inside, inside[1:])), span["end"] - span["start"]




def explicit_run():
    mesh = softsim.cuboid((8, 8, 6), (0.1, 0.1, 0.08))
    return lambda: softsim.run_dhd(mesh, {"boundary": {"fixed": ["bottom"]}, "solver": {"steps": 20000},
                                          "material": {"density": 1000}})


def static_solve():
    mesh = softsim.cuboid((10, 10, 8), (0.1, 0.1, 0.08))
    return lambda: softsim.solve_static(mesh, {"boundary": {"fixed": ["bottom"], "prescribed": [
        {"set": "top", "displacement": [0, 0, -0.004]}]}, "solver": {"increments": 4}})


def rpim_dataset():
    # A plate of 15 x 15 x 3 nodes: long enough to time (the paper's 11 x 11 x 3 takes ~0.15 s).
    return lambda: softsim.rpim_precompute({"plate": {"nodes": [15, 15, 3]}, "dataset": {"kind": "axis_z", "count": 3}})


@pytest.mark.parametrize("make", [explicit_run, static_solve, rpim_dataset], ids=lambda m: m.__name__)
def test_other_threads_run_during_the_computation(make):
    pause, duration = largest_pause_while(make())
    assert duration > 0.2, f"the computation took {duration:.3f} s: too short to tell"
    assert pause < duration / 2, f"this thread stopped for {pause:.3f} s of a {duration:.3f} s call"
