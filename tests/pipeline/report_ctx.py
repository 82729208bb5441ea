"""A stand-in for the pipeline's report context, for running reports on small synthetic
artifacts: params, the runs of each stage, the experiment document and an output folder."""
import csv
from types import SimpleNamespace


class FakeContext:
    def __init__(self, out_dir, runs=None, params=None, experiment=None):
        self.results_dir = out_dir
        self.params = params or {}
        self.experiment = experiment or {}
        self._runs = runs or {}
        out_dir.mkdir(parents=True, exist_ok=True)

    def runs(self, stage):
        if stage not in self._runs:
            raise KeyError(stage)
        return self._runs[stage]

    def all_runs(self):
        return [r for runs in self._runs.values() for r in runs]

    def out(self, name):
        path = self.results_dir / name
        path.parent.mkdir(parents=True, exist_ok=True)
        return path

    def log(self, line):
        pass


def run(payload, config=None, run_id="run#0", sweep=None):
    return SimpleNamespace(payload=payload, config=config or {}, id=run_id, sweep=sweep or {})


def read_csv(path):
    """The rows of a written table as lists of strings, header first."""
    with open(path, newline="") as f:
        return list(csv.reader(f))
