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

# How long CI takes is in docs/ci.md. Optimised with line tables (-g1: file and line in every
# backtrace and sanitizer report, a third less compile time than full debug information).
RELWITHDEBINFO_FLAGS ?= -O2 -g1 -DNDEBUG
# The sanitizer build: line tables for its reports, unoptimised. -O1 ran its tests 20 s faster
# (37 s against 56 s) but compiled a third slower (docs/ci.md).
SANITIZE_FLAGS ?= -O0 -g1
# ccache (installed by scripts/install-deps.sh; CMake uses it when present) hashes paths under
# the clone relative to it and ignores the working directory, so a fresh clone in another
# folder (CI) reuses the objects that a build of the same sources on this machine left.
export CCACHE_BASEDIR ?= $(CURDIR)
export CCACHE_NOHASHDIR ?= true
# Ninja where it is installed (scripts/install-deps.sh installs it): it starts a target's
# compiles before the libraries it links are built.
# $(call cmake_configure,DIR,ARGUMENTS): configures DIR, quietly unless it fails. A tree
# configured earlier with another generator is configured afresh (its objects are rebuilt,
# from ccache when they are there).
cmake_generator = $(if $(shell command -v ninja 2>/dev/null),Ninja,Unix Makefiles)
define cmake_configure
	@mkdir -p $(1)
	@if [ -f $(1)/CMakeCache.txt ] && \
		! grep -qx 'CMAKE_GENERATOR:INTERNAL=$(cmake_generator)' $(1)/CMakeCache.txt; then \
		rm -rf $(1)/CMakeCache.txt $(1)/CMakeFiles; fi
	@cmake -S . -B $(1) -G '$(cmake_generator)' -Wno-dev $(2) > $(1)/configure.log 2>&1 \
		|| (cat $(1)/configure.log; exit 1)
endef

.PHONY: all deps configure build demo test test-unit test-gpu sanitize-configure test-sanitize \
	bench-smoke install clean fuzz-build fuzz fuzz-replay fuzz-frame format format-check

all: build

deps:
	@bash scripts/install-deps.sh

configure: deps
	$(call cmake_configure,$(BUILD),-DCMAKE_BUILD_TYPE=$(BUILD_TYPE) \
		'-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=$(RELWITHDEBINFO_FLAGS)')

build: configure
	@cmake --build $(BUILD) -j$(JOBS)

# Renders a scene Encore generates itself (no external file needed) and prints the PNG's path.
demo: build
	@mkdir -p $(OUT)
	@$(ENCORE) gen --objects 400 --meshes 6 --materials 5 -o $(OUT)/demo-scene.glb
	@$(ENCORE) --verbose render $(OUT)/demo-scene.glb --strategy bundles -o $(OUT)/demo.png

test: build
	@cd $(BUILD) && ctest --output-on-failure -j2 --timeout 900

# The Python package encore, installed with pip (pyproject.toml: scikit-build-core, offline) into
# the active virtual environment, or INSTALL_PYTHON's; one made with
# `/usr/bin/python3 -m venv --system-site-packages DIR` sees Debian's scikit-build-core and numpy.
# The build folder (WHEEL_BUILD) lies beside $(BUILD) and is kept: ccache serves `make build`'s
# objects (the same compiler, c++, and flags) and a second install rebuilds only what changed.
WHEEL_BUILD ?= $(BUILD)-wheel
INSTALL_PYTHON ?= $(if $(VIRTUAL_ENV),$(VIRTUAL_ENV)/bin/python)
install: deps
	@if [ -z "$(INSTALL_PYTHON)" ]; then \
		echo "make install: no virtual environment; make one and activate it, or name its python:"; \
		echo "  /usr/bin/python3 -m venv --system-site-packages ~/venv && make install INSTALL_PYTHON=~/venv/bin/python"; \
		exit 1; fi
	@mkdir -p $(WHEEL_BUILD)
	@CXX="$${CXX:-c++}" flock $(WHEEL_BUILD)/.pip.lock $(INSTALL_PYTHON) -m pip install \
		--no-build-isolation --disable-pip-version-check \
		--config-settings=build-dir=$(abspath $(WHEEL_BUILD)) .

# .clang-format on every tracked C++ source (CI checks it; `make format` applies it).
format-check:
	@bash scripts/check-format.sh

format:
	@bash scripts/check-format.sh --fix

test-unit: build
	@cd $(BUILD) && ctest --output-on-failure -j2 -L unit

test-gpu: build
	@cd $(BUILD) && ctest --output-on-failure -j2 -L gpu

# Unit, command-line (bad input) and the robustness GPU tests (device limits, device loss, fault
# injection, soak, a short run of the frame fuzzer: CTest label sanitize) under AddressSanitizer +
# UndefinedBehaviorSanitizer, with LeakSanitizer on. Only those suites and the encore binary are
# built.
SANITIZE_ENV = ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 \
	UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
sanitize-configure: deps
	$(call cmake_configure,$(ASAN_BUILD),-DCMAKE_BUILD_TYPE=Debug -DENCORE_SANITIZE=ON \
		'-DCMAKE_CXX_FLAGS_DEBUG=$(SANITIZE_FLAGS)')

