"""The scene of async_sim runs in words, read from the runs' own configs: what a caption or a
sentence of the async reports may say about the bar, the probe, the input and the solver. A value
that differs between the runs a sentence covers is named with every value it takes, and
`differences` says how two groups of runs differ, for sentences that compare them."""
from pipeline.tables import fmt

# (key, path in the async_sim config); the async block (primary size, secondary rate, exchange)
# is what the sweeps vary, so it is not part of the scene.
SCENE_PATHS = {
    "nodes": ("model", "nodes"), "length": ("model", "length"), "youngs_modulus": ("model", "youngs_modulus"),
    "density": ("model", "density"), "damping": ("model", "damping", "ratio"),
    "rate": ("haptics", "rate"), "duration": ("haptics", "duration"), "probe": ("haptics", "probe_stiffness"),
    "input": ("input", "kind"), "amplitude": ("input", "amplitude"),
    "f_start": ("input", "start_frequency"), "f_end": ("input", "end_frequency"),
    "f_sine": ("input", "frequency"), "growth_time": ("input", "growth_time"),
    "solver": ("solver", "kind"), "scheme": ("solver", "implicit_scheme"),
    "linear_solver": ("linear_solver",),
}

WORDS = {
    "nodes": lambda v: f"{v} nodes", "length": lambda v: f"{fmt(1e3 * v)} mm long",
    "youngs_modulus": lambda v: f"E = {fmt(v / 1000)} kPa", "density": lambda v: f"ρ = {fmt(v)} kg/m³",
    "damping": lambda v: f"damping ratio {fmt(v)}", "rate": lambda v: f"haptic rate {fmt(v / 1000)} kHz",
    "duration": lambda v: f"{fmt(v)} s", "probe": lambda v: f"probe spring {fmt(v)} N/m",
    "input": lambda v: f"{v} input", "amplitude": lambda v: f"amplitude {fmt(1e3 * v)} mm",
    "f_start": lambda v: f"from {fmt(v)} Hz", "f_end": lambda v: f"to {fmt(v)} Hz",
    "f_sine": lambda v: f"sine of {fmt(v)} Hz", "growth_time": lambda v: f"growing over {fmt(v)} s",
    "solver": lambda v: f"{v} solver", "scheme": lambda v: SCHEMES.get(v, str(v).replace("_", " ")),
    "linear_solver": lambda v: f"{v} solves",
}
SCHEMES = {"backward_euler": "backward Euler", "newmark": "Newmark"}


def _get(config: dict, path):
    v = config
    for key in path:
        if not isinstance(v, dict) or key not in v:
            return None
        v = v[key]
    return v


def scene(config: dict) -> dict:
    """The scene values of one async_sim config (None where the config leaves one to the tool)."""
    return {key: _get(config, path) for key, path in SCENE_PATHS.items()}


def values(rows, key):
    """Every value of `key` among the rows, sorted (None left out)."""
    return sorted({r["scene"][key] for r in rows if r["scene"][key] is not None}, key=str)


def one(rows, key, unit_scale=1.0, unit=""):
    """The value of `key` over the rows: "10" or, where they differ, "10 or 20"."""
    vals = values(rows, key)
    text = " or ".join(fmt(v * unit_scale) if isinstance(v, (int, float)) else str(v) for v in vals)
    return f"{text}{(' ' + unit) if unit else ''}" if vals else "unknown"


def describe(rows) -> str:
    """The bar scene of the rows in one phrase, every value from their configs."""
    scheme = values(rows, "scheme")
    solver = " or ".join(SCHEMES.get(s, s.replace("_", " ")) for s in scheme) if scheme else one(rows, "solver")
    text = (f"1-D bar of {one(rows, 'nodes')} nodes, probe spring {one(rows, 'probe', 1, 'N/m')} at "
            f"{one(rows, 'rate', 1e-3, 'kHz')}, {one(rows, 'input')} {one(rows, 'amplitude', 1e3, 'mm')} from "
            f"{one(rows, 'f_start', 1, 'Hz')} to {one(rows, 'f_end', 1, 'Hz')} over {one(rows, 'duration', 1, 's')}, "
            f"{solver} in every region")
    return text


def chirp(rows) -> str:
    """The input in a few words: "chirp 1 mm 0-5 Hz"."""
    return (f"{one(rows, 'input')} {one(rows, 'amplitude', 1e3, 'mm')} "
            f"{one(rows, 'f_start')}-{one(rows, 'f_end', 1, 'Hz')}")


def differences(rows_a, rows_b, name_a: str, name_b: str, ignore=("linear_solver",)) -> list:
    """How the scenes of two groups of runs differ: ["probe spring 20 N/m in the in-turn runs,
    10 N/m in the sweep", ...]; empty where they share the scene."""
    out = []
    for key in SCENE_PATHS:
        if key in ignore:
            continue
        a, b = values(rows_a, key), values(rows_b, key)
        if a != b:
            wa = " or ".join(WORDS[key](v) for v in a) or "unset"
            wb = " or ".join(WORDS[key](v) for v in b) or "unset"
            out.append(f"{wa} in {name_a}, {wb} in {name_b}")
    return out


def same_scene_clause(rows_a, rows_b, name_a: str, name_b: str) -> str:
    """"" where the two groups share the scene, else a sentence saying how they differ."""
    diff = differences(rows_a, rows_b, name_a, name_b)
    if not diff:
        return ""
    return " Note: the two are not the same scene (" + "; ".join(diff) + "), so the comparison mixes that difference in."


def regions(rows, primary=True) -> str:
    """The regions' settings of the rows: "E = 5 kPa, primary region 10 nodes, secondary region
    every 20th frame (50 Hz)" (primary size left out with primary=False, for sweeps of it)."""
    def either(vals, f):
        return " or ".join(f(v) for v in sorted(set(vals)))
    text = f"E = {either([r['E'] for r in rows], lambda v: fmt(v / 1000))} kPa"
    if primary:
        text += f", primary region {either([r['n'] for r in rows], str)} nodes"
    return (text + f", secondary region every {either([r['every'] for r in rows], lambda e: f'{e}th')} frame "
            f"({either([r['rate'] for r in rows], lambda v: f'{v:.3g} Hz')})")


def growing_sine(rows) -> str:
    """The growing sine of the rows: "1 Hz sine growing from 0 to 20 mm over 10 s"."""
    return (f"{one(rows, 'f_sine', 1, 'Hz')} sine growing from 0 to {one(rows, 'amplitude', 1e3, 'mm')} over "
            f"{one(rows, 'growth_time', 1, 's')}")
