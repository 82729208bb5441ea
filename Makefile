# The doors a user knows: setup · build · demo · test · reproduce · bench · clean
# (README.md says what each does and how long it takes on a small machine).
PYTHON ?= /usr/bin/python3
BUILD  ?= build
JOBS   ?= $(shell nproc)
# ccache, where installed, makes a rebuild take seconds; paths relative to this folder let
# another clone on the same machine (CI's) reuse the objects.
CCACHE := $(shell command -v ccache 2>/dev/null)
CMAKE_FLAGS ?= -DCMAKE_BUILD_TYPE=Release \
  $(if $(CCACHE),-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
export CCACHE_BASEDIR ?= $(CURDIR)
# Extra flags of `pipeline run` for reproduce, e.g. PIPELINE_FLAGS="--executor dask-local" or
# PIPELINE_FLAGS="--scheduler tcp://HOST:8786 -j 256" (a later -j wins over JOBS)
PIPELINE_FLAGS ?=

.PHONY: all setup configure build python-link python-unlink demo view test test-ci test-all reproduce reproduce-quick report \
        bench fuzz test-sanitize clean

all: build

setup:
	@bash pipeline/setup.sh

configure: setup
	@cmake -S . -B $(BUILD) $(CMAKE_FLAGS) > /dev/null

build: configure
	@cmake --build $(BUILD) -j $(JOBS)
	@$(MAKE) --no-print-directory python-link

# `import softsim` for Debian's python3 from anywhere: a one-line softsim.pth in the user's
# site-packages naming $(BUILD)/python (what an editable install does, without pip, which Debian's
# python3 does not let install here). The build tree stays the one copy: a rebuild is imported at
# once. PYTHON_LINK=0 skips it; `make python-unlink` removes it.
PYTHON_LINK ?= 1
python-link:
	@if [ "$(PYTHON_LINK)" = 1 ] && [ -d $(BUILD)/python/softsim ]; then \
	  site=$$($(PYTHON) -m site --user-site) && mkdir -p "$$site" && \
	  realpath $(BUILD)/python > "$$site/softsim.pth" && \
	  echo "python: import softsim works in $(PYTHON) ($$site/softsim.pth -> $$(realpath $(BUILD)/python))"; \
	fi
python-unlink:
	@rm -f "$$($(PYTHON) -m site --user-site)/softsim.pth"

# A first result in about a minute: the complete C++ stepping example (cpp/examples/step_scene.cpp,
# a probe pressed 2 mm into the paper's cuboid at 1 kHz frames) writes its force against depth.
# It builds only what the example needs (the core and fe groups of the library).
demo: configure
	@cmake --build $(BUILD) -j $(JOBS) --target step_scene
	@mkdir -p $(BUILD)/demo
	@$(BUILD)/examples/step_scene $(BUILD)/demo/press.csv
	@echo "demo: force on the tool against tip depth, one line per 1 ms frame: $(BUILD)/demo/press.csv"
	@tail -n 3 $(BUILD)/demo/press.csv

# The live liver in a browser: meshes it once (build/view/), then `haptic_sim view` on
# http://127.0.0.1:$(VIEW_PORT)/ until Ctrl-C (pipeline/view_scene.py).
VIEW_PORT ?= 8080
view: build
	@$(PYTHON) -m pipeline.view_scene --port $(VIEW_PORT)

# Tests. `make test` is the quick suite (a few minutes on two cores); the checks labelled slow
# (ctest label `slow`, pytest marker `slow`) run in `make test-all`; CI runs `make test-ci`, the
# quick suite and the slow pytest checks (everything but recompiling the library as a consumer's
# subdirectory, which alone takes about ten minutes on two cores).
CTEST = cd $(BUILD) && ctest --output-on-failure -j $(JOBS)
test: build
	@$(CTEST) -LE slow
	@$(PYTHON) -m pytest -q -m "not slow" tests/pipeline

test-ci: test
	@$(PYTHON) -m pytest -q -m slow tests/pipeline; rc=$$?; [ $$rc -eq 0 ] || [ $$rc -eq 5 ]

test-all: build
	@$(CTEST)
	@$(PYTHON) -m pytest -q tests/pipeline

reproduce: build
	@$(PYTHON) -m pipeline run all -j $(JOBS) $(PIPELINE_FLAGS)

# The experiments whose tables and figures stand beside the three papers' (pipeline/cli.py,
# PAPERS), at full size, without our own studies around them and the haptic, cutting, contact,
# stability and benchmark experiments that take most of the full run's time; REPORT.md then says
# that only part of the experiments were rerun.
reproduce-quick: build
	@$(PYTHON) -m pipeline run papers -j $(JOBS) $(PIPELINE_FLAGS)

# REPORT.md assembled again from the summaries in results/, nothing rerun.
report:
	@$(PYTHON) -m pipeline report

bench: build
	@$(PYTHON) -m pipeline bench

# The test suite under AddressSanitizer and UndefinedBehaviorSanitizer (its own build tree).
test-sanitize: setup
	@cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSOFTSIM_SANITIZE=ON -DSOFTSIM_BENCHMARKS=OFF > /dev/null
	@cmake --build build-asan -j $(JOBS)
	@cd build-asan && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 ctest --output-on-failure -j $(JOBS)
	@PIPELINE_BIN=build-asan/bin ASAN_OPTIONS=detect_leaks=1 $(PYTHON) -m pytest -q tests/pipeline

# Every input parser under libFuzzer (clang, with ASan/UBSan) for FUZZ_SECONDS each, seeded
# from tests/fuzz_corpus/; run_app is the executables' entry point, config file to artifact.
FUZZ_SECONDS ?= 60
FUZZERS = gmsh_reader:gmsh vtk_reader:vtk vtu_reader:vtu mesh_artifact:mesh_artifact dhd_config:dhd_config rpim_config:rpim_config fit_inputs:fit_inputs async_config:async_config run_app:run_app wire_protocol:wire_protocol
fuzz: setup
	@cmake -S . -B build-fuzz -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	  -DSOFTSIM_FUZZ=ON -DSOFTSIM_SANITIZE=ON -DSOFTSIM_TESTS=OFF -DSOFTSIM_BENCHMARKS=OFF > /dev/null
	@cmake --build build-fuzz -j $(JOBS) --target $(foreach f,$(FUZZERS),fuzz_$(word 1,$(subst :, ,$(f))))
	@for f in $(FUZZERS); do \
	  name=$${f%%:*}; seeds=$${f##*:}; corpus=build-fuzz/corpus/$$name; \
	  mkdir -p $$corpus; cp tests/fuzz_corpus/$$seeds/* $$corpus/; \
	  echo "fuzz: $$name for $(FUZZ_SECONDS) s"; \
	  if ! build-fuzz/bin/fuzz_$$name $$corpus -max_total_time=$(FUZZ_SECONDS) -timeout=10 -rss_limit_mb=4096 \
	       -artifact_prefix=build-fuzz/crash-$$name- > build-fuzz/fuzz_$$name.log 2>&1; then \
	    tail -n 30 build-fuzz/fuzz_$$name.log; echo "fuzz: $$name FAILED (input saved under build-fuzz/)"; exit 1; \
	  fi; tail -n 1 build-fuzz/fuzz_$$name.log; \
	done; echo "fuzz: no crash in any parser"

clean:
	rm -rf $(BUILD) build-asan build-fuzz
