"""A python stage for the tests: its payload names the artifact it read, as a stage that records
its input's path does (tests/pipeline/test_cache_location.py)."""
from pipeline.artifacts import write_artifact


def run(ctx):
    write_artifact(ctx.out_path, "recorded_input", 1, "stage_records_input", ctx.config,
                   {"input": ctx.config["input"]})
