"""Shared pieces of the DHD-FEA reports (paper 000): the error metric, the Pareto front, reading
engine artifacts, pictures of deformed meshes, VTU export and the assembly of
results/dhd/summary.md from one section per experiment.

The error metric (000 §3.2, Tables 2–3). The paper measures "the modulus of the difference in
displacements of corresponding nodes" and uses "the average difference", reported in percent.
Our primary figure is the mean nodal difference relative to the mean nodal displacement of the
all-TLED reference:

    e = Σ_v |u_v − u_v^TLED| / Σ_v |u_v^TLED|

It is the paper's average difference made dimensionless by the only displacement scale the
reference itself offers; it does not depend on whether fixed nodes are counted (they add zero
to both sums) nor on the length unit. The alternatives are reported beside it (CSV), since the
paper does not say what its percentage is relative to: the mean difference relative to the
applied displacement, the RMS ratio, the ratio of maxima, and the mean of per-node relative
differences over nodes that move by more than 1 % of the largest reference displacement.
"""
import json
import re

import numpy as np

from pipeline import plots
from pipeline.element_kinds import (element_kind_names, element_kinds, kind_counts, kind_legend,  # noqa: F401
                                    kind_names, small_strain_kinds)
from pipeline.report_md import read_parts
from pipeline.artifacts import write_text_atomic

SECTION_DIR = "sections"


# --------------------------------------------------------------------------- error metric
def displacement_error(u, u_ref, applied: float = None, moving_share: float = 0.01) -> dict:
    """Every figure of merit of a displacement field u against the reference u_ref (n × 3)."""
    u = np.asarray(u, dtype=float).reshape(-1, 3)
    u_ref = np.asarray(u_ref, dtype=float).reshape(-1, 3)
    if u.shape != u_ref.shape:
        raise ValueError(f"displacement fields differ in shape: {u.shape} vs {u_ref.shape}")
    diff = np.linalg.norm(u - u_ref, axis=1)
    ref = np.linalg.norm(u_ref, axis=1)
    if not ref.sum() > 0:
        raise ValueError("the reference displacement field is zero")
    moving = ref > moving_share * ref.max()
    return {
        "mean_diff": float(diff.mean()),
        "max_diff": float(diff.max()),
        "mean_ref": float(ref.mean()),
        "rel_mean": float(diff.sum() / ref.sum()),
        "rel_applied": float(diff.mean() / applied) if applied else None,
        "rel_rms": float(np.sqrt((diff ** 2).mean() / (ref ** 2).mean())),
        "rel_max": float(diff.max() / ref.max()),
        "rel_per_node": float((diff[moving] / ref[moving]).mean()),
    }


# --------------------------------------------------------------------------- Pareto front
def pareto_front(times, errors) -> list:
    """Indices of the points no other point beats in both time and error (both minimised),
    ordered by time. A point equal to another in both is kept once (the first)."""
    t = np.asarray(times, dtype=float)
    e = np.asarray(errors, dtype=float)
    order = np.lexsort((np.arange(len(t)), e, t))
    front, best = [], np.inf
    for i in order:
        if e[i] < best:
            front.append(int(i))
            best = e[i]
    return front


# --------------------------------------------------------------------------- artifacts
def displacement(run) -> np.ndarray:
    return np.asarray(run.payload["displacement"], dtype=float)


# --------------------------------------------------------------------------- formatting
def pct(x, digits=1):
    return None if x is None else round(100.0 * x, digits)


DISPLAY_UNITS = {"cm": 100.0, "mm": 1000.0, "m": 1.0}


def display_unit(ctx):
    """The unit applied displacements are shown in (params "display_unit", cm by default) and
    its factor from metres."""
    unit = ctx.params.get("display_unit", "cm")
    return unit, DISPLAY_UNITS[unit]


# --------------------------------------------------------------------------- pictures
def boundary_owner(tets: np.ndarray, boundary: np.ndarray) -> np.ndarray:
    """For each boundary triangle, the tetrahedron it belongs to."""
    owner = {}
    for e, t in enumerate(tets):
        for face in ((t[1], t[2], t[3]), (t[0], t[2], t[3]), (t[0], t[1], t[3]), (t[0], t[1], t[2])):
            owner[tuple(sorted(face))] = e
    return np.array([owner[tuple(sorted(f))] for f in boundary], dtype=int)


