"""The material and boundary blocks of the CalculiX stages, read with dhd_sim's syntax and
semantics (cpp/apps/dhd_sim.md), so that one experiment can hand the same blocks to dhd_sim and
to CalculiX and both solve the same scene.

material:  {"model": "linear" | "neo_hookean_decoupled", "E": 5000, "nu": 0.35, "density": ...}
           {"model": "mooney_rivlin", "C10", "C01", "K"} | {"model": "ogden", "mu": [..], "alpha": [..], "K"}
boundary:  {"fixed": [set name | {selector, "components": "xyz"}],
            "prescribed": [{selector, "displacement": [x, y, z], "components": "xyz",
                            "ramp_time", "ramp"}],
            "forces": [{selector, "force": [x, y, z], "per": "node" | "total",
                        "ramp_time", "ramp"}]}
selector:  exactly one of "set", "nodes", "nearest", "sphere" {center, radius}, "box" {min, max}

Constraints apply in the order fixed, then prescribed; a later entry overrides an earlier one
on the same node and component, and each entry's reaction is the sum over the components it
owns in the end. Ramps describe time histories of the explicit solver; a static step ramps
every value linearly over the step, so they are accepted and ignored here, as dhd_sim's static
solver does.
"""
import numpy as np

from pipeline.config_reader import ConfigReader

# 000 §3.1: the defaults dhd_sim uses too.
DEFAULT_E = 5000.0
DEFAULT_NU = 0.35
SELECTORS = ("set", "nodes", "nearest", "sphere", "box")


# --------------------------------------------------------------------------- material
def read_material(reader: ConfigReader) -> dict:
    """Elastic constants of the model and the CalculiX card that represents it."""
    reader.require_object()
    if reader.raw("model", required=True) == "neo_hookean_paper":
        reader.fail("\"linear\", \"neo_hookean_decoupled\", \"mooney_rivlin\" or \"ogden\": CalculiX's "
                    "NEO HOOKE is the decoupled form; the paper's form (000 eq. 14) has no CalculiX "
                    "counterpart", "model")
    model = reader.choice("model", ["linear", "neo_hookean_decoupled", "mooney_rivlin", "ogden"])
    if model in ("mooney_rivlin", "ogden"):
        info = _read_invariant_law(reader, model)
    else:
        E = reader.number("E", DEFAULT_E, positive=True)
        nu = reader.number("nu", DEFAULT_NU)
        if not -1.0 < nu < 0.5:
            reader.fail("a Poisson ratio in (-1, 0.5)", "nu")
        mu = E / (2.0 * (1.0 + nu))
        K = E / (3.0 * (1.0 - 2.0 * nu))
        info = {"model": model, "E": E, "nu": nu, "mu": mu, "bulk_modulus": K,
                "lambda": E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu))}
    if reader.has("density"):
        reader.number("density", positive=True)  # statics: mass plays no part
    reader.reject_unknown()
    if "E" not in info:  # the small-strain constants the law linearises to
        mu, K = info["mu"], info["bulk_modulus"]
        info["lambda"] = K - 2.0 * mu / 3.0
        info["E"] = 9.0 * K * mu / (3.0 * K + mu)
        info["nu"] = (3.0 * K - 2.0 * mu) / (2.0 * (3.0 * K + mu))
    if model == "linear":
        info["ccx_card"] = "*ELASTIC"
        info["ccx_constants"] = [info["E"], info["nu"]]  # as given
    elif model == "neo_hookean_decoupled":
        # CalculiX NEO HOOKE: U = C10 (Ibar1 - 3) + (J - 1)^2 / D1, the decoupled form
        # W = mu/2 (Ibar1 - 3) + K/2 (J - 1)^2, hence C10 = mu/2 and D1 = 2/K.
        info["ccx_card"] = "*HYPERELASTIC, NEO HOOKE"
        info["C10"] = mu / 2.0
        info["D1"] = 2.0 / K
        info["ccx_constants"] = [info["C10"], info["D1"]]
    return info


