"""Independent small-strain FEM in numpy/scipy for the stability stages: tet geometry, the
linear stiffness and lumped mass of a tet_mesh, and the highest natural frequency, from which
the exact stability limit of the undamped central-difference scheme follows (Δt ≤ 2/ω_max).

This is a second implementation, on purpose: the step limit measured with dhd_sim is compared
with it, and both with the paper's estimate Δt_cr = L_e / c (000 eqs. 34–35).
"""
import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla


def lame(E, nu):
    mu = E / (2 * (1 + nu))
    lam = E * nu / ((1 + nu) * (1 - 2 * nu))
    return mu, lam


def wave_speed(E, nu, rho):
    """Dilatational wave speed, 000 eq. 35."""
    return np.sqrt(E * (1 - nu) / (rho * (1 + nu) * (1 - 2 * nu)))


def tet_geometry(X, T):
    """Per tet: signed volume, smallest altitude 3V/A_max, shortest edge, smallest dihedral angle (deg)."""
    P = X[T]  # (m, 4, 3)
    e1, e2, e3 = P[:, 1] - P[:, 0], P[:, 2] - P[:, 0], P[:, 3] - P[:, 0]
    vol = np.einsum("ij,ij->i", e1, np.cross(e2, e3)) / 6.0
    faces = [(1, 2, 3), (0, 2, 3), (0, 1, 3), (0, 1, 2)]
    normals = []
    areas = []
    for a, b, c in faces:
        n = np.cross(P[:, b] - P[:, a], P[:, c] - P[:, a])
        normals.append(n)
        areas.append(0.5 * np.linalg.norm(n, axis=1))
    areas = np.array(areas).T
    altitude = 3 * np.abs(vol) / areas.max(axis=1)
    edges = [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)]
    edge_len = np.array([np.linalg.norm(P[:, j] - P[:, i], axis=1) for i, j in edges]).T
    # Dihedral angle at the edge shared by faces f and g: π − angle between outward normals.
    dihedral = []
    for f in range(4):
        for g in range(f + 1, 4):
            nf = normals[f] / np.linalg.norm(normals[f], axis=1)[:, None]
            ng = normals[g] / np.linalg.norm(normals[g], axis=1)[:, None]
            # Orient both outward: the normal of face f must point away from node f.
            sf = np.sign(np.einsum("ij,ij->i", nf, P[:, faces[f][0]] - P[:, f]))
            sg = np.sign(np.einsum("ij,ij->i", ng, P[:, faces[g][0]] - P[:, g]))
            c = np.einsum("ij,ij->i", nf * sf[:, None], ng * sg[:, None])
            dihedral.append(180.0 - np.degrees(np.arccos(np.clip(c, -1, 1))))
    dihedral = np.array(dihedral).T
    return {"volume": vol, "altitude": altitude, "min_edge": edge_len.min(axis=1),
            "min_dihedral_deg": dihedral.min(axis=1), "max_dihedral_deg": dihedral.max(axis=1)}


def shape_gradients(X, T):
    """∇N (m, 4, 3) and volumes (m) of linear tets."""
    P = X[T]
    J = np.stack([P[:, 1] - P[:, 0], P[:, 2] - P[:, 0], P[:, 3] - P[:, 0]], axis=2)  # columns = edges
    Jinv = np.linalg.inv(J)  # rows: ∇ξ_k
    g = np.zeros((len(T), 4, 3))
    g[:, 1:, :] = Jinv
    g[:, 0, :] = -Jinv.sum(axis=1)
    vol = np.linalg.det(J) / 6.0
    return g, vol


def linear_stiffness(X, T, E, nu):
    """Global small-strain stiffness (3n × 3n, CSR)."""
    mu, lam = lame(E, nu)
    g, vol = shape_gradients(X, T)
    m = len(T)
    # K_ab = V (μ (∇N_a·∇N_b) I + μ ∇N_b ⊗ ∇N_a + λ ∇N_a ⊗ ∇N_b)
    Ke = np.zeros((m, 12, 12))
    for a in range(4):
        for b in range(4):
            ga, gb = g[:, a, :], g[:, b, :]
            blk = (mu * np.einsum("ij,ij->i", ga, gb)[:, None, None] * np.eye(3)[None]
                   + mu * np.einsum("ij,ik->ijk", gb, ga) + lam * np.einsum("ij,ik->ijk", ga, gb))
            Ke[:, 3 * a:3 * a + 3, 3 * b:3 * b + 3] = vol[:, None, None] * blk
    dofs = (3 * T[:, :, None] + np.arange(3)[None, None, :]).reshape(m, 12)
    rows = np.repeat(dofs, 12, axis=1).ravel()
    cols = np.tile(dofs, (1, 12)).ravel()
    n3 = 3 * len(X)
    return sp.csr_matrix((Ke.ravel(), (rows, cols)), shape=(n3, n3))


def lumped_mass(X, T, rho):
    """ρV/4 per node (000 Fig. 7), per dof."""
    _, vol = shape_gradients(X, T)
    m = np.zeros(len(X))
    np.add.at(m, T.ravel(), np.repeat(rho * vol / 4.0, 4))
    return np.repeat(m, 3)


def max_frequency(X, T, E, nu, rho, constrained_nodes):
    """ω_max (rad/s) of the constrained linear model with lumped mass."""
    K = linear_stiffness(X, T, E, nu)
    M = lumped_mass(X, T, rho)
    free = np.ones(3 * len(X), dtype=bool)
    for n in constrained_nodes:
        free[3 * n:3 * n + 3] = False
    idx = np.flatnonzero(free)
    s = 1.0 / np.sqrt(M[idx])
    A = sp.diags(s) @ K[idx][:, idx] @ sp.diags(s)
    # A seeded random start vector: ARPACK's default start is random and unseeded, which made the
    # last digits vary from run to run (a constant vector could miss the top mode by symmetry).
    v0 = np.random.default_rng(0).standard_normal(A.shape[0])
    lam = spla.eigsh(A, k=1, which="LA", return_eigenvectors=False, tol=1e-10, v0=v0)[0]
    return float(np.sqrt(lam))
