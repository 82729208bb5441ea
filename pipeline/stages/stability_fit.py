"""Marquardt fits under stress -> "stability_fit" v1.

On RPIM datasets of the plate (forces along one axis), marquardt_fit is driven where it can
break:

- noise: Gaussian noise of relative level σ (× the largest |u| of the dataset) added to every
  surface displacement of the training cases (seeded); cross-validation chooses the orders;
  the fit is checked against the exact superposition of the clean unit solutions;
- orders too high for the data: fixed orders beyond what the load cases can determine;
- conditioning: the largest condition number of the normal equations over every CV candidate,
  for the scaled Legendre basis and for raw monomials of SI coordinates;
- start and damping: the relations are linear in their coefficients, so Levenberg–Marquardt
  from b = 0 reaches the same least-squares minimum whatever the initial damping d₀ (Ceres'
  trust region 1/d₀); d₀ is swept over 20 decades with a small iteration limit, the one knob
  that can keep it from getting there.

Config:
  dataset: rpim_dataset artifact (forces along `axis`), axis: "x" | "y" | "z"
  noise: [σ], seed, cv: marquardt_fit cv block,
  high_orders: [{"name", "orders": marquardt_fit orders block}],
  damping: [d₀], damping_max_iterations, damping_orders (fixed orders of these fits),
  damping_tight: [{"initial_damping", "max_iterations"}] (iteration limits too small on purpose)
"""
# Executables this stage runs: part of its cache key (pipeline/runner.py).
TOOLS = ("marquardt_fit",)

import json
import tempfile
from pathlib import Path

import numpy as np

from pipeline.artifacts import write_artifact
from pipeline.stages.stability_common import run_tool, tool_hashes

SCHEMA = "stability_fit"
TOOL = "pipeline.stages.stability_fit"


def noisy_copy(path, folder, sigma, seed):
    from pipeline.paths import ROOT
    with open(ROOT / path) as f:
        doc = json.load(f)
    rng = np.random.default_rng(seed)
    cases = doc["payload"]["cases"]
    scale = max(np.abs(np.array(c["top_displacement"])).max() for c in cases)
    for c in cases:
        u = np.array(c["top_displacement"])
        c["top_displacement"] = (u + sigma * scale * rng.standard_normal(u.shape)).tolist()
    doc["provenance"]["config"] = {"noise": sigma, "seed": seed, "of": str(path)}
    out = Path(folder) / f"noisy_{sigma:g}.json"
    out.write_text(json.dumps(doc))
    return str(out), float(scale)


def summary_of_fit(payload, axis):
    sel = payload["selection"][axis]
    comps = {}
    for c, s in sel["components"].items():
        comps[c] = {"surface": s["surface"], "parameter_order": s["parameter_order"],
                    "surface_condition": s["surface_fit"]["condition"],
                    "surface_iterations": s["surface_fit"]["max_iterations"]}
    check = payload["check"][axis]["errors"]
    training = payload["training"][axis]["fit_vs_data"]
    ff = sel["force_fit"]
    return {"force_order": sel["force_order"],
            "force_fit": {**{k: ff[k] for k in ("condition", "iterations", "max_iterations", "termination", "rmse",
                                                "final_cost") if k in ff},
                          "steps": len(ff.get("damping_history", []))},
            "components": comps,
            "check_rmse": check["rmse"], "check_reference_rms": check["reference_rms"],
            "training_rmse": training["rmse"]}


def max_condition(cv_payload):
    worst, refused = 0.0, {}
    for t in cv_payload["tables"]:
        for c in t["candidates"]:
            if c.get("max_condition") is not None:
                worst = max(worst, c["max_condition"])
            if c["status"] != "ok":
                refused[c["status"]] = refused.get(c["status"], 0) + 1
    return worst, refused


def run(ctx):
    cfg = ctx.config
    axis = cfg["axis"]
    rows_noise, rows_orders, rows_cond, rows_damping = [], [], [], []
    with tempfile.TemporaryDirectory(prefix="stability_fit_") as tmp:
        for sigma in cfg["noise"]:
            path, scale = noisy_copy(cfg["dataset"], tmp, sigma, cfg["seed"]) if sigma > 0 else (cfg["dataset"], None)
            fit = run_tool("marquardt_fit", {"datasets": {axis: path}, "cv": cfg["cv"], "timing": {"evaluations": 0}},
                           mode="fit")
            row = {"noise": sigma, **fit.as_json()}
            if fit.ok:
                row.update(summary_of_fit(fit.payload, axis))
            rows_noise.append(row)
            ctx.log(f"noise {sigma}: exit {fit.code} {fit.message}")
        for case in cfg["high_orders"]:
            fit = run_tool("marquardt_fit", {"datasets": {axis: cfg["dataset"]}, "orders": case["orders"],
                                             "timing": {"evaluations": 0}}, mode="fit")
            rows_orders.append({"name": case["name"], "orders": case["orders"], **fit.as_json()})
            ctx.log(f"orders {case['name']}: exit {fit.code} {fit.message}")
    for basis, scaling in (("legendre", "unit_interval"), ("monomial", "unit_interval"), ("monomial", "none")):
        cv = run_tool("marquardt_fit", {"datasets": {axis: cfg["dataset"]}, "basis": basis, "input_scaling": scaling,
                                        "cv": cfg["cv"]}, mode="cv")
        row = {"basis": basis, "input_scaling": scaling, **cv.as_json()}
        if cv.ok:
            row["max_condition"], row["refused"] = max_condition(cv.payload)
            # Condition of the chosen surface fit of every component, against its order.
            row["by_order"] = []
            for t in cv.payload["tables"]:
                if t.get("relation") == "surface":
                    for c in t["candidates"]:
                        row["by_order"].append({"component": t.get("component"), "model": t.get("model"),
                                                "label": c.get("label"), "parameters": c.get("parameters"),
                                                "status": c["status"], "max_condition": c.get("max_condition")})
        rows_cond.append(row)
        ctx.log(f"cv {basis}/{scaling}: exit {cv.code}")
    trials = [(d0, cfg["damping_max_iterations"]) for d0 in cfg["damping"]]
    trials += [(t["initial_damping"], t["max_iterations"]) for t in cfg.get("damping_tight", [])]
    for d0, limit in trials:
        fit = run_tool("marquardt_fit", {"datasets": {axis: cfg["dataset"]}, "orders": cfg["damping_orders"],
                                         "solver": {"initial_damping": d0, "max_iterations": limit},
                                         "timing": {"evaluations": 0}}, mode="fit")
        row = {"initial_damping": d0, "max_iterations": limit, **fit.as_json()}
        if fit.ok:
            row.update(summary_of_fit(fit.payload, axis))
        rows_damping.append(row)
        ctx.log(f"d0 {d0}: exit {fit.code} {fit.message}")
    payload = {"axis": axis, "noise": rows_noise, "high_orders": rows_orders, "conditioning": rows_cond,
               "damping": rows_damping, "seed": cfg["seed"], "tools": tool_hashes(TOOLS)}
    write_artifact(ctx.out_path, SCHEMA, 1, TOOL, cfg, payload, inputs=[cfg["dataset"]], seed=cfg["seed"])