# Triangle edge colour by element kind name: dark linear, blue corotational, light for the
# nonlinear kinds (TLED, and any kind not named here, e.g. ANP).
KIND_EDGE = {"linear": (0.15, 0.15, 0.15, 0.9), "corotational": (0.2, 0.35, 0.9, 0.9)}
NONLINEAR_EDGE = (1.0, 1.0, 1.0, 0.9)


def draw_deformed(ax, nodes, tets, boundary, u, kinds, vmax=None, view=(22, -58), scale_mm=True,
                  cmap="viridis", values=None, axis_labels=True):
    """The deformed boundary coloured by |u| (or by the nodal scalar `values`, e.g. the difference
    to TLED, in display units), triangle edges coloured by the kind of the element they belong to
    (as in 000 Fig. 10: light edges nonlinear, dark edges linear). `kinds`: each element's kind
    name (element_kind_names)."""
    from matplotlib import cm, colors
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    f = 1000.0 if scale_mm else 1.0
    x = (nodes + u) * f
    mag = np.linalg.norm(u, axis=1) * f if values is None else np.asarray(values)
    tri = np.asarray(boundary)
    owner = boundary_owner(np.asarray(tets), tri)
    face_mag = mag[tri].mean(axis=1)
    norm = colors.Normalize(0.0, vmax if vmax is not None else max(face_mag.max(), 1e-12))
    mapper = cm.ScalarMappable(norm=norm, cmap=cmap)
    faces = mapper.to_rgba(face_mag)
    kinds = np.asarray(kinds)
    if kinds.dtype.kind != "U":
        raise TypeError("draw_deformed: kinds must be element kind names (element_kind_names), not codes")
    edges = [KIND_EDGE.get(str(kinds[o]), NONLINEAR_EDGE) for o in owner]
    coll = Poly3DCollection(x[tri], facecolors=faces, edgecolors=edges, linewidths=0.35)
    ax.add_collection3d(coll)
    lo, hi = (nodes * f).min(axis=0), (nodes * f).max(axis=0)
    c, r = (lo + hi) / 2, (hi - lo).max() / 2
    ax.set_xlim(c[0] - r, c[0] + r)
    ax.set_ylim(c[1] - r, c[1] + r)
    ax.set_zlim(c[2] - r, c[2] + r)
    ax.view_init(*view)
    if axis_labels:
        unit = "mm" if scale_mm else "m"
        ax.set_xlabel(f"x ({unit})", fontsize=7)
        ax.set_ylabel(f"y ({unit})", fontsize=7)
        ax.set_zlabel(f"z ({unit})", fontsize=7)
    ax.tick_params(labelsize=6)
    return mapper


def draw_difference(ax, nodes, tets, boundary, u, kinds, values_mm, vmax, view=(12, 72)):
    """The deformed boundary coloured by a nodal difference in mm (e.g. to all-TLED) on the magma
    scale, without axis labels (it sits under a |u| panel that has them)."""
    return draw_deformed(ax, nodes, tets, boundary, u, kinds, vmax=vmax, view=view, cmap="magma", values=values_mm,
                         axis_labels=False)


def write_vtu(path, nodes, tets, u, kinds, extra_point_data=None):
    """The reference mesh with point data "displacement" (m) and cell data "element_kind" (the
    codes of the artifact's element_kind_legend); ParaView's Warp By Vector shows the deformed shape."""
    import meshio
    point_data = {"displacement": np.asarray(u, dtype=float)}
    for k, v in (extra_point_data or {}).items():
        point_data[k] = np.asarray(v, dtype=float)
    mesh = meshio.Mesh(np.asarray(nodes, dtype=float), [("tetra", np.asarray(tets, dtype=np.int64))],
                       point_data=point_data,
                       cell_data={"element_kind": [np.asarray(kinds, dtype=np.int32)]})
    meshio.write(str(path), mesh, file_format="vtu", binary=True)