test-sanitize: sanitize-configure
	@cmake --build $(ASAN_BUILD) -j$(JOBS) --target encore_sanitize_suites
	@cd $(ASAN_BUILD) && $(SANITIZE_ENV) \
		ctest --output-on-failure -j2 --timeout 900 -L 'unit|cli|sanitize'

# libFuzzer targets of the loader (docs/fuzzing.md), built with clang in their own directory.
# `make fuzz` fuzzes each target for FUZZ_SECONDS on a working corpus that persists between
# runs; `make fuzz-replay` (CI) replays the seed corpus and fuzzes each for a fixed 20 s.
FUZZ_BUILD ?= build-fuzz
FUZZ_SECONDS ?= 60
FUZZ_TARGETS = encore_fuzz_load encore_fuzz_prepare encore_fuzz_numbers
FUZZ_MODELS ?= ../shared/models
# One process per target (the machine is shared); -jobs would also log to ./fuzz-N.log.
FUZZ_FLAGS = -dict=fuzz/gltf.dict -max_len=65536 -timeout=10 -rss_limit_mb=2048 -detect_leaks=1 \
	-print_final_stats=1
FUZZ_ENV = ASAN_OPTIONS=abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1

fuzz-build: deps
	$(call cmake_configure,$(FUZZ_BUILD),-DCMAKE_CXX_COMPILER=$$(command -v clang++) -DENCORE_FUZZ=ON \
		-DENCORE_BUILD_TESTS=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo \
		'-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=$(RELWITHDEBINFO_FLAGS)')
	@cmake --build $(FUZZ_BUILD) -j$(JOBS) --target $(FUZZ_TARGETS) encore_fuzz_corpus
	@bash fuzz/make-corpus.sh $(FUZZ_BUILD)/fuzz/seeds \
		$(FUZZ_BUILD)/fuzz/encore_fuzz_corpus_generator $(FUZZ_MODELS) $(ENCORE)

fuzz: fuzz-build
	@for target in $(FUZZ_TARGETS); do \
		mkdir -p $(FUZZ_BUILD)/fuzz/corpus/$$target $(FUZZ_BUILD)/fuzz/findings && \
		echo "fuzz: $$target for $(FUZZ_SECONDS) s" && \
		$(FUZZ_ENV) $(FUZZ_BUILD)/fuzz/$$target $(FUZZ_FLAGS) -max_total_time=$(FUZZ_SECONDS) \
			-artifact_prefix=$(FUZZ_BUILD)/fuzz/findings/$$target- \
			$(FUZZ_BUILD)/fuzz/corpus/$$target $(FUZZ_BUILD)/fuzz/seeds || exit 1; \
	done

fuzz-replay: fuzz-build
	@for target in $(FUZZ_TARGETS); do \
		rm -rf $(FUZZ_BUILD)/fuzz/replay/$$target && \
		mkdir -p $(FUZZ_BUILD)/fuzz/replay/$$target $(FUZZ_BUILD)/fuzz/findings && \
		echo "fuzz-replay: $$target" && \
		$(FUZZ_ENV) $(FUZZ_BUILD)/fuzz/$$target $(FUZZ_FLAGS) -runs=0 $(FUZZ_BUILD)/fuzz/seeds && \
		$(FUZZ_ENV) $(FUZZ_BUILD)/fuzz/$$target $(FUZZ_FLAGS) -max_total_time=20 \
			-artifact_prefix=$(FUZZ_BUILD)/fuzz/findings/$$target- \
			$(FUZZ_BUILD)/fuzz/replay/$$target $(FUZZ_BUILD)/fuzz/seeds || exit 1; \
	done

# The frame fuzzer (docs/fuzzing.md) of the sanitizer build, run long: FRAME_FUZZ_ITERATIONS
# mutated seeds through load, prepare and one frame on lavapipe, from iteration FRAME_FUZZ_FIRST
# with random seed FRAME_FUZZ_SEED (make test-sanitize runs 1,000 of them).
FRAME_FUZZ_ITERATIONS ?= 5000
FRAME_FUZZ_FIRST ?= 0
FRAME_FUZZ_SEED ?= 1
FRAME_FUZZ_DIR = $(ASAN_BUILD)/tests/frame-fuzz
fuzz-frame: sanitize-configure
	@cmake --build $(ASAN_BUILD) -j$(JOBS) --target encore_frame_fuzzer \
		encore_fuzz_corpus_generator encore
	@bash fuzz/make-corpus.sh $(FRAME_FUZZ_DIR)/seeds \
		$(ASAN_BUILD)/tests/encore_fuzz_corpus_generator $(FUZZ_MODELS) \
		$(ASAN_BUILD)/apps/encore/encore
	@$(SANITIZE_ENV) $(ASAN_BUILD)/tests/encore_frame_fuzzer \
		--iterations $(FRAME_FUZZ_ITERATIONS) --first $(FRAME_FUZZ_FIRST) \
		--seed $(FRAME_FUZZ_SEED) --findings $(FRAME_FUZZ_DIR)/findings $(FRAME_FUZZ_DIR)/seeds

clean:
	rm -rf $(BUILD) $(ASAN_BUILD) $(WHEEL_BUILD) $(OUT)
