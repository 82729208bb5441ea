# The doors a user knows: setup · build · test · reproduce · bench · clean.
PYTHON ?= /usr/bin/python3
BUILD  ?= build
JOBS   ?= $(shell nproc)
CMAKE_FLAGS ?= -DCMAKE_BUILD_TYPE=Release
# Extra flags of `pipeline run` for reproduce, e.g. PIPELINE_FLAGS="--executor dask-local" or
# PIPELINE_FLAGS="--scheduler tcp://HOST:8786 -j 256" (a later -j wins over JOBS)
PIPELINE_FLAGS ?=

.PHONY: all setup configure build test reproduce bench fuzz test-sanitize clean

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
	@$(PYTHON) -m pipeline run all -j $(JOBS) $(PIPELINE_FLAGS)

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
