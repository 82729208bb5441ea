"""The CalculiX decks of the locking study (pipeline.stages.incompressible_reference): the punch
holds exactly the top nodes under the 5 × 5 mm square (corners and mid-side nodes of C3D20R),
the clamped set is the bottom face, and the punch is bonded (all three components) while the
cantilever's end face is moved in z only. No ccx run: the deck alone."""
import numpy as np

from pipeline.stages.incompressible_reference import deck, scene_nodes
from pipeline.stages.calculix_plate import PlateMesh

SIZE = [0.02, 0.02, 0.01]


def test_punch_nodes_are_the_top_nodes_under_the_square():
    mesh = PlateMesh(SIZE, [8, 8, 4], "C3D20R")
    clamped, loaded = scene_nodes(mesh.positions, SIZE, "punch", 0.0025)
    P = mesh.positions
    assert np.all(P[clamped, 2] == 0.0)
    assert len(clamped) == np.count_nonzero(P[:, 2] == 0.0)
    # 2.5 mm hexes with mid-side nodes: a 1.25 mm lattice, 5 × 5 points on the square, less the
    # 4 face centres a 20-node hexahedron does not have.
    assert len(loaded) == 21
    assert np.all(np.abs(P[loaded, :2] - 0.01) <= 0.0025 + 1e-12)
    assert np.allclose(P[loaded, 2], 0.01)


def test_punch_is_bonded_and_cantilever_end_moves_in_z_only():
    punch, _ = deck("punch", SIZE, [8, 8, 4], "C3D20R", 5000.0, 0.49, 0.001, 0.0025, 5)
    assert "LOADED, 1, 2, 0.0" in punch and "LOADED, 3, 3, -0.001" in punch
    assert "*HYPERELASTIC, NEO HOOKE" in punch and "NLGEOM" in punch
    beam, _ = deck("cantilever", [0.04, 0.01, 0.01], [16, 4, 4], "C3D20R", 5000.0, 0.49, 0.002, 0.0025, 5)
    assert "LOADED, 1, 2, 0.0" not in beam and "LOADED, 3, 3, -0.002" in beam
