# swell - ocean renderer for OpenGL ES 2 class GPUs.  `make run`, `make test`; see README.md.

# ---- knobs ---------------------------------------------------------------------------------
# C compiler (clang is used automatically for SAN= and fuzz builds if you set CC=clang)
CC ?= cc
# optimisation for the programs and the library
OPT ?= -O2
# sanitizers, e.g. SAN=address,undefined (builds into its own directory)
SAN ?=
# where objects and programs go
BUILD ?= build/$(if $(SAN),san,rel)
# where `make run` bakes the default tables
TABLES_DIR ?= build/tables/default
# where `make install` puts swell; the programs look for their data in $(PREFIX)/share/swell
PREFIX ?= /usr/local
# where the library and swell.pc go
LIBDIR ?= $(PREFIX)/lib
# staging root for packagers: files go to $(DESTDIR)$(PREFIX)/...
DESTDIR ?=
# seconds per fuzz target for `make fuzz`
FUZZ_SECONDS ?= 30
# ---------------------------------------------------------------------------------------------

PKG_CONFIG ?= pkg-config
# binutils matching CC (CC=aarch64-linux-gnu-gcc: aarch64-linux-gnu-ld, -ar, -objcopy), unless
# given on the command line or in the environment
TOOL_PREFIX := $(patsubst %gcc,%,$(filter %-gcc,$(notdir $(CC))))
ifeq ($(origin LD),default)
LD := $(TOOL_PREFIX)ld
endif
ifeq ($(origin AR),default)
AR := $(TOOL_PREFIX)ar
endif
OBJCOPY ?= $(TOOL_PREFIX)objcopy
# the library's packages; the programs add the KMS back-end's
LIB_PKGS := fftw3f libpng zlib cglm egl glesv2
PKGS := $(LIB_PKGS) gbm libdrm libinput libudev
PKG_CFLAGS = $(shell $(PKG_CONFIG) --cflags $(PKGS) 2>/dev/null)
PKG_LIBS = $(shell $(PKG_CONFIG) --libs $(PKGS) 2>/dev/null)
LIB_PKG_LIBS = $(shell $(PKG_CONFIG) --libs $(LIB_PKGS) 2>/dev/null)
# a missing package is named here, not as a missing header in the middle of a build
MISSING_PKGS := $(if $(filter clean deps,$(MAKECMDGOALS)),,$(shell for p in $(PKGS); do \
    $(PKG_CONFIG) --exists $$p 2>/dev/null || printf '%s ' $$p; done))
ifneq ($(strip $(MISSING_PKGS)),)
ifeq ($(filter run test,$(MAKECMDGOALS)),)
$(error pkg-config finds no $(strip $(MISSING_PKGS)): run `make deps` (as root) or tools/install-deps.sh)
endif
endif

WARN := -std=c11 -D_GNU_SOURCE -D_FILE_OFFSET_BITS=64 -Wall -Wextra -Wshadow -Werror=implicit-function-declaration \
        -Wno-unused-parameter
SANFLAGS := $(if $(SAN),-fsanitize=$(SAN) -fno-omit-frame-pointer -fno-sanitize-recover=all,)
CFLAGS ?= -g
# -fPIC: every object also goes into libswell.so; -fvisibility=hidden: it exports swell.h alone
ALL_CFLAGS = $(WARN) $(OPT) $(CPPFLAGS) $(CFLAGS) $(SANFLAGS) $(PKG_CFLAGS) -fPIC \
             -fvisibility=hidden -Iinclude -Isrc -I$(BUILD)/gen -MMD -MP
LDLIBS_ALL = $(LDFLAGS) $(PKG_LIBS) -lm -lpthread

