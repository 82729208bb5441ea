"""What a python stage's run(ctx) and a report's report(ctx) receive."""
import json
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Dict, List

from pipeline.paths import RESULTS, ROOT


class RunView:
    """A finished run as a report sees it."""

    def __init__(self, run, artifact_path: Path):
        self.id = run.id
        self.stage = run.stage
        self.index = run.index
        self.config = run.config
        self.sweep = run.sweep
        self.path = artifact_path
        self._doc = None

    @property
    def artifact(self) -> Dict[str, Any]:
        if self._doc is None:
            with open(self.path) as f:
                self._doc = json.load(f)
        return self._doc

    @property
    def payload(self) -> Dict[str, Any]:
        return self.artifact["payload"]


@dataclass
class StageContext:
    """For `python` stages: the resolved config and where the artifact goes."""
    config: Dict[str, Any]
    out_path: Path
    run_id: str
    experiment: str
    log_lines: List[str] = field(default_factory=list)

    def log(self, line: str) -> None:
        self.log_lines.append(line)

    @property
    def root(self) -> Path:
        return ROOT


class ReportContext:
    def __init__(self, experiment, run, views: Dict[str, List[RunView]]):
        self.experiment = experiment.doc
        self.experiment_name = experiment.name
        self.params = run.params
        self._views = views
        self.results_dir = RESULTS / experiment.results_subdir
        self.outputs: List[Path] = []

    def runs(self, stage: str) -> List[RunView]:
        if stage not in self._views:
            raise KeyError(f"report has no input stage {stage!r}; add it to the stage's inputs")
        return self._views[stage]

    def all_runs(self) -> List[RunView]:
        """Every input run of the report, stage by stage."""
        return [v for views in self._views.values() for v in views]

    def out(self, name: str) -> Path:
        from pipeline.artifacts import ResultPath  # its write_text is atomic
        path = ResultPath(self.results_dir / name)
        path.parent.mkdir(parents=True, exist_ok=True)
        if path not in self.outputs:
            self.outputs.append(path)
        return path
