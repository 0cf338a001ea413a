# Thin wrappers over CMake and CTest. Each target first installs what is missing (Debian, apt).
JOBS ?= $(shell nproc)
SANITIZE ?= 0

SANITIZE_DIR ?= build-sanitize
# No Python module: an instrumented library cannot be loaded by an uninstrumented interpreter.
# -O1 -g1 (line tables for the reports' stack traces), as the sanitizers' authors advise: with
# Eigen, -O2 -g under ASan compiles 2.5 times slower (docs/reliability.md).
SANITIZE_FLAGS = -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
  -DTHETAD_SANITIZE=ON -DTHETAD_BUILD_BENCH=OFF -DTHETAD_BUILD_PYTHON=OFF

ifeq ($(SANITIZE),1)
BUILD_DIR ?= $(SANITIZE_DIR)
CMAKE_FLAGS += $(SANITIZE_FLAGS)
else
BUILD_DIR ?= build
CMAKE_FLAGS += -DCMAKE_BUILD_TYPE=Release
endif
BENCH_DIR ?= build-bench
OUT ?= out
# Ninja for a new build folder: it compiles a target's units while the libraries it links are still
# being built, where Make's generated files wait for them, so that both cores stay busy (docs/
# performance-log.md, "Build time, third pass"). A folder keeps the generator it was configured with.
generator = $(if $(wildcard $(1)/CMakeCache.txt),,-G Ninja)

.PHONY: all deps configure build program test sanitize demo bench fuzz clean

all: build

deps:
	@bash scripts/install-deps.sh

configure: deps
	cmake -S . -B $(BUILD_DIR) $(call generator,$(BUILD_DIR)) $(CMAKE_FLAGS)

build: configure
	cmake --build $(BUILD_DIR) -j $(JOBS)

# The thetad program alone (what the demo runs): no test, benchmark or Python module.
program: configure
	cmake --build $(BUILD_DIR) -j $(JOBS) --target thetad

test: build
	cd $(BUILD_DIR) && ctest --output-on-failure -j $(JOBS)

# The sanitizer subset (docs/reliability.md): the unit tests of the numerics, the simulator and
# the readers, and the fuzz replays, under ASan and UBSan; builds only what they need.
sanitize: deps
	cmake -S . -B $(SANITIZE_DIR) $(call generator,$(SANITIZE_DIR)) $(SANITIZE_FLAGS)
	cmake --build $(SANITIZE_DIR) -j $(JOBS) --target sanitize_tests
	cd $(SANITIZE_DIR) && ctest --output-on-failure -j $(JOBS) -L sanitize

# The quick diagnostics first, then scenario I with every disturbance of the paper (seed 1), logging
# every 20th sample (the figures draw ~1500 windows; the summaries use every sample), then
# its figures (the paper's Figs. 2-9 with the controllers overlaid; see docs/reproduction.md).
demo: program
	$(BUILD_DIR)/apps/thetad demo --out $(OUT)
	$(BUILD_DIR)/apps/thetad compare --scenario scenario-1 --controllers all --seed 1 --log-every 20 --out $(OUT)/scenario-1
	$(BUILD_DIR)/apps/thetad plot --in $(OUT)/scenario-1 --out $(OUT)/scenario-1/figures --baseline theta-d

# Benchmarks are built separately with -march=native (see docs/performance.md).
bench: deps
	cmake -S . -B $(BENCH_DIR) $(call generator,$(BENCH_DIR)) -DCMAKE_BUILD_TYPE=Release -DTHETAD_NATIVE=ON -DTHETAD_BUILD_TESTS=OFF
	cmake --build $(BENCH_DIR) -j $(JOBS)
	bash bench/run.sh $(BENCH_DIR) $(OUT)/bench

# libFuzzer targets (Clang, ASan, UBSan) of the input readers, each run FUZZ_SECONDS from the seed
# corpus; new inputs go to build-fuzz/corpus, crashes to build-fuzz/findings (docs/reliability.md).
FUZZ_DIR ?= build-fuzz
FUZZ_SECONDS ?= 60
fuzz:
	@bash scripts/install-deps.sh clang libclang-rt-14-dev
	CC=clang CXX=clang++ cmake -S . -B $(FUZZ_DIR) $(call generator,$(FUZZ_DIR)) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTHETAD_FUZZ=ON \
	  -DTHETAD_BUILD_TESTS=OFF -DTHETAD_BUILD_BENCH=OFF -DTHETAD_BUILD_PYTHON=OFF
	cmake --build $(FUZZ_DIR) -j $(JOBS) --target fuzz_scenario fuzz_settings fuzz_controllers fuzz_campaign
	for target in scenario settings controllers campaign; do \
	  mkdir -p $(FUZZ_DIR)/corpus/$$target $(FUZZ_DIR)/findings/$$target && \
	  $(FUZZ_DIR)/fuzz/fuzz_$$target -max_total_time=$(FUZZ_SECONDS) -timeout=10 -rss_limit_mb=4096 \
	    -artifact_prefix=$(FUZZ_DIR)/findings/$$target/ $(FUZZ_DIR)/corpus/$$target fuzz/corpus/$$target || exit 1; \
	done

clean:
	rm -rf build $(SANITIZE_DIR) $(BENCH_DIR) $(FUZZ_DIR)
