# Entry points for a fresh Debian 12 machine: `make demo` and `make test` do all set-up.
BUILD ?= build
JOBS ?= 2
PREFIX ?= /usr/local
CMAKE_FLAGS ?=
# make sanitize: the unit tests built with ASan + UBSan (gcc); SANITIZE_TESTS, when given, a Catch2
# test spec that picks some (file names are tags: [#test_mesh_io],[#test_hostile_inputs]).
# make fuzz: each libFuzzer target of fuzz/ for FUZZ_SECONDS.
SANITIZE_BUILD ?= build-sanitize
SANITIZE_TESTS ?=
FUZZ_BUILD ?= build-fuzz
FUZZ_SECONDS ?= 60
# CI's share of both: the tests of the input readers, the samples, the predicates, the diagrams
# and their verification, the MPS, the metrics and the pictures (under the sanitizers about a
# quarter of the suite's time: the remesh tests, three quarters of it, run the same predicates
# and diagrams many times over), and 60 s of each fuzz target.
CI_SANITIZE_TESTS ?= [\#test_hostile_inputs],[\#test_mesh_io],[\#test_samples],[\#test_predicates],[\#test_ball_triangle],[\#test_symbolic_vertex],[\#test_lrvd],[\#test_verification],[\#test_surface_mesh],[\#test_mps],[\#test_mps_features],[\#test_quality],[\#test_remesh_check],[\#test_render]
CI_FUZZ_SECONDS ?= 60

.PHONY: all setup configure build test unit sanitize fuzz demo bench images install clean

all: build

setup:
	bash scripts/setup.sh $(BUILD)/cgal-data

configure: setup
	cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release $(CMAKE_FLAGS)

build: configure
	cmake --build $(BUILD) -j $(JOBS)

# What CI runs (.ci/run): every unit test, then the unit tests of CI_SANITIZE_TESTS under ASan and
# UBSan, then each fuzz target for CI_FUZZ_SECONDS. `make unit` runs the unit tests alone.
test: unit
	$(MAKE) sanitize SANITIZE_TESTS='$(CI_SANITIZE_TESTS)'
	$(MAKE) fuzz FUZZ_SECONDS=$(CI_FUZZ_SECONDS)

unit: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS) --timeout 900

# Every unit test under AddressSanitizer and UndefinedBehaviorSanitizer; any report fails its test.
sanitize: setup
	cmake -S . -B $(SANITIZE_BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release -DLRVD_SANITIZE=ON -DLRVD_BUILD_PYTHON=OFF \
	  -DLRVD_CGAL_DATA_DIR=$(abspath $(BUILD))/cgal-data $(CMAKE_FLAGS)
	cmake --build $(SANITIZE_BUILD) -j $(JOBS) --target lrvd lrvd_tests lrvd_library_example
	cd $(SANITIZE_BUILD) && export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1 && \
	  $(if $(SANITIZE_TESTS),./lrvd_tests -# '$(SANITIZE_TESTS)',ctest --output-on-failure -j $(JOBS) --timeout 1800)

# The libFuzzer targets (clang 14, ASan + UBSan), each run for FUZZ_SECONDS from the generated seeds
# and its corpus; a crashing input is kept in tests/data/fuzz/TARGET/, which the unit tests replay.
fuzz: setup
	cmake -S . -B $(FUZZ_BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=clang++-14 \
	  -DLRVD_FUZZ=ON -DLRVD_BUILD_TESTS=OFF -DLRVD_BUILD_PYTHON=OFF $(CMAKE_FLAGS)
	cmake --build $(FUZZ_BUILD) -j $(JOBS) --target fuzz_mesh_file fuzz_point_files fuzz_compute lrvd_fuzz_seeds
	bash fuzz/run.sh $(FUZZ_BUILD) $(FUZZ_SECONDS)

# Remesh CGAL's elk (genus 1, thin legs and antlers) to exactly 516 vertices with a CVT on the
# LRVD, check the result, and write the LRVD cells of 300 random samples beside it; a picture of each.
demo: build
	mkdir -p $(BUILD)/demo
	$(BUILD)/lrvd remesh $(BUILD)/cgal-data/elk.off -n 516 --seed 1 \
	  -o $(BUILD)/demo/elk_516.off --report $(BUILD)/demo/elk_516_report.json
	$(BUILD)/lrvd compute $(BUILD)/cgal-data/elk.off -n 300 --seed 1 \
	  -o $(BUILD)/demo/elk_lrvd_cells.ply --report $(BUILD)/demo/elk_lrvd_report.json
	$(BUILD)/lrvd render $(BUILD)/demo/elk_516.off --edges -o $(BUILD)/demo/elk_516.png
	$(BUILD)/lrvd render $(BUILD)/cgal-data/elk.off -n 300 --seed 1 -o $(BUILD)/demo/elk_lrvd_cells.png

# The 20-row CVT remeshing table (four CGAL models, N = 300 ... 4000), LRVD only, one thread:
# about a minute. docs/results.md and bench/README.md give the full tables and how to read them.
bench: build
	mkdir -p $(BUILD)/bench
	$(BUILD)/bench_remesh --lrvd-only --threads 1 --out $(BUILD)/bench/remesh.md --json $(BUILD)/bench/remesh.json

# The pictures of docs/reference/render.md (lrvd render on the elk and the comb stress mesh).
images: build
	bash scripts/docs_images.sh $(BUILD)

# The lrvd command, the libraries, their headers and the CMake package (docs/guide/library.md), and
# the Python module under the prefix's site-packages (docs/guide/python.md).
install: build
	cmake --install $(BUILD) --prefix $(PREFIX)

clean:
	rm -rf $(BUILD) $(SANITIZE_BUILD) $(FUZZ_BUILD)
