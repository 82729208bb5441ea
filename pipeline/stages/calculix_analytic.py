"""Closed-form homogeneous solutions used to check the CalculiX stages and the solvers compared
with them: uniaxial stress of a block whose lateral faces are traction free."""
import math

from scipy.optimize import brentq


def uniaxial_linear(nu: float, strain: float):
    """Small-strain uniaxial stress: lateral strain −ν ε; returns (lateral strain, σ_zz / E)."""
    return -nu * strain, strain


def uniaxial_neo_hookean_decoupled(mu: float, K: float, stretch: float):
    """Uniaxial stress of W = μ/2 (Ī₁ − 3) + K/2 (J − 1)² (CalculiX NEO HOOKE, C10 = μ/2,
    D1 = 2/K) at axial stretch `stretch` with traction-free lateral faces.

    Cauchy stress: σ = μ J^(−5/3) dev(b) + K (J − 1) I with b = diag(λt², λt², λ²), J = λt² λ.
    Returns (λt, σ_zz, nominal axial force per reference area σ_zz λt²)."""
    def stresses(lt):
        J = lt * lt * stretch
        i1 = 2.0 * lt * lt + stretch * stretch
        lateral = mu * J ** (-5.0 / 3.0) * (lt * lt - i1 / 3.0) + K * (J - 1.0)
        axial = mu * J ** (-5.0 / 3.0) * (stretch * stretch - i1 / 3.0) + K * (J - 1.0)
        return lateral, axial

    # The lateral stress grows monotonically with λt; bracket the root generously.
    lo, hi = 0.2 / math.sqrt(stretch), 5.0 / math.sqrt(stretch)
    lt = brentq(lambda s: stresses(s)[0], lo, hi, xtol=1e-15, rtol=1e-15)
    sigma = stresses(lt)[1]
    return lt, sigma, sigma * lt * lt
