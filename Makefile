# The README's two commands: `make demo` (the main job) and `make test` (the tests).
# Each installs whatever is missing (scripts/install-deps.sh, Debian packages only), configures
# and builds; when everything is present they go straight to work.

BUILD ?= build
ASAN_BUILD ?= build-asan
BUILD_TYPE ?= RelWithDebInfo
JOBS ?= $(shell nproc)
OUT ?= out
ENCORE = $(BUILD)/apps/encore/encore
export XDG_RUNTIME_DIR ?= /tmp

.PHONY: all deps configure build demo test test-unit test-gpu test-sanitize bench-smoke clean

all: build

deps:
	@bash scripts/install-deps.sh

configure: deps
	@mkdir -p $(BUILD)
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=$(BUILD_TYPE) -Wno-dev > $(BUILD)/configure.log 2>&1 \
		|| (cat $(BUILD)/configure.log; exit 1)

build: configure
	@cmake --build $(BUILD) -j$(JOBS)

# Renders a scene Encore generates itself (no external file needed) and prints the PNG's path.
demo: build
	@mkdir -p $(OUT)
	@$(ENCORE) gen --objects 400 --meshes 6 --materials 5 -o $(OUT)/demo-scene.glb
	@$(ENCORE) --verbose render $(OUT)/demo-scene.glb --strategy bundles -o $(OUT)/demo.png

test: build
	@cd $(BUILD) && ctest --output-on-failure -j2 --timeout 900

test-unit: build
	@cd $(BUILD) && ctest --output-on-failure -j2 -L unit

test-gpu: build
	@cd $(BUILD) && ctest --output-on-failure -j2 -L gpu

# Unit and command-line (bad input) tests under AddressSanitizer + UndefinedBehaviorSanitizer.
test-sanitize: deps
	@mkdir -p $(ASAN_BUILD)
	@cmake -S . -B $(ASAN_BUILD) -DCMAKE_BUILD_TYPE=Debug -DENCORE_SANITIZE=ON -Wno-dev \
		> $(ASAN_BUILD)/configure.log 2>&1 || (cat $(ASAN_BUILD)/configure.log; exit 1)
	@cmake --build $(ASAN_BUILD) -j$(JOBS)
	@cd $(ASAN_BUILD) && ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 \
		UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
		ctest --output-on-failure -j2 -L 'unit|cli'

clean:
	rm -rf $(BUILD) $(ASAN_BUILD) $(OUT)