# --------------------------------------------------------------------------- summary.md
SUMMARY_HEAD = """## DHD-FEA: dual-mode hybrid explicit FEM (paper 000)

Every experiment below was run by this project's `dhd_sim`; the paper's numbers appear only
beside ours and are labelled as the paper's. What the experiments are and every modelling choice:
[experiments/dhd.md](../experiments/dhd.md). Tables and plots: [dhd/](dhd/).
"""

SECTION_ORDER = ["table1", "table2", "partition", "pareto", "fig9", "liver"]


MODEL_WORDS = {
    "neo_hookean_paper": "the paper's neo-Hookean form (000 eq. 22)",
    "neo_hookean_decoupled": "the decoupled neo-Hookean form of CalculiX and of Miller's TLED",
    "mooney_rivlin": "the decoupled Mooney–Rivlin law (CalculiX's MOONEY-RIVLIN)",
    "ogden": "the decoupled Ogden law (CalculiX's OGDEN)",
    "linear": "linear elasticity",
}


def material_line(ctx) -> str:
    """One sentence naming the material law of every dhd_sim run the report read, and whether
    the config chose it or left `material.model` out (the default is the paper's form, which
    differs from CalculiX's by 5–9 % in reaction: the reader must see which one the numbers are)."""
    seen = {}
    for view in ctx.all_runs():
        m = view.payload.get("material") if isinstance(view.payload, dict) else None
        if not isinstance(m, dict) or "model" not in m:
            continue
        values = seen.setdefault((m["model"], bool(m.get("model_defaulted", False))), ([], [], []))
        for bucket, key in zip(values, ("E", "nu", "density")):
            if m.get(key) is not None and m[key] not in bucket:
                bucket.append(m[key])
    if not seen:
        return ""

    def spread(values, unit):
        values = sorted(values)
        if len(values) == 1:
            return f"{values[0]:g}{unit}"
        return f"{values[0]:g} to {values[-1]:g}{unit} ({len(values)} values)"

    parts = []
    for (model, defaulted), (E, nu, rho) in seen.items():
        how = "the default, `material.model` left out" if defaulted else "chosen in the config"
        parts.append(f"`{model}`, {MODEL_WORDS.get(model, model)}, {how}: E = {spread(E, ' Pa')}, "
                     f"ν = {spread(nu, '')}, ρ = {spread(rho, ' kg/m³')}")
    return "Material of these runs: " + "; ".join(parts) + "."


def append_material_line(ctx, path) -> None:
    """Ends the summary part at `path` with material_line(ctx) (once)."""
    line = material_line(ctx)
    if not line or not path.exists():
        return
    text = path.read_text().rstrip("\n")
    if line not in text:
        write_text_atomic(path, text + "\n\n" + line + "\n\n")


def write_section(ctx, key: str, text: str, facts: dict = None) -> None:
    """Writes this experiment's part of results/dhd/summary.md (and the few numbers the opening
    verdict needs, as JSON, and which run wrote it) and re-assembles the whole file from every
    part present, so the summary is complete whichever experiment ran last. The section ends with
    the material law its runs used (material_line)."""
    if not re.match(r"^[a-z0-9_]+$", key):
        raise ValueError(f"section key {key!r}")
    material = material_line(ctx)
    write_text_atomic(ctx.out(f"{SECTION_DIR}/{key}.md"), text.strip() + ("\n\n" + material if material else "") + "\n")
    if facts is not None:
        write_text_atomic(ctx.out(f"{SECTION_DIR}/{key}.json"), json.dumps(facts, indent=1, sort_keys=True) + "\n")
    name = getattr(ctx, "experiment_name", None)
    if name:
        from pipeline.artifacts import git_commit
        origin = {"experiment": name, "commit": git_commit(), "definition": definition_hash(name)}
        write_text_atomic(ctx.out(f"{SECTION_DIR}/{ORIGIN_DIR}/{key}.json"), json.dumps(origin, indent=1, sort_keys=True) + "\n")
    assemble_summary(ctx)


