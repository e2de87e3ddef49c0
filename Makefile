# The two commands of README.md, and their parts. Each target does all set-up it needs.
#   make demo   bootstrap, build the programs (not the tests), run the main job on the local
#               default (scripts/demo): a small sweep of the paper's CartPole experiment on a
#               local cluster, its table and figures
#   make test   bootstrap, build, run every test with ctest; then build the fuzz targets
#               (tests/fuzz/, in build-fuzz/ with clang) and give each a short pass
# and for whoever changes a config key, its default or its range:
#   make docs   regenerate docs/config.md from the code's tables (tools/config_reference.cc);
#               `make test` fails while it is stale
BUILD_DIR ?= build
FUZZ_BUILD_DIR ?= build-fuzz
JOBS ?= $(shell nproc)

# What `dcs up` and the client run: the demo builds these alone, not the tests and benchmarks.
PROGRAMS := dcs dcs-coordinator dcs-learner dcs-actor

.PHONY: all bootstrap configure build programs test fuzz-configure fuzz-build fuzz demo sanitize \
	docs clean

all: build

bootstrap:
	scripts/bootstrap

configure: bootstrap
	cmake -S . -B $(BUILD_DIR) -G Ninja -DCMAKE_BUILD_TYPE=Release

build: configure
	cmake --build $(BUILD_DIR) -j $(JOBS)

programs: configure
	cmake --build $(BUILD_DIR) -j $(JOBS) --target $(PROGRAMS)

test: build
	ctest --test-dir $(BUILD_DIR) --output-on-failure -j $(JOBS)
	$(MAKE) fuzz

fuzz-configure: bootstrap
	cmake -S . -B $(FUZZ_BUILD_DIR) -G Ninja -DCMAKE_CXX_COMPILER=clang++-14 -DDCS_FUZZ=ON

fuzz-build: fuzz-configure
	cmake --build $(FUZZ_BUILD_DIR) -j $(JOBS)

# Each fuzz target's seeds, then new inputs for DCS_FUZZ_SECONDS (tests/fuzz/CMakeLists.txt).
fuzz: fuzz-build
	ctest --test-dir $(FUZZ_BUILD_DIR) --output-on-failure -j $(JOBS) -L fuzz

demo: programs
	scripts/demo $(BUILD_DIR)

docs: configure
	cmake --build $(BUILD_DIR) -j $(JOBS) --target dcs-config-reference
	$(BUILD_DIR)/tools/dcs-config-reference --out docs/config.md

# The release check (README "Working on DCS"): every test under ASan+UBSan, then under TSan.
sanitize:
	scripts/sanitize

clean:
	rm -rf $(BUILD_DIR) $(FUZZ_BUILD_DIR)
