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

.PHONY: all deps configure build demo test test-unit test-gpu test-sanitize bench-smoke clean \
	fuzz-build fuzz fuzz-replay

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

# Unit, command-line (bad input) and the robustness GPU tests (device limits, device loss, fault
# injection, soak: CTest label sanitize) under AddressSanitizer + UndefinedBehaviorSanitizer, with
# LeakSanitizer on.
test-sanitize: deps
	@mkdir -p $(ASAN_BUILD)
	@cmake -S . -B $(ASAN_BUILD) -DCMAKE_BUILD_TYPE=Debug -DENCORE_SANITIZE=ON -Wno-dev \
		> $(ASAN_BUILD)/configure.log 2>&1 || (cat $(ASAN_BUILD)/configure.log; exit 1)
	@cmake --build $(ASAN_BUILD) -j$(JOBS)
	@cd $(ASAN_BUILD) && ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 \
		UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
		ctest --output-on-failure -j2 --timeout 900 -L 'unit|cli|sanitize'

# libFuzzer targets of the loader (docs/fuzzing.md), built with clang in their own directory.
# `make fuzz` fuzzes each target for FUZZ_SECONDS on a working corpus that persists between
# runs; `make fuzz-replay` (CI) replays the seed corpus and fuzzes each for a fixed 20 s.
FUZZ_BUILD ?= build-fuzz
FUZZ_SECONDS ?= 60
FUZZ_TARGETS = encore_fuzz_load encore_fuzz_prepare
FUZZ_MODELS ?= ../shared/models
# One process per target (the machine is shared); -jobs would also log to ./fuzz-N.log.
FUZZ_FLAGS = -dict=fuzz/gltf.dict -max_len=65536 -timeout=10 -rss_limit_mb=2048 -detect_leaks=1 \
	-print_final_stats=1
FUZZ_ENV = ASAN_OPTIONS=abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1

fuzz-build: deps
	@mkdir -p $(FUZZ_BUILD)
	@test -f $(FUZZ_BUILD)/CMakeCache.txt || CC=clang CXX=clang++ cmake -S . -B $(FUZZ_BUILD) \
		-DENCORE_FUZZ=ON -DENCORE_BUILD_TESTS=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo -Wno-dev \
		$$(command -v ccache >/dev/null && echo -DCMAKE_CXX_COMPILER_LAUNCHER=ccache) \
		> $(FUZZ_BUILD)/configure.log 2>&1 || (cat $(FUZZ_BUILD)/configure.log; exit 1)
	@cmake --build $(FUZZ_BUILD) -j$(JOBS) --target $(FUZZ_TARGETS) encore_fuzz_corpus
	@bash fuzz/make-corpus.sh $(FUZZ_BUILD)/fuzz/seeds $(FUZZ_BUILD)/fuzz/encore_fuzz_corpus \
		$(FUZZ_MODELS) $(ENCORE)

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

clean:
	rm -rf $(BUILD) $(ASAN_BUILD) $(OUT)