ORIGIN_DIR = "origin"


def definition_hash(name: str):
    """A hash of what an experiment runs (every run's resolved definition, shared stages included,
    and its paper block): a section written from another definition is out of date. None when
    the experiment does not load."""
    from pipeline import experiment as experiment_mod
    from pipeline.errors import ExperimentError
    from pipeline.hashing import sha256_json
    try:
        exp = experiment_mod.load(name)
    except ExperimentError:
        return None
    return sha256_json({"paper": exp.doc.get("paper"), "runs": [
        [rid, r.kind, r.target, r.mode, r.args, r.config, r.sweep, r.inputs, r.params] for rid, r in exp.runs.items()]})[:16]


def provenance_line(origins: dict, keys: list) -> str:
    """Which runs the sections come from: one commit for all, or each section's experiment and
    commit, and any section whose experiment has changed since it was written."""
    if not keys:
        return ""
    stale = [k for k in keys if k in origins and origins[k].get("definition") is not None
             and definition_hash(origins[k]["experiment"]) not in (None, origins[k]["definition"])]
    commits = {origins[k]["commit"] if k in origins else None for k in keys}
    if len(commits) == 1 and None not in commits and not stale:
        names = sorted({origins[k]["experiment"] for k in keys})
        return (f"All sections below were written at commit `{commits.pop()}` (by {', '.join(names)}); the verdict "
                "is drawn from them.\n")
    parts = []
    for k in keys:
        o = origins.get(k)
        where = f"`{o['experiment']}` at commit `{o['commit']}`" if o else "an unrecorded run"
        parts.append(f"{k} by {where}" + (" (its experiment has changed since: rerun it)" if k in stale else ""))
    return ("The sections below come from separate runs, and the verdict combines them: " + "; ".join(parts)
            + ".\n")


def assemble_summary(ctx) -> None:
    section_dir = ctx.results_dir / SECTION_DIR
    found = {p.stem: p for p in section_dir.glob("*.md")} if section_dir.exists() else {}
    facts = {p.stem: json.loads(p.read_text()) for p in section_dir.glob("*.json")} if section_dir.exists() else {}
    origin_dir = section_dir / ORIGIN_DIR
    origins = {p.stem: json.loads(p.read_text()) for p in origin_dir.glob("*.json")} if origin_dir.exists() else {}
    keys = [k for k in SECTION_ORDER if k in found] + sorted(k for k in found if k not in SECTION_ORDER)
    parts = [SUMMARY_HEAD, provenance_line(origins, keys), verdict(facts)] + \
        read_parts(section_dir, [f"{k}.md" for k in keys])
    write_text_atomic(ctx.out("summary.md"), "\n".join(p for p in parts if p))


# --------------------------------------------------------------------------- the paper's numbers
# Every figure of the paper lives in the "paper" block of its experiment file; reports read it
# from there (ctx.experiment for their own, experiment_paper for another's, e.g. in the verdict).
def experiment_paper(name: str) -> dict:
    """The "paper" block of experiments/<name>.json; {} when the file or the block is absent."""
    from pipeline.paths import EXPERIMENTS
    path = EXPERIMENTS / f"{name}.json"
    return json.loads(path.read_text()).get("paper", {}) if path.exists() else {}


def paper_error_shares(paper: dict) -> list:
    """The shares r (percent) at which 000 Tables 2–3 report an error, from a "paper" block."""
    return sorted({r for name in ("table2", "table3") for r in paper.get(name, {}).get("linear_fraction_percent", [])})


def paper_frame_rates(paper: dict) -> dict:
    """{r percent: frame rate (Hz)} of 000 Table 1, from a "paper" block."""
    t = paper.get("table1", {})
    return dict(zip(t.get("linear_fraction_percent", []), t.get("frame_rate_hz", [])))


def share_range(shares) -> str:
    """"10–40" for the shares [10, 20, 30, 40] (percent)."""
    shares = sorted(shares)
    if not shares:
        return "the paper's shares"
    return f"{shares[0]}" if shares[0] == shares[-1] else f"{shares[0]}–{shares[-1]}"


