# manylods - build, test and demo.
#
#   make demo        build and run examples/demo (a built-in procedural scene)
#   make test        every test, gcc -O2 and clang with sanitizers, the compile
#                    matrix and examples/minimal; ends with "N passed, M failed"
#   make test-fast   only the tests built with gcc -O2
#   make matrix      only the compile matrix (tests/compile/matrix.sh)
#   make clean       remove build/
#
# CC, CXX, CLANG and CLANGXX may be overridden (make test CC=gcc-13).  V=1
# shows the compiler command lines.  Everything built lands under build/.

ifeq ($(origin CC),default)
CC = gcc
endif
ifeq ($(origin CXX),default)
CXX = g++
endif
CLANG ?= clang
CLANGXX ?= clang++
export CC CXX CLANG CLANGXX

BUILD    := build
WARNINGS := -Wall -Wextra -pedantic
CFLAGS   ?=
LDLIBS   := -lm -pthread
TEST_CFLAGS := -std=c99 -O2 $(WARNINGS) -I. $(CFLAGS)
SAN_CFLAGS  := -std=c99 -fsanitize=address,undefined -fno-sanitize-recover=all -g -O1 \
               -fno-omit-frame-pointer $(WARNINGS) -I. $(CFLAGS)
EXAMPLE_CFLAGS := -std=c99 -O2 $(WARNINGS) $(CFLAGS)
DEMO_DEFINES ?= -DMANYLODS_PTHREADS
# Test programs build in parallel: with the caller's -jN if given, else on
# every core.
JOBS ?= $(shell nproc 2>/dev/null || echo 2)
PARALLEL = $(if $(findstring jobserver,$(MAKEFLAGS)),,-j$(JOBS))

TEST_SOURCES := $(sort $(wildcard tests/test_*.c))
TEST_NAMES   := $(TEST_SOURCES:tests/%.c=%)
GCC_TESTS    := $(TEST_NAMES:%=$(BUILD)/gcc/%)
SAN_TESTS    := $(TEST_NAMES:%=$(BUILD)/san/%)
HEADERS      := manylods.h $(wildcard tests/*.h) $(wildcard examples/*.h)

# LeakSanitizer on, and a readable report from UBSan.
export ASAN_OPTIONS ?= detect_leaks=1:abort_on_error=0
export UBSAN_OPTIONS ?= print_stacktrace=1

ifeq ($(V),1)
Q :=
say = @true
else
Q := @
say = @printf '  %-6s %s\n'
endif

.PHONY: all demo test test-fast matrix clean test-programs fast-programs
.DELETE_ON_ERROR:

all: $(BUILD)/examples/demo $(BUILD)/examples/minimal

demo: $(BUILD)/examples/demo
	$(Q)$(BUILD)/examples/demo

# Build what can be built (-k), then let tests/run.sh count a program that did
# not build as a failure: the last line is always the total.
test:
	-$(Q)$(MAKE) --no-print-directory -s -k $(PARALLEL) test-programs
	$(Q)tests/run.sh \
	    --section "tests, $(CC) -O2" $(GCC_TESTS) \
	    --section "tests, $(CLANG) -fsanitize=address,undefined -O1" $(SAN_TESTS) \
	    --section "compile matrix" tests/compile/matrix.sh \
	    --section "examples" --check $(BUILD)/examples/minimal

test-fast:
	-$(Q)$(MAKE) --no-print-directory -s -k $(PARALLEL) fast-programs
	$(Q)tests/run.sh --section "tests, $(CC) -O2" $(GCC_TESTS)

matrix:
	$(Q)tests/compile/matrix.sh

test-programs: $(GCC_TESTS) $(SAN_TESTS) $(BUILD)/examples/minimal
fast-programs: $(GCC_TESTS)

$(BUILD)/gcc/%: tests/%.c $(HEADERS)
	$(say) CC $@
	$(Q)mkdir -p $(@D) && rm -f $@
	$(Q)$(CC) $(TEST_CFLAGS) $< -o $@ $(LDLIBS)

$(BUILD)/san/%: tests/%.c $(HEADERS)
	$(say) CLANG $@
	$(Q)mkdir -p $(@D) && rm -f $@
	$(Q)$(CLANG) $(SAN_CFLAGS) $< -o $@ $(LDLIBS)

$(BUILD)/examples/minimal: examples/minimal.c manylods.h
	$(say) CC $@
	$(Q)mkdir -p $(@D) && rm -f $@
	$(Q)$(CC) $(EXAMPLE_CFLAGS) $< -o $@ $(LDLIBS)

$(BUILD)/examples/demo: examples/demo.c $(HEADERS)
	$(say) CC $@
	$(Q)mkdir -p $(@D) && rm -f $@
	$(Q)$(CC) $(EXAMPLE_CFLAGS) $(DEMO_DEFINES) $< -o $@ $(LDLIBS)

clean:
	rm -rf $(BUILD)
