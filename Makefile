# Thin wrapper over CMake. `make demo` and `make test` work on a fresh Debian 12 machine: they install what is
# missing (scripts/install-deps.sh), configure, build, and then render or test.
BUILD ?= build
JOBS ?= $(shell nproc)
CMAKE_ARGS ?=
# The compiler: clang++ (Debian's clang 14, installed by install-deps.sh). Its single-ray traversal kernel is 2 to
# 8 % faster than g++ 12's on the 1 M to 16 M triangle bunnies, the same on small meshes (AVX2 EPYC,
# bench/RESULTS.md, 2026-11-23). `make CXX_COMPILER=g++` builds with GCC (CMake re-creates a build directory's cache when the
# compiler changes).
CXX_COMPILER ?= clang++
CONFIGURE = cmake -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=$(CXX_COMPILER)

.PHONY: all deps configure build demo gallery test test-sanitize test-tsan bench bench-scalar-vs-simd bench-cycles \
        bench-startup fuzz lua-stubs clean

all: build

deps:
	bash scripts/install-deps.sh

configure: deps
	$(CONFIGURE) -S . -B $(BUILD) $(CMAKE_ARGS)

build: configure
	cmake --build $(BUILD) -j $(JOBS)

demo: build
	mkdir -p out
	./$(BUILD)/torte scenes/cornell-box.lua output=out/cornell-box.exr

# The gallery (README.md, "Gallery"): the seed's four figures and one image per shipped scene, rendered by
# scripts/gallery.sh to $(GALLERY_DIR)/<name>.png with $(GALLERY_DIR)/gallery.md (command, time, peak memory,
# geometry per image). About 6 minutes on 2 cores; figures whose ../shared/data is missing are skipped.
# GALLERY_IMAGES picks some by name (e.g. GALLERY_IMAGES='cornell-box shapes'); default all.
GALLERY_DIR ?= docs/gallery
GALLERY_IMAGES ?=

gallery: build
	bash scripts/gallery.sh $(BUILD) $(GALLERY_DIR) $(GALLERY_IMAGES)

test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS) --timeout 600

# Sanitizer builds (tests/sanitizers/README.md): clang with -fsanitize=address,undefined in $(ASAN_BUILD), or
# -fsanitize=thread in $(TSAN_BUILD), the whole suite built; heavy tests run at reduced sizes
# (TORTE_TEST_REDUCED=1, set by the build's ctest environment with the sanitizer options and suppressions).
# `make test-tsan` runs the tests matching TSAN_TESTS (a ctest regex; default all) except those matching
# TSAN_EXCLUDE: the tests that wait for SIGINT to stop a busy Lua loop or a render (TSan defers an asynchronous
# signal until the receiving thread calls an intercepted libc function, which those loops never do, so the
# handler never runs), and one test whose own 60 s limit TSan's slowdown exceeds on 2 busy cores (the wrong-NBT-type
# catalogue: clean when run alone, in 31 s). tests/sanitizers/README.md has the details. Not in .ci/run: no time
# is left there for a third build.
ASAN_BUILD ?= build-asan
TSAN_BUILD ?= build-tsan
SANITIZE_CONFIGURE = cmake -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=clang++ -DTORTE_BUILD_BENCH=OFF
TSAN_TESTS ?= .
TSAN_EXCLUDE ?= runtime: the first Ctrl-C stops Lua code|bad input: interrupt/rt_sigint_(loop|pcall_loop|coroutine|frame_callback|sandboxed|render_save)|minecraft errors: values of the wrong NBT type

test-sanitize: deps
	$(SANITIZE_CONFIGURE) -DTORTE_SANITIZE=address,undefined -S . -B $(ASAN_BUILD) $(CMAKE_ARGS)
	cmake --build $(ASAN_BUILD) -j $(JOBS)
	cd $(ASAN_BUILD) && ctest --output-on-failure -j $(JOBS) --timeout 900

test-tsan: deps
	$(SANITIZE_CONFIGURE) -DTORTE_SANITIZE=thread -S . -B $(TSAN_BUILD) $(CMAKE_ARGS)
	cmake --build $(TSAN_BUILD) -j $(JOBS)
	cd $(TSAN_BUILD) && ctest --output-on-failure -j $(JOBS) --timeout 900 -R '$(TSAN_TESTS)' -E '$(TSAN_EXCLUDE)'

# Benchmarks (bench/RESULTS.md). `make bench` installs Embree (install-deps.sh --bench), configures, builds
# torte_bench and embree-compare, and runs both. Quick by default (bunny, dragon, bunny-1m); BENCH_FULL=1 adds
# the 4 M and 16 M triangle bunnies. BENCH_ARGS go to torte_bench (Google Benchmark flags, e.g.
# BENCH_ARGS='--benchmark_filter=primary --benchmark_min_time=0.3'), COMPARE_ARGS to embree-compare
# (--threads 2, --reps 5, --scenes bunny,dragon).
BENCH_ARGS ?= --benchmark_min_time=0.1
COMPARE_ARGS ?=
BENCH_FULL ?= 0
SCALAR_BUILD ?= $(BUILD)-scalar
SCALAR_VS_SIMD_FILTER ?= /(primary/closest|shadow/any)/wide8/|^(shading|eval)/

