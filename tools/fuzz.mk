# fuzz.mk - robustness targets, included by the Makefile (which sets FUZZ_SECONDS, BUILD, SAN).
#
#   make fuzz FUZZ_SECONDS=N   build tests/fuzz/fuzz_*.c with clang -fsanitize=fuzzer,address,
#                              undefined and run each target N seconds from its committed seed
#                              corpus. A crash, leak, timeout or out-of-memory input is copied to
#                              tests/fuzz/regressions/<target>/ (replayed by `make test` from then
#                              on: tests/unit/test_fuzz_replay.c) and the target fails.
#   make valgrind              tools/valgrind.sh: memcheck of a small bake and a short
#                              surfaceless run, suppressions only for Mesa's own code.
#
# New inputs libFuzzer finds go to $(FUZZ_BUILD)/corpus/<target>, not into the committed seeds;
# promote a useful one by copying it to tests/fuzz/corpus/<target>/ by hand.

# ---- knobs ---------------------------------------------------------------------------------
# compiler for the fuzz build (libFuzzer ships with clang)
FUZZ_CC ?= clang
# where the fuzz build and its working corpora go
FUZZ_BUILD ?= build/fuzz
# extra libFuzzer flags, e.g. FUZZ_FLAGS=-jobs=2
FUZZ_FLAGS ?=
# ---------------------------------------------------------------------------------------------

FUZZ_TARGETS := fuzz_ktx fuzz_manifest fuzz_preset fuzz_set
# The layers below the GL ones, whole (a module added there is built here too): the loaders,
# the bake and the CPU side of the sea (fuzz_set); the GL modules are not fuzzed, so they are
# not built.
FUZZ_LIB_SRC := $(wildcard src/core/*.c src/tables/*.c src/optics/*.c src/bake/*.c \
                           src/geometry/*.c)
FUZZ_SAN := -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer
FUZZ_CFLAGS := -std=c11 -D_GNU_SOURCE -D_FILE_OFFSET_BITS=64 -Wall -Wextra -Wshadow -Wno-unused-parameter -O1 -g \
               $(FUZZ_SAN) -Iinclude -Isrc -I$(BUILD)/gen -Itests/fuzz
FUZZ_LIB_OBJ := $(FUZZ_LIB_SRC:src/%.c=$(FUZZ_BUILD)/obj/%.o)
FUZZ_BIN := $(FUZZ_TARGETS:%=$(FUZZ_BUILD)/%)

.PHONY: fuzz fuzz-build valgrind
.SECONDARY: $(FUZZ_LIB_OBJ)

$(FUZZ_BUILD)/obj/%.o: src/%.c
	@mkdir -p $(dir $@)
	$(FUZZ_CC) $(FUZZ_CFLAGS) -fsanitize=fuzzer-no-link -MMD -MP -c $< -o $@

$(FUZZ_BUILD)/obj/core/datadir.o: $(BUILD)/gen/datadir_paths.h

$(FUZZ_BUILD)/%: tests/fuzz/%.c tests/fuzz/fuzz_common.h $(FUZZ_LIB_OBJ)
	@mkdir -p $(dir $@)
	$(FUZZ_CC) $(FUZZ_CFLAGS) -fsanitize=fuzzer -o $@ $< $(FUZZ_LIB_OBJ) \
	    $(shell $(PKG_CONFIG) --libs zlib libpng fftw3f) -lm -lpthread

fuzz-build: $(FUZZ_BIN)

# Each target: libFuzzer exits non-zero on the first failing input and writes it with the
# artifact prefix; every artifact is then kept as a regression and the run fails.
fuzz: $(FUZZ_BIN)
	@status=0; \
	for t in $(FUZZ_TARGETS); do \
	    work=$(FUZZ_BUILD)/corpus/$$t; art=$(FUZZ_BUILD)/artifacts/$$t; \
	    mkdir -p $$work $$art tests/fuzz/regressions/$$t; rm -f $$art/*; \
	    echo "fuzz $$t: $(FUZZ_SECONDS) s"; \
	    dict=tests/fuzz/$$t.dict; [ -e $$dict ] || dict=tests/fuzz/fuzz_manifest.dict; \
	    $(FUZZ_BUILD)/$$t -max_total_time=$(FUZZ_SECONDS) -timeout=10 -rss_limit_mb=2048 \
	        -print_final_stats=1 -artifact_prefix=$$art/ -dict=$$dict $(FUZZ_FLAGS) \
	        $$work tests/fuzz/corpus/$$t > $(FUZZ_BUILD)/$$t.log 2>&1; rc=$$?; \
	    grep -E '^stat::number_of_executed_units|^stat::peak_rss_mb|^#[0-9]+.*DONE' \
	        $(FUZZ_BUILD)/$$t.log | sed "s/^/  $$t: /"; \
	    found=$$(ls $$art 2>/dev/null); \
	    if [ $$rc -ne 0 ] || [ -n "$$found" ]; then \
	        status=1; echo "FAIL fuzz $$t (exit $$rc); log: $(FUZZ_BUILD)/$$t.log"; \
	        grep -E 'ERROR|SUMMARY|contract violated' $(FUZZ_BUILD)/$$t.log | head -n 5; \
	        for f in $$found; do \
	            cp $$art/$$f tests/fuzz/regressions/$$t/$$f; \
	            echo "  kept tests/fuzz/regressions/$$t/$$f"; \
	        done; \
	    else echo "PASS fuzz $$t"; fi; \
	done; \
	exit $$status

# tests/cli/test_bad_input.sh drives both programs, so the unit suite needs swell built too.
test-unit: $(SWELL)

valgrind: $(SWELL_BAKE) $(SWELL)
	@tools/valgrind.sh $(BUILD)

-include $(wildcard $(FUZZ_BUILD)/obj/*.d)
