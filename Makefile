# The doors a user knows: setup · build · test · reproduce · bench · clean.
PYTHON ?= /usr/bin/python3
BUILD  ?= build
JOBS   ?= $(shell nproc)
CMAKE_FLAGS ?= -DCMAKE_BUILD_TYPE=Release

.PHONY: all setup configure build test test-cpp test-pipeline reproduce bench clean

all: build

setup:
	@bash pipeline/setup.sh

configure: setup
	@cmake -S . -B $(BUILD) $(CMAKE_FLAGS) > /dev/null

build: configure
	@cmake --build $(BUILD) -j $(JOBS)

test: build
	@cd $(BUILD) && ctest --output-on-failure -j $(JOBS)
	@$(PYTHON) -m pytest -q tests/pipeline

reproduce: build
	@$(PYTHON) -m pipeline run all -j $(JOBS)

bench: build
	@$(PYTHON) -m pipeline bench

clean:
	rm -rf $(BUILD)
