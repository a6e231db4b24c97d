# hrm.h - build, test and benchmark.
#   make test    the compile matrix (gcc/clang, C99/C++, double/float,
#                -O0/-O2, ASan+UBSan, HRM_STATIC, C/C++ linkage), each run
#                of the test suite, ending with the line "N passed, N failed"
#   make bench   the single-ray convergence benchmark (writes bench/out/)
#   make examples
CC      ?= cc
WARN    = -Wall -Wextra -pedantic -Werror -Wshadow -Wdouble-promotion
BUILD   = build

.PHONY: all test bench bench-quick examples clean

all: test

test:
	@sh tests/run.sh

$(BUILD)/bench: bench/bench.c bench/reference.h bench/scenes.h bench/svg.h hrm.h
	@mkdir -p $(BUILD)
	$(CC) -std=c99 -O2 $(WARN) -I. bench/bench.c -o $@ -lm

# bench/out/ is the run's scratch output (ignored by git); bench/results/ is
# the committed snapshot of its figures and summary that the README links to.
bench: $(BUILD)/bench
	./$(BUILD)/bench --out bench/out
	@mkdir -p bench/results
	cp bench/out/*.svg bench/out/summary.md bench/results/

bench-quick: $(BUILD)/bench
	./$(BUILD)/bench --quick --out bench/out/quick

$(BUILD)/example_ray: examples/ray.c hrm.h
	@mkdir -p $(BUILD)
	$(CC) -std=c99 -O2 $(WARN) -I. examples/ray.c -o $@ -lm

$(BUILD)/example_render: examples/render.c hrm.h
	@mkdir -p $(BUILD)
	$(CC) -std=c99 -O2 $(WARN) -I. examples/render.c -o $@ -lm

examples: $(BUILD)/example_ray $(BUILD)/example_render

clean:
	rm -rf $(BUILD)