def _span(values, digits=2, whole_above_10=True):
    values = [v for v in values if v is not None]
    if not values:
        return "–"
    lo, hi = (_f(v, digits, whole_above_10) for v in (min(values), max(values)))
    return lo if lo == hi else f"{lo}–{hi}"


def _f(x, digits=2, whole_above_10=True):
    """Short number for prose: significant digits, whole numbers from 10 on (ratios)."""
    from pipeline.tables import fmt
    x = float(x)
    return str(int(round(x))) if whole_above_10 and abs(x) >= 10 else fmt(x, digits)


# The layer split's error must grow at least this many times when its last layer turns cheap for
# the summary to say the elements near the tool must stay nonlinear.
JUMP = 3.0


def verdict(facts: dict) -> str:
    """The opening "in short" of summary.md, in plain words, from the facts the reports left."""
    agree, differ, why = [], [], []
    t2, t1 = facts.get("table2"), facts.get("table1")
    shares = share_range(paper_error_shares(experiment_paper("dhd_table2")))
    rate0 = paper_frame_rates(experiment_paper("dhd_table1")).get(0)
    part, liver = facts.get("partition"), facts.get("liver")
    if t2:
        _table2_verdict(t2, shares, agree, differ, why)
    if part and part.get("layer_jump") is not None and part["layer_jump"] >= JUMP:
        agree.append("the elements near the tool must stay nonlinear (the paper's operational region): the "
                     f"layer split's error grows {_f(part['layer_jump'], 2)} times or more once its last layer, "
                     "the one under the tool, turns cheap")
    if part and part.get("best_family"):
        liver_too = (f", and on the liver {liver['best_family']} wins too" if liver and liver.get("best_family")
                     == part["best_family"] else "")
        wins = f"{part['best_family']} gives the smallest error at {part['best_wins']} of {part['shares']} shares"
        if part.get("best_strategy", part["best_family"].split(",")[0]) != "layer":
            differ.append(f"the paper's layer split is not the best at equal r: {wins}{liver_too}")
        else:
            agree.append(f"the paper's layer split is the best at equal r: {wins}{liver_too}")
    if t1:
        _table1_verdict(t1, rate0, agree, differ, why)
    if not (agree or differ or why):
        return ""
    out = ["**In short.**\n"]
    if agree:
        out.append("- *Where we agree with the paper:* " + "; ".join(agree) + ".")
    if differ:
        out.append("- *Where we differ:* " + "; ".join(differ) + ".")
    if why:
        out.append("- *Why:* " + "; ".join(why) + ".")
    return "\n".join(out) + "\n"


def _speed_words(s50: float) -> str:
    """Our speed at r = 50 % against all-TLED in words, from the number (faster, slower or the same)."""
    if s50 > 1.02:
        return f"{_f(s50, 3)} times as fast as all-TLED"
    if s50 < 0.98:
        return f"slower than all-TLED ({_f(s50, 3)} times its speed)"
    return f"as fast as all-TLED ({_f(s50, 3)} times its speed)"