def _read_invariant_law(reader: ConfigReader, model: str) -> dict:
    """Mooney-Rivlin and Ogden with dhd_sim's constants (material/mooney_rivlin.hpp, ogden.hpp)
    and CalculiX's: MOONEY-RIVLIN U = C10 (Ibar1 - 3) + C01 (Ibar2 - 3) + (J - 1)^2 / D1 is ours
    with D1 = 2/K; OGDEN, N=n U = sum 2 mu_i / alpha_i^2 (sum_k lbar_k^alpha_i - 3) + sum (J - 1)^(2i) / D_i
    is ours (sum mu_p / alpha_p (...)) with mu_i = mu_p alpha_p / 2, D1 = 2/K and no higher
    volumetric terms. CalculiX does not read D2 = 0 as "no term" (N = 2 with two equal terms
    then differs from N = 1 by 1.3 % in a uniaxial test), so D2 = D3 = 1e30 make them vanish."""
    K = reader.number("K", positive=True)
    if model == "mooney_rivlin":
        c10, c01 = reader.number("C10"), reader.number("C01")
        if not c10 + c01 > 0:
            reader.fail("C10 + C01 > 0 (the shear modulus is 2 (C10 + C01))", "C01")
        return {"model": model, "mu": 2.0 * (c10 + c01), "bulk_modulus": K, "C10": c10, "C01": c01,
                "D1": 2.0 / K, "ccx_card": "*HYPERELASTIC, MOONEY-RIVLIN", "ccx_constants": [c10, c01, 2.0 / K]}
    mu = reader.raw("mu", required=True)
    alpha = reader.raw("alpha", required=True)
    ok = (isinstance(mu, list) and isinstance(alpha, list) and 1 <= len(mu) <= 3 and len(alpha) == len(mu)
          and all(isinstance(x, (int, float)) and not isinstance(x, bool) for x in mu + alpha)
          and all(a != 0 for a in alpha))
    if not ok:
        reader.fail("arrays mu and alpha of one length 1 to 3, every alpha non-zero", "mu")
    shear = sum(0.5 * m * a for m, a in zip(mu, alpha))
    if not shear > 0:
        reader.fail("terms with sum mu_p alpha_p > 0", "mu")
    constants = []
    for m, a in zip(mu, alpha):
        constants += [0.5 * m * a, a]
    constants += [2.0 / K] + [1e30] * (len(mu) - 1)
    return {"model": model, "mu": shear, "bulk_modulus": K, "mu_p": list(mu), "alpha_p": list(alpha),
            "ccx_card": f"*HYPERELASTIC, OGDEN, N={len(mu)}", "ccx_constants": constants}


# --------------------------------------------------------------------------- node selection
def select_nodes(entry: ConfigReader, nodes: np.ndarray, node_sets: dict):
    """(name, sorted node indices) of an entry's selector, as dhd_sim names them."""
    present = [k for k in SELECTORS if entry.has(k)]
    if len(present) != 1:
        entry.fail("exactly one node selector of \"set\", \"nodes\", \"nearest\", \"sphere\", "
                   "\"box\"")
    n = len(nodes)
    if entry.has("set"):
        name = entry.string("set")
        if name not in node_sets:
            entry.fail("the name of a node set of the mesh (" + ", ".join(sorted(node_sets))
                       + ")", "set")
        ids = [int(i) for i in node_sets[name]]
    elif entry.has("nodes"):
        v = entry.raw("nodes")
        if not (isinstance(v, list) and all(isinstance(i, int) and not isinstance(i, bool)
                                            for i in v)):
            entry.fail("a list of node indices", "nodes")
        bad = [i for i in v if not 0 <= i < n]
        if bad:
            entry.fail(f"node indices in [0, {n - 1}] (got {bad[0]})", "nodes")
        ids, name = list(v), "nodes"
    elif entry.has("nearest"):
        p = np.asarray(entry.vector("nearest", 3))
        # argmin returns the lowest index on ties, as dhd_sim does.
        ids = [int(np.argmin(((nodes - p) ** 2).sum(axis=1)))]
        name = f"node {ids[0]}"
    elif entry.has("sphere"):
        s = entry.at("sphere").require_object()
        c = np.asarray(s.vector("center", 3))
        r = s.number("radius", positive=True)
        s.reject_unknown()
        ids = np.flatnonzero(np.linalg.norm(nodes - c, axis=1) <= r).tolist()
        name = "sphere"
    else:
        b = entry.at("box").require_object()
        lo, hi = np.asarray(b.vector("min", 3)), np.asarray(b.vector("max", 3))
        b.reject_unknown()
        tol = 1e-9 * np.linalg.norm(nodes.max(axis=0) - nodes.min(axis=0))
        inside = np.all((nodes >= lo - tol) & (nodes <= hi + tol), axis=1)
        ids = np.flatnonzero(inside).tolist()
        name = "box"
    ids = sorted(set(ids))
    if not ids:
        entry.fail("a node selection that matches at least one node")
    return name, ids


def read_components(entry: ConfigReader):
    text = entry.raw("components", "xyz")
    comps = [{"x": 0, "y": 1, "z": 2}.get(ch, -1) for ch in text] if isinstance(text, str) else []
    if not comps or -1 in comps or len(set(comps)) != len(comps):
        entry.fail("a non-empty subset of \"xyz\" without repeats", "components")
    return sorted(comps)


