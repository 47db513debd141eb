# bench.mk - `make bench` (issue 5): included by the Makefile (`include tools/bench.mk`).
# Runs the scene matrix, bake times and callgrind counts; writes build/bench/results.json,
# docs/bench.md and docs/bench.png. Knobs are environment variables read by tools/bench.sh
# (BENCH_SCENES, BENCH_PATHS, BENCH_QUALITIES, BENCH_TIERS, BENCH_SIZE, BENCH_FRAMES,
# BENCH_WARMUP, BENCH_MINUTES, BENCH_CALLGRIND, BENCH_DETILE), e.g. `make bench
# BENCH_TIERS=gles2-min` or `make bench BENCH_DETILE="on off"`.

# where tools/bench.sh writes results.json, tables and logs
BENCH_OUT ?= build/bench
export BENCH_OUT BENCH_SCENES BENCH_PATHS BENCH_QUALITIES BENCH_TIERS BENCH_SIZE BENCH_FRAMES \
       BENCH_WARMUP BENCH_MINUTES BENCH_CALLGRIND BENCH_CG_FRAMES BENCH_CG_TIERS BENCH_CG_PATHS \
       BENCH_DETILE

.PHONY: bench
bench: deps $(SWELL) $(SWELL_BAKE)
	@tools/bench.sh $(BUILD)

# The README's pictures (docs/*.png), every command listed in tools/pictures.sh.
.PHONY: pictures
pictures: deps $(SWELL)
	@tools/pictures.sh $(BUILD)
