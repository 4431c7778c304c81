# Thin wrapper over CMake. `make demo` and `make test` work on a fresh Debian 12 machine: they install what is
# missing (scripts/install-deps.sh), configure, build, and then render or test.
BUILD ?= build
JOBS ?= $(shell nproc)
CMAKE_ARGS ?=

.PHONY: all deps configure build demo test bench clean

all: build

deps:
	bash scripts/install-deps.sh

configure: deps
	cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release $(CMAKE_ARGS)

build: configure
	cmake --build $(BUILD) -j $(JOBS)

demo: build
	mkdir -p out
	./$(BUILD)/torte scenes/cornell-box.lua output=out/cornell-box.exr

test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS) --timeout 600

bench: CMAKE_ARGS += -DTORTE_BUILD_BENCH=ON
bench: build
	@ls $(BUILD)/bench 2>/dev/null || echo "no benchmarks yet"

clean:
	rm -rf $(BUILD) out
