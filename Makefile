# The README's two commands: `make report` and `make test`. Both install missing Debian
# packages (as root), configure, build Release, then run the main job or the tests.
SHELL := /bin/bash
BUILD ?= build
JOBS ?= $(shell nproc 2>/dev/null || echo 2)
REPORT_DIR ?= report
# Seconds per scene and back-end for the mesh ladder (keeps `make report` under 10 minutes).
BUDGET ?= 20
PACKAGES := g++ cmake make pkg-config libeigen3-dev libgsl-dev libboost-test-dev \
            libspectra-dev libtomlplusplus-dev nlohmann-json3-dev libcli11-dev libfmt-dev \
            libsuitesparse-dev libopenblas0-serial gnuplot-nox calculix-ccx \
            pybind11-dev python3-dev python3-numpy python3-scipy python3-pytest python3-distributed \
            universal-ctags

.PHONY: all deps configure build report test bench sanitize fuzz clean

all: build

deps:
	@missing=""; \
	for p in $(PACKAGES); do \
	  dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q "install ok installed" || missing="$$missing $$p"; \
	done; \
	if [ -n "$$missing" ]; then \
	  if [ "$$(id -u)" = "0" ]; then \
	    echo "Installing:$$missing"; \
	    export DEBIAN_FRONTEND=noninteractive; \
	    apt-get update -qq && apt-get install -y -qq --no-install-recommends $$missing; \
	  else \
	    echo "Missing Debian packages. Run as root:"; \
	    echo "  apt-get install -y$$missing"; \
	    exit 1; \
	  fi; \
	fi

configure: deps
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release -DMODALBENCH_PYTHON=ON

build: configure
	cmake --build $(BUILD) -j $(JOBS)

report: build
	./$(BUILD)/app/modalbench compare --out $(REPORT_DIR) --budget $(BUDGET) --reference calculix
	./$(BUILD)/app/modalbench stability --out $(REPORT_DIR)/stability
	@echo "Report: $(CURDIR)/$(REPORT_DIR)/index.html  (stability sweep: $(CURDIR)/$(REPORT_DIR)/stability/stability.html)"

test: build
	ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS)

# Every benchmark program (Release build); figures on stdout.
bench: build
	@set -e; for b in $(BUILD)/benchmarks/*/bench_*; do echo "=== $$b"; "$$b"; done

# The address and undefined-behaviour sanitizer build, with the whole test suite and the fuzz
# corpus replayed (no address-space cap: ASan reserves terabytes of it).
sanitize: deps
	cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Debug -DMODALBENCH_SANITIZE=ON -DMODALBENCH_PYTHON=OFF
	cmake --build build-asan -j $(JOBS)
	ctest --test-dir build-asan --output-on-failure -j $(JOBS) -E '^fuzz\.'
	python3 tests/fuzz/fuzz.py --exe build-asan/app/modalbench --replay tests/fuzz/corpus --out build-asan/fuzz-replay \
	  --mem-cap-mb 0 --time-cap 300 --solver-max-time 120

# The scene fuzzer: 2000 seeded cases on every back-end; each finding is kept as a scene under
# $(BUILD)/fuzz/findings (copy the ones worth keeping into tests/fuzz/corpus for replay).
FUZZ_CASES ?= 2000
fuzz: build
	python3 tests/fuzz/fuzz.py --exe $(BUILD)/app/modalbench --cases $(FUZZ_CASES) --seed 1 --out $(BUILD)/fuzz \
	  --keep-findings $(BUILD)/fuzz/findings --jobs $(JOBS) --solver-max-time 5

clean:
	rm -rf $(BUILD) build-asan
