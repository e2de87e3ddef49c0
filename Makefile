# The two commands of README.md, and their parts. Each target does all set-up it needs.
#   make demo   bootstrap, build, run the main job on the local default (scripts/demo): a small
#               sweep of the paper's CartPole experiment on a local cluster, its table and figures
#   make test   bootstrap, build, run every test with ctest
BUILD_DIR ?= build
JOBS ?= $(shell nproc)

.PHONY: all bootstrap configure build test demo bench clean

all: build

bootstrap:
	scripts/bootstrap

configure: bootstrap
	cmake -S . -B $(BUILD_DIR) -G Ninja -DCMAKE_BUILD_TYPE=Release

build: configure
	cmake --build $(BUILD_DIR) -j $(JOBS)

test: build
	ctest --test-dir $(BUILD_DIR) --output-on-failure -j $(JOBS)

demo: build
	scripts/demo $(BUILD_DIR)

clean:
	rm -rf $(BUILD_DIR)
