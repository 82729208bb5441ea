"""REPORT.md for a reader: the summary table reads every number from the result tables (a changed
table changes the summary; a missing one drops its row, nothing is typed in), the contents list
links every section's heading, and the provenance comes last. `pipeline diff` tells a real change
in results/ from timing noise."""
import csv
import importlib
import subprocess
import sys

import pytest

from conftest import ROOT


@pytest.fixture
def results(tmp_path, monkeypatch):
    """report_md and report_summary writing into a throw-away results folder."""
    monkeypatch.setenv("PIPELINE_RESULTS", str(tmp_path / "results"))
    from pipeline import paths, report_md, report_summary
    for mod in (paths, report_summary, report_md):
        importlib.reload(mod)
    yield tmp_path / "results"
    monkeypatch.delenv("PIPELINE_RESULTS")
    for mod in (paths, report_summary, report_md):
        importlib.reload(mod)


def write_csv(path, header, rows):
    path.parent.mkdir(parents=True, exist_ok=True)
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(header)
        w.writerows(rows)


ERROR_HEADER = ["share of linear elements r", "mean error e (ours, %)", "mean error (paper, %)"]


def test_summary_reads_ours_and_the_papers_from_the_table(results):
    from pipeline import report_md
    write_csv(results / "dhd" / "table2.csv", ERROR_HEADER,
              [["0 %", 0.0, ""], ["10 %", 0.031, 5.7], ["40 %", 0.27, 22.7], ["50 %", 0.4, ""]])
    (results / "dhd" / "summary.md").write_text("## DHD-FEA\n\ntext\n\n### Table 2\n\nmore\n")
    report_md.assemble()
    text = (results / "REPORT.md").read_text()
    row = next(line for line in text.splitlines() if line.startswith("| 000 Table 2"))
    # The paper's largest tabulated share, our number and the paper's from the same row.
    assert "r = 40 %" in row and "| 0.27 % | 22.7 % |" in row, row
    # A rerun that measures another error changes the summary with it.
    write_csv(results / "dhd" / "table2.csv", ERROR_HEADER, [["0 %", 0.0, ""], ["40 %", 0.5, 22.7]])
    report_md.assemble()
    row = next(line for line in (results / "REPORT.md").read_text().splitlines() if line.startswith("| 000 Table 2"))
    assert "| 0.5 % | 22.7 % |" in row, row
    # Tables that do not exist give no row.
    assert "000 Table 3" not in (results / "REPORT.md").read_text()


def test_contents_first_provenance_last(results):
    from pipeline import report_md
    (results / "mesh").mkdir(parents=True)
    (results / "mesh" / "summary.md").write_text("## Meshes\n\nmeshes\n")
    (results / "stability").mkdir()
    (results / "stability" / "summary.md").write_text(
        "# Stability: where it breaks\n\n## Explicit time step\n\n```\n# not a heading\n```\n\n## Marquardt fits\n")
    (results / "rpim").mkdir()
    (results / "rpim" / "fit_summary.md").write_text("## Marquardt fits (paper 002, §3–5)\n\n## Marquardt fits\n")
    report_md.assemble()
    text = (results / "REPORT.md").read_text()
    headings = [line for line in text.splitlines() if line.startswith("## ")]
    assert headings[0] == "## Contents" and headings[-1] == "## Provenance", headings
    contents = text.split("## Contents\n")[1].split("\n## ")[0]
    assert "- [Meshes](#meshes)" in contents
    assert "- [Marquardt fits (paper 002, §3–5)](#marquardt-fits-paper-002-35)" in contents
    # The same heading twice: the second anchor takes a number, as a Markdown viewer numbers it.
    assert "[Marquardt fits](#marquardt-fits)" in contents and "(#marquardt-fits-1)" in contents
    assert "  - [Explicit time step](#explicit-time-step)" in contents      # under its area
    assert "not a heading" not in contents
    assert text.index("## Provenance") > text.index("## Meshes")
    assert "Assembled at commit" in text.split("## Provenance")[1]


