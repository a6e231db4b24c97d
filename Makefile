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

$(BUILD)/bench: bench/bench.c bench/reference.h bench/scenes.h hrm.h
	@mkdir -p $(BUILD)
	$(CC) -std=c99 -O2 $(WARN) -I. bench/bench.c -o $@ -lm

bench: $(BUILD)/bench
	@mkdir -p bench/out
	./$(BUILD)/bench

bench-quick: $(BUILD)/bench
	./$(BUILD)/bench --quick

$(BUILD)/example_ray: examples/ray.c hrm.h
	@mkdir -p $(BUILD)
	$(CC) -std=c99 -O2 $(WARN) -I. examples/ray.c -o $@ -lm

$(BUILD)/example_render: examples/render.c hrm.h
	@mkdir -p $(BUILD)
	$(CC) -std=c99 -O2 $(WARN) -I. examples/render.c -o $@ -lm

examples: $(BUILD)/example_ray $(BUILD)/example_render

clean:
	rm -rf $(BUILD)
