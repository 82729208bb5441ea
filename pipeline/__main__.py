"""Entry point: /usr/bin/python3 -m pipeline {run,list,clean,bench}."""
import sys

from pipeline.cli import main

sys.exit(main(sys.argv[1:]))