def _table1_verdict(t1: dict, rate0, agree: list, differ: list, why: list) -> None:
    """The Table 1 part of the verdict: every claim from the measured ratios, and each one carries
    the timing's busy-machine note (dhd_table1's "busy_note") when the sitting was disturbed."""
    # facts from before the timing recorded the machine's load say so
    busy = t1.get("busy_note", "(machine load not recorded for this timing)") or ""
    first = f" {busy}" if busy else ""
    note = f" {busy.split(':')[0]})" if ":" in busy else first
    s50, p50 = t1.get("speedup_50_ours"), t1.get("speedup_50_paper")
    if s50 is not None and p50:
        if s50 > 1.02 and p50 > 1.02:
            agree.append(f"linear elements make the explicit step faster{first}")
        elif p50 > 1.02:
            differ.append(f"linear elements do not make our explicit step faster, unlike the paper's{first}")
        if abs(s50 / p50 - 1.0) > 0.2:
            differ.append(f"at r = 50 % our step is {_speed_words(s50)}, against the paper's {_f(p50, 3)}{note}")
        else:
            agree.append(f"at r = 50 % our step is {_speed_words(s50)}, the paper's {_f(p50, 3)}{note}")
    if t1.get("c_ours") is not None:
        node = f"{_f(t1['node_ns'], 3)} ns per node of an all-TLED mesh"
        if t1.get("node_ns_linear") is not None:
            node += f", {_f(t1['node_ns_linear'], 3)} ns of an all-linear one"
        ratio = t1["ns_linear"] / t1["ns_tled"]
        kernel = ("the TLED kernel is vectorised, and the linear rows are bound by streaming the assembled "
                  "stiffness matrix and by their instructions per block, see cpp/apps/dhd_sim.md")
        why.append(f"a linear element costs {_f(t1['c_ours'], 2)} of a TLED element in our engine (node work "
                   f"included), {_f(t1['c_paper'], 2)} in the paper's timings: per element and step our linear "
                   f"elements take {_f(t1['ns_linear'], 3)} ns against {_f(t1['ns_tled'], 3)} ns for TLED "
                   f"({_f(ratio, 2)}×" + (f": {kernel}" if ratio > 0.3 else "") + "), and the node phase "
                   f"(gather and central-difference update, {node}) remains{note}")
        why.append(f"absolute speed is not comparable: {_f(t1['steps_per_second_tled'], 3)} steps/s all-TLED on "
                   f"one core here{note} against {_f(rate0, 3) if rate0 else 'the paper’s'} frames/s there, whose "
                   "frames include rendering and an unknown number of steps")


def _table2_verdict(t2: dict, shares: str, agree: list, differ: list, why: list) -> None:
    """The Tables 2–3 part of the verdict: each clause only where the facts the report computed
    (trend of ours and of the paper's, settled or not, the literal reading) support it."""
    ours_grow, paper_grow = t2.get("ours_grow", True), t2.get("paper_grow", True)
    loads_agree = t2.get("larger_load_larger") and t2.get("paper_larger_load_larger", True)
    if ours_grow and paper_grow:
        agree.append("the error of DHD-FEA against all-TLED grows with the share r of linear elements"
                     + (" and with the applied displacement" if loads_agree else "") + " (000 Tables 2–3)")
    elif ours_grow != paper_grow:
        differ.append("our error " + ("grows" if ours_grow else "does not grow") + " at every share r, the paper's "
                      + ("does" if paper_grow else "does not") + " (000 Tables 2–3)")
    state = t2.get("state", "settled")
    for load, ours in sorted(t2["settled_10_40"].items()):
        paper = t2["paper_10_40"].get(load)
        if paper:
            ratio = [p / o for p, o in zip(paper, ours) if o > 0]
            smaller = all(r > 1 for r in ratio)
            differ.append(f"at {load} and r = {shares} % our errors ({state}) are {_span(ours, 2)} %, the paper's "
                          f"{_span(paper, 3, whole_above_10=False)} %: "
                          + (f"{_span(ratio, 2)} times smaller" if smaller else f"{_span(ratio, 2)} times the paper's"
                             if ratio else "not comparable"))
    literal = t2.get("transient") or {}
    if t2.get("transient_10_40") and literal:
        load, vals = sorted(t2["transient_10_40"].items())[0]
        text = (f"the paper compares the two models after 1000 iterations of a motion started by applying the "
                f"displacement at once; read that way (α = {_f(literal['alpha'])} 1/s) we get {_span(vals, 2)} % at "
                f"{load} for r = {shares} %, "
                + ("growing with r like the paper's" if literal.get("grows") and paper_grow else
                   "growing with r" if literal.get("grows") else "not growing at every share"))
        if literal.get("moving") and t2.get("settled"):
            text += (": the block still moves then, and most of such an error is the phase drift between two "
                     "vibrating bodies of slightly different stiffness, so it depends on damping and sampling time, "
                     "which the paper does not give; the settled comparison isolates the error of the linear "
                     "elements themselves")
        why.append(text)


def save(fig, ctx, name: str) -> str:
    plots.save(fig, ctx.out(name))
    return name




