"""Errors of the pipeline itself: a bad experiment file is the user's input error (exit 2)."""


class ExperimentError(Exception):
    """A malformed experiment: names the file, the JSON pointer and what was expected."""


class RunFailed(Exception):
    """A stage run exited non-zero; carries the run id, the exit code and the tool's message."""

    def __init__(self, run_id: str, code: int, message: str):
        super().__init__(f"{run_id}: exit {code}: {message}")
        self.run_id = run_id
        self.code = code
        self.message = message

    def __reduce__(self):  # picklable, so it can cross to and from a Dask worker
        return (RunFailed, (self.run_id, self.code, self.message))
