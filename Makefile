# Entry points for a fresh Debian 12 machine: `make demo` and `make test` do all set-up.
BUILD ?= build
JOBS ?= 2
PREFIX ?= /usr/local
CMAKE_FLAGS ?=

.PHONY: all setup configure build test demo bench images install clean

all: build

setup:
	bash scripts/setup.sh $(BUILD)/cgal-data

configure: setup
	cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release $(CMAKE_FLAGS)

build: configure
	cmake --build $(BUILD) -j $(JOBS)

test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS) --timeout 900

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
	rm -rf $(BUILD)
