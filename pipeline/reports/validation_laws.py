"""results/validation/laws*: dhd_sim's static solve against CalculiX for the hyperelastic laws
CalculiX has (Mooney-Rivlin, Ogden N = 1..3) on one block under homogeneous and
non-homogeneous loading.

params:
  "comparisons": [{"case": name, "ccx": stage, "dhd": stage, "uniaxial": true|false}]
      the ccx and dhd stages sweep the same "material" blocks; runs are paired by that block;
      "uniaxial": the case is the homogeneous one, with the closed-form top force beside them,
  "block": {"area": m², "height": m}  the block's top area and height (for that force).
"""
import json

import numpy as np
from scipy.optimize import brentq

from pipeline.reports.dhd_common import displacement_error
from pipeline.reports.validation_calculix import (_along, _dhd_displacement, _prescribed_top, _rel,
                                                  _top_reaction_vector)
from pipeline.tables import write_table


def _law(material: dict) -> str:
    """The law in words with its constants, as the config gives them."""
    if material["model"] == "mooney_rivlin":
        return f"Mooney-Rivlin C10 = {material['C10']:g}, C01 = {material['C01']:g} Pa"
    terms = ", ".join(f"({m:g}, {a:g})" for m, a in zip(material["mu"], material["alpha"]))
    return f"Ogden N = {len(material['mu'])} (mu_p Pa, alpha_p) = {terms}"


def _energy(material: dict, l1: float, l2: float) -> float:
    """W of the law (dhd_sim's constants) at principal stretches (l1, l2, l2)."""
    J = l1 * l2 * l2
    b = J ** (-1.0 / 3.0)
    vol = 0.5 * material["K"] * (J - 1.0) ** 2
    if material["model"] == "mooney_rivlin":
        I1 = b * b * (l1 * l1 + 2 * l2 * l2)
        I2 = b ** 4 * (2 * l1 * l1 * l2 * l2 + l2 ** 4)
        return material["C10"] * (I1 - 3) + material["C01"] * (I2 - 3) + vol
    return sum(m / a * ((b * l1) ** a + 2 * (b * l2) ** a - 3)
               for m, a in zip(material["mu"], material["alpha"])) + vol


def uniaxial_force(material: dict, stretch: float, area: float) -> float:
    """Top force of a homogeneous uniaxial stretch with traction-free lateral faces: the lateral
    stretch l2 where dW/dl2 = 0, then dW/dl1 times the reference area (central differences of W;
    their error, ~1e-9 relative, is far below the differences tabulated)."""
    h = 1e-6
    lateral = lambda l2: (_energy(material, stretch, l2 + h) - _energy(material, stretch, l2 - h)) / (2 * h)
    l2 = brentq(lateral, 0.5, 2.0, xtol=1e-15)
    return area * (_energy(material, stretch + h, l2) - _energy(material, stretch - h, l2)) / (2 * h)


def _key(config) -> str:
    return json.dumps(config["material"], sort_keys=True)


def comparison_rows(ctx):
    rows, worst = [], {}
    for case in ctx.params["comparisons"]:
        dhd_runs = {_key(run.config): run for run in ctx.runs(case["dhd"])}
        for run in ctx.runs(case["ccx"]):
            material = run.config["material"]
            pl = run.payload
            dhd = dhd_runs.get(_key(run.config))
            u_ccx = np.asarray(pl["displacement"])
            u_dhd = _dhd_displacement(dhd.payload) if dhd else None
            direction = _prescribed_top(run.config)
            direction = direction / np.linalg.norm(direction)
            err = _rel(u_dhd, u_ccx) if u_dhd is not None else None
            if err is not None:
                worst[(case["case"], _law(material))] = err
            f_ccx = _top_reaction_vector(pl)
            f_dhd = _top_reaction_vector(dhd.payload) if dhd else None
            a = pl["analysis"]
            exact = None
            if case.get("uniaxial"):
                block = ctx.params["block"]
                motion = _prescribed_top(run.config)
                exact = uniaxial_force(material, 1.0 + motion[2] / block["height"], block["area"]) * np.sign(motion[2])
            rows.append([case["case"], _law(material), err,
                         displacement_error(u_dhd, u_ccx)["rel_max"] if u_dhd is not None else None,
                         float(np.max(np.linalg.norm(u_ccx.reshape(-1, 3), axis=1))) * 1e3,
                         _along(f_dhd, direction), _along(f_ccx, direction), exact,
                         _rel(f_dhd, f_ccx) if f_dhd is not None and f_ccx is not None else None,
                         f"{a['increments_taken']}/{a['iterations']}"])
    return rows, worst


def report(ctx):
    rows, worst = comparison_rows(ctx)
    md = write_table(
        ctx, "laws_vs_calculix",
        ["case", "law", "‖u_dhd − u_ccx‖/‖u_ccx‖", "max_i ‖u_dhd − u_ccx‖_i / max_i ‖u_ccx‖_i",
         "max ‖u_ccx‖ (mm)", "top reaction dhd (N)", "top reaction CalculiX (N)",
         "top reaction closed form (N)", "‖F_dhd − F_ccx‖/‖F_ccx‖",
         "ccx increments/iterations"],
        rows,
        "dhd_sim's static solve (Newton, 10 increments) vs. CalculiX (NLGEOM, *HYPERELASTIC "
        "MOONEY-RIVLIN / OGDEN, C3D4 on the same tetrahedra) on a 6 × 6 × 4 cm block, the top "
        "moved by 20 % of the height. 'uniaxial': bottom sliding on z = 0, lateral faces free "
        "(a homogeneous deformation); 'clamped': bottom fixed, top moved rigidly (non-homogeneous). "
        "Reactions are the top face's total force along the prescribed motion; the closed form "
        "(uniaxial only) is the homogeneous solution of the law, computed in the report.")
    lines = ["## Tissue laws against CalculiX\n", md]
    if worst:
        (case, law), err = max(worst.items(), key=lambda kv: kv[1])
        forces = [r[8] for r in rows if r[8] is not None]
        exact = [abs(r[5] - r[7]) / abs(r[7]) for r in rows if r[7] is not None and r[5] is not None]
        lines.append(f"In words: on every case and law the two solvers agree to a relative L2 "
                     f"displacement difference of at most {err:.1e} (largest: {case}, {law}); their "
                     f"top reactions differ by at most {max(forces):.1e} relative"
                     + (f", and dhd_sim's homogeneous (uniaxial) reactions are the closed form's to "
                        f"{max(exact):.1e}" if exact else "")
                     + ". The two codes share only the mesh and the constants.\n")
    else:
        lines.append("No dhd_sim runs were available for this comparison.\n")
    lines.append("CalculiX has no built-in counterpart of the transversely isotropic law "
                 "(quadratic fibre term in the isochoric I4; its ELASTIC_FIBER material is an "
                 "exponential fibre law of another form, not tried here) nor of Prony-series relaxation "
                 "of a hyperelastic law, so those two are not in this table. They are checked "
                 "instead against closed forms: stretch along and across the fibre, P and dP "
                 "against finite differences, rotating body and fibre together, and the isotropic "
                 "limit (tests/cpp/test_transversely_isotropic.cpp); a held step strain relaxing "
                 "exactly as the Prony series, its limits g → 0, τ → 0 and τ → ∞, energy "
                 "dissipated over a closed cycle, and an explicit press that settles on the static "
                 "solution of the relaxed law (tests/cpp/test_viscoelastic.cpp).\n")
    ctx.out("laws_summary.md").write_text("\n".join(lines))