# --------------------------------------------------------------------------- engine artifacts
# The only places that know the dhd_sim config and "dhd_result" payload (cpp/apps/dhd_sim.md).


def applied_vector(config: dict) -> np.ndarray:
    """The displacement prescribed on the first "prescribed" entry: the pushed node (m)."""
    return np.asarray(config["boundary"]["prescribed"][0]["displacement"], dtype=float)


def applied_length(config: dict) -> float:
    return float(np.linalg.norm(applied_vector(config)))


def steps_per_second(payload: dict) -> float:
    return float(payload["timing"]["steps_per_second"])


def seconds_per_step(payload: dict) -> float:
    return 1.0 / steps_per_second(payload)


def describe_partition(partition: dict, small_strain=None) -> dict:
    """What a dhd_sim "partition" config asks for: strategy (uniform | layer | distance | strain
    | layers | tags | sphere), the requested share r of cheap elements (None when the strategy
    does not state one), the cheap kind (linear_element) and the nonlinear kind
    (nonlinear_element). A uniform partition needs `small_strain`, the names of the small-strain
    kinds (small_strain_kinds of the run's artifact), to tell whether its element is cheap."""
    p = partition or {}
    kind = p.get("kind", "linear_fraction" if "linear_fraction" in p else "uniform")
    cheap = p.get("linear_element", "linear")
    nonlinear = p.get("nonlinear_element", "tled")
    if kind == "uniform":
        if small_strain is None:
            raise ValueError("describe_partition: a uniform partition needs the small-strain kinds of the legend")
        element = p.get("element", "tled")
        is_cheap = element in small_strain
        return {"strategy": "uniform", "requested_r": 1.0 if is_cheap else 0.0,
                "cheap_kind": element if is_cheap else cheap, "nonlinear_kind": nonlinear if is_cheap else element}
    if kind == "linear_fraction":
        strategy = "layer" if p.get("distance", "euclidean") == "depth" else "distance"
        return {"strategy": strategy, "requested_r": float(p["linear_fraction"]), "cheap_kind": cheap,
                "nonlinear_kind": nonlinear}
    if kind == "strain":
        return {"strategy": "strain", "requested_r": float(p["linear_fraction"]) if "linear_fraction" in p
                else None, "cheap_kind": cheap, "nonlinear_kind": nonlinear}
    return {"strategy": kind, "requested_r": None, "cheap_kind": cheap, "nonlinear_kind": nonlinear}


SPLIT_RULES = {"layer": "the lowest elements", "distance": "the elements farthest from the operating point",
               "strain": "the least strained elements"}


def split_words(rows) -> str:
    """The split the hybrid runs of `rows` asked for, in words, from their configs: "layer split
    (the lowest elements linear, 000 Fig. 10)"; every distinct (strategy, distance measure, cheap
    kind) named once."""
    return split_phrase([(x["strategy"], x["run"].config.get("partition"), x["cheap_kind"]) for x in rows
                         if 0 < x["cheap_elements"] < x["elements"]])


def split_phrase(splits) -> str:
    """[(strategy, partition config, cheap kind)] in words, each distinct split once."""
    kinds = []
    for strategy, partition, cheap in splits:
        measure = (partition or {}).get("distance", "euclidean")
        key = (strategy, measure if strategy == "distance" else None, cheap)
        if key not in kinds:
            kinds.append(key)
    out = []
    for strategy, measure, cheap in kinds:
        rule = SPLIT_RULES.get(strategy, f"the elements the {strategy} rule picks")
        if measure:
            rule += f" ({measure} distance)"
        out.append(f"{strategy} split ({rule} {cheap}" + (", 000 Fig. 10)" if strategy == "layer" else ")"))
    return " and ".join(out) or "no hybrid run"


def cheap_kinds(rows) -> str:
    """The cheap element kind(s) the runs use: "linear", or "linear or corotational"."""
    kinds = sorted({x["cheap_kind"] for x in rows if x["cheap_elements"] > 0})
    return " or ".join(kinds) or "cheap"