# src/<layer>/<module>.c (docs/architecture.md); the two programs' mains are in src/app
APP_MAIN := src/app/swell.c src/app/swell_bake.c
LIB_SRC := $(filter-out $(APP_MAIN),$(wildcard src/*/*.c))
LIB_OBJ := $(LIB_SRC:src/%.c=$(BUILD)/obj/%.o)
# the programs and tests link every module (internal names included)
LIB := $(BUILD)/libswell-internal.a
# the public library: every layer but the programs' (app) and their KMS back-end (platform)
PUB_OBJ := $(filter-out $(BUILD)/obj/app/% $(BUILD)/obj/platform/%,$(LIB_OBJ))
SO_VERSION := $(shell sed -n 's/^\#define SWELL_VERSION_STRING "\(.*\)"/\1/p' include/swell.h)
SO_MAJOR := $(firstword $(subst ., ,$(SO_VERSION)))
SO_NAME := libswell.so.$(SO_MAJOR)
SHLIB := $(BUILD)/lib/libswell.so.$(SO_VERSION)
STLIB := $(BUILD)/lib/libswell.a
PC := $(BUILD)/lib/swell.pc

UNIT_SRC := $(wildcard tests/unit/test_*.c)
UNIT_BIN := $(UNIT_SRC:tests/unit/%.c=$(BUILD)/tests/%)
CLI_TESTS := $(wildcard tests/cli/test_*.sh)
FRAME_SRC := $(wildcard tests/frame/test_*.c)
FRAME_BIN := $(FRAME_SRC:tests/frame/%.c=$(BUILD)/tests/%)

SWELL := $(BUILD)/swell
SWELL_BAKE := $(BUILD)/swell-bake

.PHONY: all deps run install uninstall test test-unit test-unit-O0 test-shaders test-frame test-kms bench fuzz clean golden test-devices test-cross test-unit-exec

all: $(SWELL_BAKE) $(SWELL) $(SHLIB) $(STLIB) $(PC)

deps:
	@tools/install-deps.sh

$(BUILD)/obj/%.o: src/%.c
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) -c $< -o $@

$(BUILD)/tools/%.o: tools/%.c
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) -c $< -o $@

# the library's shader assembler for tools/validate-shaders.sh
SHADER_SOURCE := $(BUILD)/tools/shader-source
$(SHADER_SOURCE): $(BUILD)/tools/shader_source.o $(LIB)
	$(CC) $(OPT) $(SANFLAGS) $(CFLAGS) -o $@ $< $(LIB) $(LDLIBS_ALL)

$(BUILD)/tests/%.o: tests/unit/%.c
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) -Itests -c $< -o $@

$(BUILD)/tests/%.o: tests/frame/%.c
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) -Itests -c $< -o $@

# The data search order's directories (src/core/datadir.h), rewritten only when they change so
# a new PREFIX rebuilds datadir.o and nothing else.
DATADIR := $(PREFIX)/share/swell
$(BUILD)/gen/datadir_paths.h: FORCE
	@mkdir -p $(dir $@)
	@printf '#define SWELL_INSTALL_DATADIR "%s"\n#define SWELL_SOURCE_DIR "%s"\n' \
	    '$(DATADIR)' '$(CURDIR)' > $@.tmp
	@if cmp -s $@.tmp $@; then rm -f $@.tmp; else mv $@.tmp $@; fi
$(BUILD)/obj/core/datadir.o: $(BUILD)/gen/datadir_paths.h
.PHONY: FORCE
FORCE:

$(LIB): $(LIB_OBJ)
	@mkdir -p $(dir $@)
	rm -f $@
	$(AR) rcs $@ $^

# libswell.so: only swell.h's symbols exported (-fvisibility=hidden, SWELL_API)
$(SHLIB): $(PUB_OBJ)
	@mkdir -p $(dir $@)
	$(CC) -shared -Wl,-soname,$(SO_NAME) -Wl,--no-undefined $(SANFLAGS) -o $@ $^ \
	    $(LDFLAGS) $(LIB_PKG_LIBS) -lm -lpthread
	ln -sf $(notdir $@) $(BUILD)/lib/$(SO_NAME)
	ln -sf $(SO_NAME) $(BUILD)/lib/libswell.so

# libswell.a: the same objects linked into one, every name but swell.h's made local, so an
# application's own names never meet the library's
$(STLIB): $(PUB_OBJ)
	@mkdir -p $(dir $@)
	$(LD) -r -o $(BUILD)/lib/swell-all.o $^
	$(OBJCOPY) --localize-hidden $(BUILD)/lib/swell-all.o
	rm -f $@
	$(AR) rcs $@ $(BUILD)/lib/swell-all.o

$(PC): tools/swell.pc.in include/swell.h
	@mkdir -p $(dir $@)
	sed -e 's|@PREFIX@|$(PREFIX)|g' -e 's|@LIBDIR@|$(patsubst $(PREFIX)/%,$${prefix}/%,$(LIBDIR))|g' -e 's|@VERSION@|$(SO_VERSION)|g' \
	    -e 's|@PRIVATE@|$(filter-out cglm egl glesv2,$(LIB_PKGS))|g' $< > $@

# The programs are built on the public API as an embedding application is: swell.h, their own
# modules (app, platform) and the core helpers they share with the library (arguments,
# numbers, camera matrices, PNG, files, errors, the data directory; no ocean in them).
# tests/cli/test_public_api.sh checks every object of theirs; swell links libswell.a, whose
# other names are local, so a call into any other module fails to link. swell-bake links the
# internal archive's members it uses (libswell.a is one object: the bake tool would need
# libGLESv2 and libpng at run time).
APP_HELPERS := args parse camera image fsutil fail datadir
HELPER_OBJ := $(APP_HELPERS:%=$(BUILD)/obj/core/%.o)
APP_OBJ := $(filter $(BUILD)/obj/app/% $(BUILD)/obj/platform/%,$(LIB_OBJ))

$(SWELL_BAKE): $(BUILD)/obj/app/swell_bake.o $(LIB)
	$(CC) $(OPT) $(SANFLAGS) $(CFLAGS) -o $@ $< $(LIB) $(LDLIBS_ALL)

$(SWELL): $(BUILD)/obj/app/swell.o $(APP_OBJ) $(HELPER_OBJ) $(STLIB)
	$(CC) $(OPT) $(SANFLAGS) $(CFLAGS) -o $@ $^ $(LDLIBS_ALL)

$(BUILD)/tests/%: $(BUILD)/tests/%.o $(LIB)
	$(CC) $(OPT) $(SANFLAGS) $(CFLAGS) -o $@ $< $(LIB) $(LDLIBS_ALL) -lcmocka

# ---- install: `make install PREFIX=/usr DESTDIR=/tmp/stage`; the programs find their data in
# share/swell beside their bin/ (src/core/datadir.h), so a staged or moved tree works too.
BINDIR = $(DESTDIR)$(PREFIX)/bin
LIB_DEST = $(DESTDIR)$(LIBDIR)
INC_DEST = $(DESTDIR)$(PREFIX)/include
DATA_DEST = $(DESTDIR)$(PREFIX)/share/swell
MAN1DIR = $(DESTDIR)$(PREFIX)/share/man/man1
DOCDIR = $(DESTDIR)$(PREFIX)/share/doc/swell
SHADER_FILES := $(wildcard shaders_gles/*.vert shaders_gles/*.frag shaders_gles/*.glsl)
PRESET_FILES := $(wildcard tables/*.preset)
MAN1 := docs/man/swell.1 docs/man/swell-bake.1
INSTALLED = $(BINDIR)/swell $(BINDIR)/swell-bake $(SHADER_FILES:%=$(DATA_DEST)/%) \
            $(LIB_DEST)/libswell.so.$(SO_VERSION) $(LIB_DEST)/$(SO_NAME) $(LIB_DEST)/libswell.so \
            $(LIB_DEST)/libswell.a $(LIB_DEST)/pkgconfig/swell.pc $(INC_DEST)/swell.h \
            $(PRESET_FILES:%=$(DATA_DEST)/%) $(MAN1:docs/man/%=$(MAN1DIR)/%) $(DOCDIR)/LICENSE

install: all
	install -d $(BINDIR) $(DATA_DEST)/shaders_gles $(DATA_DEST)/tables $(MAN1DIR) $(DOCDIR)
	install -m 755 $(SWELL) $(SWELL_BAKE) $(BINDIR)/
	install -m 644 $(SHADER_FILES) $(DATA_DEST)/shaders_gles/
	install -m 644 $(PRESET_FILES) $(DATA_DEST)/tables/
	install -m 644 $(MAN1) $(MAN1DIR)/
	install -m 644 LICENSE $(DOCDIR)/
	install -d $(LIB_DEST)/pkgconfig $(INC_DEST)
	install -m 755 $(SHLIB) $(LIB_DEST)/
	ln -sf libswell.so.$(SO_VERSION) $(LIB_DEST)/$(SO_NAME)
	ln -sf $(SO_NAME) $(LIB_DEST)/libswell.so
	install -m 644 $(STLIB) $(LIB_DEST)/
	install -m 644 $(PC) $(LIB_DEST)/pkgconfig/
	install -m 644 include/swell.h $(INC_DEST)/
	@if [ -z "$(DESTDIR)" ] && [ "$$(id -u)" = 0 ] && command -v ldconfig >/dev/null; then ldconfig; fi

# removes exactly what install put there, then the directories swell owns if they are empty
uninstall:
	rm -f $(INSTALLED)
	-rmdir $(DATA_DEST)/shaders_gles $(DATA_DEST)/tables $(DATA_DEST) $(DOCDIR) 2>/dev/null

# ---- the two commands ------------------------------------------------------------------------
run: deps all
	@tools/run.sh $(BUILD) $(TABLES_DIR)

# With SAN= (e.g. `make test SAN=address,undefined`) the unit and frame suites run under the
# sanitizers; the -O0 rebuild and the KMS VM (TCG-emulated, minutes even without ASan) belong to
# the plain `make test`, which CI runs first.
# the machine make runs on (Debian's name): the KMS VM needs an amd64 one
HOST_ARCH := $(shell dpkg --print-architecture 2>/dev/null || echo unknown)
test:
	@tools/install-deps.sh --test --kms
	$(MAKE) test-unit
	$(if $(SAN),,$(MAKE) test-unit-O0)
	$(MAKE) test-shaders
	$(MAKE) test-frame
	$(if $(SAN),,$(if $(filter amd64,$(HOST_ARCH)),$(MAKE) test-kms,@echo "make test: test-kms \
	    SKIPPED on $(HOST_ARCH): the KMS VM boots Debian's amd64 kernel with a vkms module built \
	    for it (tests/kms/setup.sh), an x86-64 host only; every other suite ran"))
	@echo "make test$(if $(SAN), SAN=$(SAN),): all suites passed$(if $(filter amd64,$(HOST_ARCH)),, except test-kms (see above))"

# compares two PNGs (make test-cross)
IMAGE_DIFF := $(BUILD)/tools/image-diff
$(IMAGE_DIFF): $(BUILD)/tools/image_diff.o $(LIB)
	$(CC) $(OPT) $(SANFLAGS) $(CFLAGS) -o $@ $< $(LIB) $(LDLIBS_ALL)

# Mesa's llvmpipe fault with LP_NATIVE_VECTOR_WIDTH=128, shown without swell (gl/gpu.c refuses it)
$(BUILD)/tools/lp-width-repro: tools/lp_width_repro.c
	@mkdir -p $(dir $@)
	$(CC) $(OPT) $(CFLAGS) -o $@ $< $(shell $(PKG_CONFIG) --cflags --libs egl glesv2)

# seals an edited manifest again, so tests/cli/test_bad_input.sh reaches the value checks
MANIFEST_RESEAL := $(BUILD)/tools/manifest-reseal
$(MANIFEST_RESEAL): $(BUILD)/tools/manifest_reseal.o $(LIB)
	$(CC) $(OPT) $(SANFLAGS) $(CFLAGS) -o $@ $< $(LIB) $(LDLIBS_ALL)

test-unit: $(UNIT_BIN) all $(MANIFEST_RESEAL)
	@tools/run-tests.sh unit $(BUILD) $(UNIT_BIN) $(CLI_TESTS)

# issue 17 item 6: swell built for CROSS_ARCH (arm64; armhf where its packages install) with
# Debian's cross toolchain, its C unit tests under qemu-user, one frame against this machine's
# (tools/cross-test.sh); CI runs it for arm64
CROSS_ARCH ?= arm64
test-cross: all $(IMAGE_DIFF) $(BUILD)/tests/test_golden
	@tools/cross-test.sh $(CROSS_ARCH) $(BUILD)

# the C unit tests alone, through SWELL_EXEC (a runner for another architecture's programs)
test-unit-exec: $(filter-out %.sh,$(UNIT_BIN)) all
	@SWELL_EXEC="$(SWELL_EXEC)" tools/run-tests.sh unit $(BUILD) $(filter-out %.sh,$(UNIT_BIN))

# CPU numerics again without optimisation (catches UB that -O2 hides and vice versa)
test-unit-O0:
	$(MAKE) OPT=-O0 BUILD=$(BUILD)-O0 test-unit

test-shaders: $(SHADER_SOURCE)
	@SWELL_SHADER_SOURCE=$(SHADER_SOURCE) tools/validate-shaders.sh

test-frame: $(FRAME_BIN) $(SWELL)
	@tools/run-tests.sh frame $(BUILD) $(FRAME_BIN)

# The shaders through the real GPUs' compilers: Mesa's lima, vc4, v3d, panfrost, freedreno and
# etnaviv with their noop drm-shims, built once from Debian's mesa source (tools/mesa-shim.sh;
# cached outside the clone), then every GPU model, tier and quality, with and without the demo
# boat's objects (reflections, wakes, shadows, refractions: issue 18; tools/devices.py):
# build/devices/results.json and docs/devices.md. Fails while any program is refused, spills or
# passes 90 % of a hard limit (issue 15). Not in `make test`: it builds Mesa first (about 26
# CPU-minutes, once per machine), and today's shaders fail it. With
# DEVICES_KNOWN=tests/devices/known-problems.txt (what CI runs, .ci/run) the problems listed
# there are expected: it fails on any other, and on a listed one that is gone.
DEVICES_KNOWN ?=
test-devices: $(SWELL) $(SWELL_BAKE)
	tools/mesa-shim.sh > $(BUILD)/mesa-prefix
	/usr/bin/python3 tools/devices.py --build $(BUILD) --prefix "$$(cat $(BUILD)/mesa-prefix)" \
	    $(if $(DEVICES_KNOWN),--known $(DEVICES_KNOWN))

clean:
	rm -rf build

include tests/kms/kms.mk
-include tools/bench.mk
-include tools/fuzz.mk

-include $(shell find $(BUILD) -name "*.d" 2>/dev/null)

# Regenerate the golden frames deliberately (then look at tests/golden/*.png before committing)
golden: $(BUILD)/tests/test_golden $(SWELL)
	SWELL_GOLDEN_UPDATE=1 SWELL_BUILD=$(BUILD) SWELL_TMP=$(BUILD)/tmp $(BUILD)/tests/test_golden
