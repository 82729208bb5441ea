"""002 §5.3's liver: the comparison of the small-strain RPIM with dhd_sim's linear FEM states the
FEM's measured largest deformation and whether it lies inside small-strain validity."""
from test_rpim_liver_report import context

from pipeline.reports import rpim_liver


def with_check(ctx, largest):
    for r in ctx.runs("fem"):
        r.payload["small_strain_check"] = {"limit": 0.10, "elements": 12, "largest": largest, "broken": largest > 0.10}
    return ctx


def test_a_reference_beyond_small_strain_is_said_to_be_outside_validity(tmp_path):
    rpim_liver.report(with_check(context(tmp_path / "big"), 4.63))
    text = (tmp_path / "big" / "summary.md").read_text()
    assert "Both models are outside their validity here: the FEM's most deformed element reaches ‖∇u‖₂ = 463 %, " \
           "46.3 × the 10 % up to which small-strain models hold" in text
    assert "| 463 |" in (tmp_path / "big" / "rpim_liver_vs_fem.md").read_text()


def test_a_reference_inside_small_strain_is_said_to_be_valid(tmp_path):
    rpim_liver.report(with_check(context(tmp_path / "small"), 0.04))
    text = (tmp_path / "small" / "summary.md").read_text()
    assert "Both stay small-strain: the FEM's most deformed element reaches ‖∇u‖₂ = 4 %, within the 10 % limit." in text
    assert "outside their validity" not in text


def test_a_reference_without_a_check_says_the_deformation_is_unknown(tmp_path):
    rpim_liver.report(context(tmp_path / "none"))
    assert "no small-strain check for this run" in (tmp_path / "none" / "summary.md").read_text()