def _accept_ramp(entry: ConfigReader):
    if entry.has("ramp_time"):
        entry.number("ramp_time", minimum=0.0)
    if entry.has("ramp"):
        entry.choice("ramp", ["linear", "smooth"])


# --------------------------------------------------------------------------- boundary
class Boundary:
    """Resolved constraints and loads.

    constraints: [{"name", "nodes", "components", "values"}] in application order;
    owner: {(node, component): constraint index} after overriding;
    value: {(node, component): prescribed displacement (m)};
    loads: {(node, component): force (N)}."""

    def __init__(self):
        self.constraints = []
        self.owner = {}
        self.value = {}
        self.loads = {}

    def constrain(self, name, ids, components, values):
        k = len(self.constraints)
        self.constraints.append({"name": name, "nodes": ids, "components": components})
        for n in ids:
            for c in components:
                self.owner[(n, c)] = k
                self.value[(n, c)] = float(values[c])

    def constrained_nodes(self):
        return sorted({n for n, _ in self.owner})

    def reactions(self, node_force):
        """Per constraint: the sum of the reaction components it owns (dhd_sim's definition).
        node_force(n) -> [fx, fy, fz] of constrained node n."""
        out = []
        for k, con in enumerate(self.constraints):
            total = np.zeros(3)
            for n in con["nodes"]:
                f = node_force(n)
                for c in con["components"]:
                    if self.owner.get((n, c)) == k:
                        total[c] += f[c]
            out.append({"name": con["name"], "force": total.tolist()})
        return out


def read_boundary(reader: ConfigReader, nodes: np.ndarray, node_sets: dict) -> Boundary:
    reader.require_object()
    bc = Boundary()
    fixed = reader.at("fixed", default=[], required=False)
    if not isinstance(fixed.value, list):
        fixed.fail("a list of node-set names or {selector, \"components\"} objects")
    for k, item in enumerate(fixed.value):
        where = f"{fixed.pointer}/{k}"
        if isinstance(item, str):
            entry = ConfigReader({"set": item}, where, fixed.source)
            name, ids = select_nodes(entry, nodes, node_sets)
            comps = [0, 1, 2]
        else:
            entry = ConfigReader(item, where, fixed.source).require_object()
            name, ids = select_nodes(entry, nodes, node_sets)
            comps = read_components(entry)
            entry.reject_unknown()
        bc.constrain("fixed " + name, ids, comps, [0.0, 0.0, 0.0])

    pres = reader.at("prescribed", default=[], required=False)
    if not isinstance(pres.value, list):
        pres.fail("a list of {selector, \"displacement\": [x, y, z], \"components\"}")
    for k in range(len(pres.value)):
        entry = ConfigReader(pres.value[k], f"{pres.pointer}/{k}", pres.source).require_object()
        name, ids = select_nodes(entry, nodes, node_sets)
        values = entry.vector("displacement", 3)
        comps = read_components(entry)
        _accept_ramp(entry)
        entry.reject_unknown()
        bc.constrain("prescribed " + name, ids, comps, values)

    forces = reader.at("forces", default=[], required=False)
    if not isinstance(forces.value, list):
        forces.fail("a list of {selector, \"force\": [x, y, z], \"per\": \"node\" | \"total\"}")
    for k in range(len(forces.value)):
        entry = ConfigReader(forces.value[k], f"{forces.pointer}/{k}", forces.source)
        entry.require_object()
        _, ids = select_nodes(entry, nodes, node_sets)
        f = np.asarray(entry.vector("force", 3))
        if entry.choice("per", ["node", "total"], "node") == "total":
            f = f / len(ids)
        _accept_ramp(entry)
        entry.reject_unknown()
        for n in ids:
            for c in range(3):
                if f[c] != 0.0:
                    bc.loads[(n, c)] = bc.loads.get((n, c), 0.0) + float(f[c])
    for key in ("gravity", "probe"):
        if reader.has(key):
            reader.fail(f"no \"{key}\" (not modelled by the CalculiX stage)", key)
    reader.reject_unknown()
    if not bc.owner:
        reader.fail("at least one fixed or prescribed component (otherwise the body has "
                    "rigid-body modes)")
    for (n, c) in bc.loads:
        if (n, c) in bc.owner:
            reader.fail(f"no force on a constrained component (node {n}, component "
                        f"{'xyz'[c]}): CalculiX does not report it as part of the reaction",
                        "forces")
    return bc