def test_report_command_rewrites_report_md_and_runs_nothing(tmp_path):
    results = tmp_path / "results"
    (results / "mesh").mkdir(parents=True)
    (results / "mesh" / "summary.md").write_text("## Meshes\n\nmeshes\n")
    env = {"PIPELINE_RESULTS": str(results), "PIPELINE_CACHE": str(tmp_path / "cache"), "PATH": "/usr/bin:/bin"}
    r = subprocess.run([sys.executable, "-m", "pipeline", "report"], cwd=ROOT, env=env, capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert "## Meshes" in (results / "REPORT.md").read_text()
    assert not (tmp_path / "cache").exists()


def test_diff_tells_timings_from_real_changes():
    from pipeline import results_diff
    header = "share of linear elements r,steps/s (best),time per step (µs),\"mean error e (ours, %)\"\n"
    old = header + "0 %,6810.1,146.8,0.0\n10 %,6734.3,148.5,0.028\n"
    timing_only = header + "0 %,7001.2,142.8,0.0\n10 %,6734.3,151.5,0.028\n"
    real = header + "0 %,6810.1,146.8,0.0\n10 %,6734.3,148.5,0.031\n"
    assert results_diff.compare_text(".csv", old, timing_only) == (3, {})
    assert results_diff.compare_text(".csv", old, real) == (0, {"mean error e (ours, %)": 1})
    prose = "Served for 60 s, a frame took 0.17 ms (p99 0.36 ms); 55 of 60 000 answers were late; 3.6 % RMS.\n"
    assert results_diff.compare_text(".md", prose, prose.replace("0.17 ms", "0.19 ms")) == (1, {})
    t, real_prose = results_diff.compare_text(".md", prose, prose.replace("3.6 % RMS", "3.9 % RMS"))
    assert real_prose == {"numbers in the text": 1}
    table = "| r | time/frame (µs) | RMS error (%) |\n| --- | --- | --- |\n| 10 | 0.45 | 19.2 |\n"
    assert results_diff.compare_text(".md", table, table.replace("0.45", "0.52")) == (1, {})
    assert results_diff.compare_text(".md", table, table.replace("19.2", "19.3")) == (0, {"RMS error (%)": 1})
    # Last-digit changes (another compiler, CPU or summation order) are round-off, not real; a
    # value that is zero up to round-off may move by more than its own size.
    roundoff = header + "0 %,6810.1,146.8,1.2e-17\n10 %,6734.3,148.5,0.02800000000001\n"
    assert results_diff.compare_text(".csv", old, roundoff) == (0, {"round-off": 2})
    # A "|" inside a cell (|u_x/F_x|) keeps the columns in place; the CPU a time ran on is not a result.
    piped = "| model | |u_z/F_z| (mm/N) | precompute (s) |\n| --- | --- | --- |\n| RPIM | 6.252 | 0.198 |\n"
    assert results_diff.compare_text(".md", piped, piped.replace("0.198", "0.964")) == (1, {})
    assert results_diff.compare_text(".md", piped, piped.replace("6.252", "6.3")) == (0, {"|u_z/F_z| (mm/N)": 1})
    cpu = "best of 5 repeats (median beside it; AMD EPYC). Speed-up 1.35, 147 µs per step.\n"
    moved = "best of 5 repeats (median beside it; Intel(R) Xeon(R) Processor). Speed-up 0.79, 480 µs per step.\n"
    assert results_diff.compare_text(".md", cpu, moved) == (2, {})
    # Which commit ran what is bookkeeping, not a change of results.
    line = "table1 by `dhd_table1` at commit `ac904c2-dirty`.\n"
    assert results_diff.compare_text(".md", line, line.replace("ac904c2", "0123abc")) == (0, {})


def test_papers_selection_regenerates_every_table_the_summary_compares_with_a_paper():
    """`pipeline run papers` (make reproduce-quick) names shipped experiments only, and among them
    are the ones that write each table whose numbers REPORT.md's summary sets beside a paper's."""
    from pipeline import cli, report_summary
    from pipeline import experiment as experiment_mod
    shipped = set(experiment_mod.list_experiments())
    assert set(cli.PAPERS) <= shipped, set(cli.PAPERS) - shipped
    assert cli._experiment_names("papers") == cli.PAPERS
    written = set()
    for name in cli.PAPERS:
        exp = experiment_mod.load(name)
        for run in exp.runs.values():
            if run.kind == "report":
                written.add(exp.results_subdir)
    for h in report_summary.HEADLINES:
        if h.theirs is not None:
            assert h.table.split("/")[0] in written, h.table


def test_make_python_link_lets_debians_python_import_the_build_from_anywhere(tmp_path):
    """The README's set-up: after `make build` (its last step, `make python-link`), Debian's
    python3 imports this build's softsim from any folder, with no PYTHONPATH."""
    package = ROOT / "build" / "python" / "softsim"
    if not (package / "__init__.py").exists():
        pytest.skip("the Python module is not built (SOFTSIM_PYTHON off)")
    env = {"HOME": str(tmp_path), "PATH": "/usr/bin:/bin"}
    r = subprocess.run(["make", "-s", "python-link", "PYTHON=/usr/bin/python3"], cwd=ROOT, env=env,
                       capture_output=True, text=True)
    assert r.returncode == 0 and "import softsim works" in r.stdout, r.stdout + r.stderr
    r = subprocess.run(["/usr/bin/python3", "-c", "import softsim; print(softsim.__file__)"], cwd=tmp_path, env=env,
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert r.stdout.strip() == str((package / "__init__.py").resolve())
    r = subprocess.run(["make", "-s", "python-unlink", "PYTHON=/usr/bin/python3"], cwd=ROOT, env=env)
    r = subprocess.run(["/usr/bin/python3", "-c", "import softsim"], cwd=tmp_path, env=env, capture_output=True)
    assert r.returncode != 0
