"""Where things live, relative to the repository root (the working directory of every run).
PIPELINE_EXPERIMENTS, PIPELINE_RESULTS and PIPELINE_CACHE override the defaults (the tests use
them to run throw-away experiments)."""
import os
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
EXPERIMENTS = Path(os.environ.get("PIPELINE_EXPERIMENTS", ROOT / "experiments"))
RESULTS = Path(os.environ.get("PIPELINE_RESULTS", ROOT / "results"))
BUILD = ROOT / "build"
BIN = Path(os.environ.get("PIPELINE_BIN", BUILD / "bin"))
CACHE = Path(os.environ.get("PIPELINE_CACHE", BUILD / "cache"))
ARTIFACTS = CACHE / "artifacts"
CONFIGS = CACHE / "configs"
LOGS = CACHE / "logs"
STAMPS = CACHE / "stamps"


def rel(path) -> str:
    """Repository-relative path string (what configs and manifests carry)."""
    p = Path(path).resolve()
    try:
        return str(p.relative_to(ROOT))
    except ValueError:
        return str(p)