bench:
	bash scripts/install-deps.sh --bench
	$(CONFIGURE) -S . -B $(BUILD) -DTORTE_BUILD_BENCH=ON $(CMAKE_ARGS)
	cmake --build $(BUILD) -j $(JOBS) --target torte_bench embree-compare
	TORTE_BENCH_FULL=$(BENCH_FULL) ./$(BUILD)/bench/torte_bench $(BENCH_ARGS)
	TORTE_BENCH_FULL=$(BENCH_FULL) ./$(BUILD)/bench/embree-compare $(COMPARE_ARGS)

# torte against Blender's Cycles (bench/cycles/run.sh; install-deps.sh --cycles installs Debian's blender): the
# Cornell box and the dragon scene at CYCLES_SIZE^2, CYCLES_SPP spp, 64 bounces, CYCLES_THREADS threads; prints both
# times (torte: the whole process; Cycles: its render call), the ratio and the region means of both images.
# CYCLES_SCENES picks scenes (cornell dragon). Takes a few minutes: Cycles alone needs ~1 min per scene.
CYCLES_SCENES ?= cornell dragon
CYCLES_SIZE ?= 256
CYCLES_SPP ?= 1024
CYCLES_THREADS ?= 2

bench-cycles:
	bash scripts/install-deps.sh --cycles
	$(CONFIGURE) -S . -B $(BUILD) $(CMAKE_ARGS)
	cmake --build $(BUILD) -j $(JOBS) --target torte
	SIZE=$(CYCLES_SIZE) SPP=$(CYCLES_SPP) THREADS=$(CYCLES_THREADS) bash bench/cycles/run.sh ./$(BUILD)/torte $(CYCLES_SCENES)

# Start-up of torte on an empty script, median of 5 runs (issue 23: <= 0.1 s).
bench-startup: build
	bash bench/startup.sh ./$(BUILD)/torte 5

# The same torte_bench cases in this SIMD build and in a scalar-only build ($(SCALAR_BUILD), TORTE_SCALAR_ONLY=ON);
# prints per case both rates (Mrays/s; Msamples/s for the shading cases) and speedup=<simd/scalar>.
bench-scalar-vs-simd:
	bash scripts/install-deps.sh
	$(CONFIGURE) -S . -B $(BUILD) -DTORTE_BUILD_BENCH=ON -DTORTE_SCALAR_ONLY=OFF $(CMAKE_ARGS)
	$(CONFIGURE) -S . -B $(SCALAR_BUILD) -DTORTE_BUILD_BENCH=ON -DTORTE_SCALAR_ONLY=ON \
	  -DTORTE_BUILD_TESTS=OFF $(CMAKE_ARGS)
	cmake --build $(BUILD) -j $(JOBS) --target torte_bench
	cmake --build $(SCALAR_BUILD) -j $(JOBS) --target torte_bench
	TORTE_BENCH_FULL=$(BENCH_FULL) bash bench/scalar_vs_simd.sh ./$(BUILD)/bench/torte_bench \
	  ./$(SCALAR_BUILD)/bench/torte_bench '$(SCALAR_VS_SIMD_FILTER)' $(BENCH_ARGS)

# Fuzzing (fuzz/README.md): builds the libFuzzer harnesses with ASan+UBSan in $(FUZZ_BUILD) (clang only; installs
# the runtime with install-deps.sh --fuzz) and runs each for FUZZ_SECONDS on its corpus, one at a time, then prints
# executions, coverage and crashes per harness. FUZZ_HARNESSES picks some (e.g. FUZZ_HARNESSES='ply obj');
# FUZZ_ARGS go to libFuzzer. The seeds and regressions also run in `make test` (fuzz_<name>_replay, no libFuzzer).
FUZZ_BUILD ?= $(BUILD)-fuzz
FUZZ_SECONDS ?= 60
FUZZ_HARNESSES ?= ply obj nbt inflate region image kwargs lua_api

fuzz:
	bash scripts/install-deps.sh --fuzz
	cmake -G Ninja -DCMAKE_BUILD_TYPE=Release '-DCMAKE_CXX_FLAGS_RELEASE=-O1 -DNDEBUG' -DCMAKE_CXX_COMPILER=clang++ \
	  -DTORTE_FUZZ=ON -DTORTE_BUILD_TESTS=OFF -DTORTE_BUILD_BENCH=OFF -S . -B $(FUZZ_BUILD) $(CMAKE_ARGS)
	cmake --build $(FUZZ_BUILD) -j $(JOBS) --target torte_fuzzers
	FUZZ_ARGS='$(FUZZ_ARGS)' bash fuzz/run.sh $(FUZZ_BUILD) $(FUZZ_SECONDS) $(FUZZ_HARNESSES)

# The LuaLS stubs (lua/types/torte.lua) regenerated from docs/lua-api.md; `make test` checks they are current.
lua-stubs: build
	cd $(BUILD) && TORTE_UPDATE_LUA_STUBS=1 ./tests/torte_io_tests '[lua_api_stubs]'

clean:
	rm -rf $(BUILD) out