def split_record(config: dict, payload: dict) -> dict:
    """The split a run asked for and the one it realised (from the artifact's element kinds and
    legend). Raises when they disagree: exactly round(r · m) cheap elements, all of the cheap
    kind, and every other element of the nonlinear kind. "tled_elements" counts the nonlinear
    ones (TLED, or ANP where the partition asks for it)."""
    small_strain = small_strain_kinds(payload)
    want = describe_partition(config.get("partition"), small_strain)
    counts = kind_counts(payload)
    m = sum(counts.values())
    cheap = sum(counts[k] for k in small_strain)
    for name, n in counts.items():
        if n and name not in (want["cheap_kind"], want["nonlinear_kind"]):
            raise ValueError(f"partition asked for {want['cheap_kind']} cheap elements and {want['nonlinear_kind']} "
                             f"nonlinear ones, the run has {n} {name} ones")
    if want["requested_r"] is not None:
        expected = int(np.floor(want["requested_r"] * m + 0.5))
        if cheap != expected:
            raise ValueError(f"partition asked for r = {want['requested_r']} of {m} elements "
                             f"({expected} cheap), the run has {cheap}")
    return dict(want, r=cheap / m, elements=m, cheap_elements=cheap, tled_elements=m - cheap,
                counts=counts)


def sim_rows(ctx, sim_stage: str):
    """One dict per run of a dhd_sim stage: the run, its realised split, its applied displacement."""
    rows = []
    for run in ctx.runs(sim_stage):
        rec = split_record(run.config, run.payload)
        rows.append(dict(rec, run=run, stage=sim_stage, applied=applied_length(run.config)))
    return rows


def errors_against_reference(rows):
    """{applied length: rows sorted by r}, each row given "error" (displacement_error against the
    all-TLED run of the same load, found among `rows`) and "seconds_per_step"."""
    refs = {}
    for g in rows:
        if g["cheap_elements"] == 0:
            refs.setdefault(round(g["applied"], 12), g)
    out = {}
    for g in rows:
        load = round(g["applied"], 12)
        if load not in refs:
            raise ValueError(f"no all-TLED reference run for the load {load} m")
        ref = refs[load]
        g["error"] = displacement_error(displacement(g["run"]), displacement(ref["run"]), applied=load)
        g["seconds_per_step"] = seconds_per_step(g["run"].payload)
        g["ref_seconds_per_step"] = seconds_per_step(ref["run"].payload)
        out.setdefault(load, []).append(g)
    return {load: sorted(group, key=lambda x: x["r"]) for load, group in sorted(out.items())}


# --------------------------------------------------------------------------- cost model
def cost_model(timing_payload: dict):
    """Time per step of a configuration from a "dhd_timing" artifact. The error runs are too
    short (about 0.05 s of stepping each) to time reliably on a shared machine, so a
    configuration with n_k elements of kind k out of m is given t = Σ_k (n_k / m) t_k, t_k the
    best-of-repeats time per step of the uniform all-k run on the same mesh and scene (the node
    phase is the same in every run, so it is carried along pro rata). Returns ({kind: t_k},
    [(mixed run, measured t, modelled t)]): the mixed runs of the timing stage check the model."""
    uniform, mixed = {}, []
    threads = min(r["threads"] for r in timing_payload["runs"])
    runs = [r for r in timing_payload["runs"] if r["threads"] == threads]
    for run in runs:
        present = [k for k, n in run["counts"].items() if n > 0]
        if len(present) == 1:
            uniform[present[0]] = 1.0 / run["steps_per_second"]
    for run in runs:
        if sum(1 for n in run["counts"].values() if n > 0) > 1:
            mixed.append((run, 1.0 / run["steps_per_second"], model_time(uniform, run["counts"])))
    return uniform, mixed


def model_time(uniform: dict, counts: dict) -> float:
    m = sum(counts.values())
    return sum(n / m * uniform[k] for k, n in counts.items() if n > 0)


def at_share(row: dict, r: float) -> bool:
    """Whether a run's realised share is the requested r (round(r · m) cheap elements)."""
    return row["cheap_elements"] == int(np.floor(r * row["elements"] + 0.5))
