# materia: a C99 reference implementation of pbrt-v2's material system.
#
#   make                       library (static + shared) and tools, in build/float
#   make check                 every unit test and the conformance suite
#   make PRECISION=double      the same with mt_real = double, in build/double
#   make SANITIZE=address,undefined check
#   make check-tsan            the thread-safety test under ThreadSanitizer (clang)
#   make bench                 benchmarks (float and double, ratios from one run),
#                              then materia and pbrt-v2 side by side (bench-pbrt)
#   make bench-pbrt BENCH_SPP=16 BENCH_REPEAT=1 BENCH_GROUPS=material
#                              only the side-by-side timing, a quick run
#   make demo                  a contact sheet of every material: demo.png
#   make golden                render the golden images again
#   make tradeoff [QUICK=1] [TRADEOFF_ONLY=1,5]
#                              the speed/accuracy trade report, float and
#                              double builds: build/tradeoff/report.md
#   make reference             docs/REFERENCE.md from the parameter tables
#   make amalgamation          build/amalgamation/materia.c and materia.h
#   make NO_EXR=1 NO_PNG=1     without OpenEXR, without libpng (either or both)
#   make vectors               write the published conformance vectors (vectors/)
#   make fuzz FUZZ_SECONDS=60  libFuzzer on every reader (clang), N seconds each
#   make install PREFIX=/usr/local DESTDIR=   (make uninstall with the same)
#
# CFLAGS, CPPFLAGS and LDFLAGS belong to the user: the flags materia needs are
# kept in MT_* variables and added to them.

VERSION      := 0.1.0
SOVERSION    := 0
PRECISION    ?= float
SANITIZE     ?=
PREFIX       ?= /usr/local
DESTDIR      ?=
CFLAGS       ?= -O3 -g
PKG_CONFIG   ?= pkg-config

comma := ,
ifeq ($(filter $(PRECISION),float double),)
$(error PRECISION must be float or double, not '$(PRECISION)')
endif
# Image formats left out (docs/LINKING.md): NO_EXR=1 builds without OpenEXR,
# NO_PNG=1 without libpng, each in a build directory of its own.
NO_EXR ?=
NO_PNG ?=
OMIT := $(if $(NO_EXR),-noexr)$(if $(NO_PNG),-nopng)
BUILD ?= build/$(PRECISION)$(if $(SANITIZE),-$(subst $(comma),-,$(SANITIZE)))$(OMIT)

# --- dependencies, found with pkg-config ------------------------------------
# OpenEXR: only its C API (OpenEXRCore). The OpenEXR module's Libs would drag
# in the C++ libraries, so only its variables are read.
NEED_DEPS := $(filter-out clean distclean help uninstall amalgamation,$(or $(MAKECMDGOALS),all))
DEP_MODULES := $(strip $(if $(NO_PNG),,libpng) $(if $(NO_EXR),,OpenEXR))
ifneq ($(NEED_DEPS),)
  DEPS_OK := $(if $(DEP_MODULES),$(shell $(PKG_CONFIG) --exists $(DEP_MODULES) 2>/dev/null && echo yes),yes)
  ifneq ($(DEPS_OK),yes)
    $(error missing build dependencies (pkg-config $(DEP_MODULES)). Install them with: \
      sudo apt-get install -y pkg-config $(if $(NO_PNG),,libpng-dev) $(if $(NO_EXR),,libopenexr-dev) \
      (or leave a format out: make NO_EXR=1, make NO_PNG=1))
  endif
  ifeq ($(NO_EXR),)
    EXR_INCDIR := $(shell $(PKG_CONFIG) --variable=includedir OpenEXR)
    EXR_LIBDIR := $(shell $(PKG_CONFIG) --variable=libdir OpenEXR)
    EXR_SUFFIX := $(shell $(PKG_CONFIG) --variable=libsuffix OpenEXR)
  endif
  ifeq ($(NO_PNG),)
    PNG_CFLAGS := $(shell $(PKG_CONFIG) --cflags libpng)
    PNG_LIBS   := $(shell $(PKG_CONFIG) --libs libpng)
  endif
endif
DEP_CFLAGS := $(filter-out -I/usr/include,$(if $(NO_EXR),,-I$(EXR_INCDIR)) $(PNG_CFLAGS)) \
              -DMATERIA_HAVE_EXR=$(if $(NO_EXR),0,1) -DMATERIA_HAVE_PNG=$(if $(NO_PNG),0,1)
DEP_LIBS   := $(if $(NO_EXR),,-L$(EXR_LIBDIR) -lOpenEXRCore$(EXR_SUFFIX)) $(PNG_LIBS)

# --- flags -------------------------------------------------------------------
MT_WARN    := -std=c99 -Wall -Wextra -Wpedantic -Wshadow -Wstrict-prototypes \
              -Wmissing-prototypes -Wno-unused-parameter
MT_CFLAGS  := $(MT_WARN) -fPIC -fvisibility=hidden -MMD -MP
# sqrt and the like compiled as the instruction alone, without the branch
# and call that would set errno for a negative argument: the same results
# bit for bit (materia never reads errno after a math function), about 1.7%
# fewer instructions in a render.
MT_CFLAGS  += -fno-math-errno
# The library promises no floating-point exception but inexact and underflow
# for valid input (checked with fetestexcept). gcc keeps the program's
# exceptions by default; clang may evaluate both sides of a branch or pad
# vectors with garbage lanes unless told that the exceptions matter.
MT_CFLAGS  += $(shell $(CC) -ffp-exception-behavior=maytrap -Werror -E -x c /dev/null >/dev/null 2>&1 && echo -ffp-exception-behavior=maytrap)
MT_CPPFLAGS := -Iinclude -I$(BUILD)/include -Isrc -Itests -D_POSIX_C_SOURCE=200809L $(DEP_CFLAGS)
MT_LDLIBS  := $(DEP_LIBS) -lpthread -lm
ifneq ($(SANITIZE),)
  MT_CFLAGS  += -fsanitize=$(SANITIZE) -fno-omit-frame-pointer -fno-sanitize-recover=all
  MT_LDFLAGS += -fsanitize=$(SANITIZE)
endif

# Link-time optimization of the programs (materia-render and the other
# tools, the benchmarks, the shared library): the library's objects carry
# both machine code and the compiler's intermediate form (-ffat-lto-objects),
# so the programs are optimized across files (about 6% off a render) from an
# archive of those objects (LTO_LIB), while the tests link the same machine
# code without it (-fno-lto: one LTO link per test would cost minutes).
# libmateria.a, the archive a user's program links, has the intermediate
# form removed: a linker plugin would otherwise run the compiler's LTO pass
# on every link of it, -flto or not, and fail where the user's compiler is
# another version. Off under the sanitizers and where the compiler cannot do
# it (clang before 17 has no fat objects); LTO=no turns it off, LTO=yes
# forces it.
LTO ?= auto
ifeq ($(LTO),auto)
  ifeq ($(SANITIZE),)
    ifneq ($(NEED_DEPS),)
      LTO_OK := $(shell printf 'int main(void){return 0;}\n' | $(CC) -flto=auto -ffat-lto-objects -Werror -x c - -o /dev/null >/dev/null 2>&1 && echo yes)
    endif
  endif
else ifeq ($(LTO),yes)
  LTO_OK := yes
endif
OBJCOPY ?= objcopy
ifeq ($(LTO_OK),yes)
  MT_CFLAGS += -flto=auto -ffat-lto-objects
  # gcc's link-time pass warns of reads it cannot follow through flags (the
  # BVH's lazily set-up triangle test) and ignores the pragma that answers it
  # at compile time, where every file is still checked; a compiler that does
  # not know the warning (clang) is not given the option
  ifneq ($(NEED_DEPS),)
    LTO_NOWARN := $(shell printf 'int main(void){return 0;}\n' | $(CC) -Wno-maybe-uninitialized -Werror -x c - -o /dev/null >/dev/null 2>&1 && echo -Wno-maybe-uninitialized)
  endif
  MT_LDFLAGS += $(LTO_NOWARN)
endif

ALL_CFLAGS   = $(MT_CFLAGS) $(CFLAGS)
NO_LTO       = $(if $(filter yes,$(LTO_OK)),-fno-lto)
ALL_CPPFLAGS = $(MT_CPPFLAGS) $(CPPFLAGS)
ALL_LDFLAGS  = $(MT_LDFLAGS) $(LDFLAGS)

# --- sources -----------------------------------------------------------------
LIB_SRC   := $(sort $(wildcard src/*.c src/*/*.c))
CONF_SRC  := $(sort $(wildcard conformance/*.c))
TOOL_SRC  := $(sort $(wildcard tools/*.c))
TEST_SRC  := $(sort $(wildcard tests/test_*.c))
TSUP_SRC  := $(sort $(wildcard tests/support/*.c))
BENCH_SRC := $(sort $(wildcard bench/*.c))
TRADE_SRC := $(sort $(wildcard tradeoff/*.c))

FUZZ_TARGETS := scene query brdf merl $(if $(NO_EXR),,exr) $(if $(NO_PNG),,png) pfm spd

LIB_OBJ   := $(LIB_SRC:%.c=$(BUILD)/obj/%.o)
CONF_OBJ  := $(CONF_SRC:%.c=$(BUILD)/obj/%.o)
TSUP_OBJ  := $(TSUP_SRC:%.c=$(BUILD)/obj/%.o)
TOOLS     := $(TOOL_SRC:tools/%.c=$(BUILD)/bin/%)
TESTS     := $(TEST_SRC:tests/%.c=$(BUILD)/tests/%)
BENCHES   := $(BENCH_SRC:bench/%.c=$(BUILD)/bench/%)
TRADEOFFS := $(TRADE_SRC:tradeoff/%.c=$(BUILD)/tradeoff/%)
# the suite's objects but its main, for the trade-off programs (an archive:
# a program takes only what it uses)
CONF_LIB  := $(BUILD)/obj/libconformance.a
CONF_BIN  := $(BUILD)/bin/materia-conformance
# a deliberately wrong protocol implementation, for tests/test_impl.c
IMPL_WRONG := $(BUILD)/tests/impl-wrong
# a material system other than pbrt-v2's behind the protocol, for tests/test_impl.c
IMPL_OTHER := $(BUILD)/tests/impl-other
# the fuzz targets with driver.c (make check runs each over its corpus)
FUZZ_BINS := $(FUZZ_TARGETS:%=$(BUILD)/fuzz/fuzz-%)
FUZZ_SUP  := $(BUILD)/obj/fuzz/fuzz_util.o

# A double-precision build is another library (its mt_real differs): it is
# named materia-double (libmateria-double.so.0, materia-double.pc, headers
# in include/materia-double, tools materia-*-double) so that both install
# side by side.
LIBNAME    := materia$(if $(filter double,$(PRECISION)),-double)

# Embree 3, for bench/embree's side-by-side harness only (make bench): found
# with pkg-config or, as Debian's libembree-dev ships no .pc file, by its
# header and -lembree3; absent, the harness is simply not built.
ifneq ($(filter bench benches bench-pbrt,$(MAKECMDGOALS)),)
  EMBREE_CFLAGS := $(shell $(PKG_CONFIG) --cflags embree3 2>/dev/null)
  EMBREE_LIBS   := $(or $(shell $(PKG_CONFIG) --libs embree3 2>/dev/null),-lembree3)
  EMBREE_OK     := $(shell printf '\043include <embree3/rtcore.h>\nint main(void){rtcReleaseDevice(rtcNewDevice(0));return 0;}\n' | \
                     $(CC) $(EMBREE_CFLAGS) -x c - -o /dev/null $(EMBREE_LIBS) >/dev/null 2>&1 && echo yes)
endif
ifeq ($(EMBREE_OK),yes)
  BENCHES += $(BUILD)/bench/bvh-embree
endif

STATIC_LIB := $(BUILD)/libmateria.a
LTO_LIB    := $(if $(filter yes,$(LTO_OK)),$(BUILD)/obj/libmateria-lto.a,$(STATIC_LIB))
SHARED_LIB := $(BUILD)/lib$(LIBNAME).so.$(VERSION)
SONAME     := lib$(LIBNAME).so.$(SOVERSION)
CONFIG_H   := $(BUILD)/include/materia/config.h
FLAGS_STAMP := $(BUILD)/flags

.PHONY: FORCE all lib tools tests benches tradeoffs tradeoff check check-tsan check-full vectors other-conformance bench bench-pbrt demo golden fuzz install uninstall reference amalgamation clean distclean help
.DEFAULT_GOAL := all

all: lib tools $(CONF_BIN)
lib: $(STATIC_LIB) $(SHARED_LIB)
tools: $(TOOLS)
tests: $(TESTS) $(CONF_BIN) $(IMPL_WRONG) $(IMPL_OTHER) $(FUZZ_BINS)
benches: $(BENCHES)
tradeoffs: $(TRADEOFFS)

$(CONFIG_H): Makefile $(FLAGS_STAMP)
	@mkdir -p $(dir $@)
	@{ echo '/* generated by the Makefile: the precision this build of materia uses */'; \
	   echo '#ifndef MATERIA_CONFIG_H'; echo '#define MATERIA_CONFIG_H'; \
	   echo '#define MT_USE_DOUBLE $(if $(filter double,$(PRECISION)),1,0)'; \
	   echo '#define MT_VERSION "$(VERSION)"'; echo '#endif'; } > $@.tmp && mv $@.tmp $@

# The precision, compiler and flags as this build directory last saw them: a
# change (CFLAGS=..., LTO=no, another CC, PRECISION with the same BUILD)
# rebuilds every object rather than mixing objects of two configurations.
$(FLAGS_STAMP): FORCE
	@mkdir -p $(dir $@)
	@printf '%s\n' '$(subst ','\'',$(PRECISION): $(CC) $(ALL_CPPFLAGS) $(ALL_CFLAGS))' > $@.new; \
	 if cmp -s $@.new $@; then rm -f $@.new; else mv $@.new $@; fi
FORCE:

$(BUILD)/obj/%.o: %.c $(CONFIG_H) $(FLAGS_STAMP)
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CPPFLAGS) $(ALL_CFLAGS) -c $< -o $@

# machine code only (see LTO above); objcopy keeps the archive's index
$(STATIC_LIB): $(LIB_OBJ)
	@rm -f $@ $@.tmp
	$(AR) rcs $@.tmp $^
	$(if $(filter yes,$(LTO_OK)),$(OBJCOPY) -R '.gnu.lto_*' -R '.gnu.debuglto_*' -R .llvm.lto $@.tmp)
	mv $@.tmp $@

ifeq ($(LTO_OK),yes)
$(LTO_LIB): $(LIB_OBJ)
	@rm -f $@
	$(AR) rcs $@ $^
endif

$(SHARED_LIB): $(LIB_OBJ)
	$(CC) -shared -Wl,-soname,$(SONAME) $(ALL_CFLAGS) $(ALL_LDFLAGS) -o $@ $^ $(MT_LDLIBS) $(LDLIBS)
	ln -sf $(notdir $@) $(BUILD)/$(SONAME)
	ln -sf $(notdir $@) $(BUILD)/lib$(LIBNAME).so

$(BUILD)/bin/materia-conformance: $(CONF_OBJ) $(TSUP_OBJ) $(STATIC_LIB)
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) $(NO_LTO) $(ALL_LDFLAGS) -o $@ $(CONF_OBJ) $(TSUP_OBJ) $(STATIC_LIB) $(MT_LDLIBS) $(LDLIBS)

$(BUILD)/bin/%: $(BUILD)/obj/tools/%.o $(LTO_LIB)
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) $(ALL_LDFLAGS) -o $@ $< $(LTO_LIB) $(MT_LDLIBS) $(LDLIBS)

$(IMPL_OTHER): $(BUILD)/obj/tests/impl_other.o
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) $(NO_LTO) $(ALL_LDFLAGS) -o $@ $< -lm

# The in-process implementation interface (include/materia/impl.h):
# materia's own BSDFs as a plugin, the C example, a plugin with planted
# errors (tests/plugin_planted.c), and a program that links a plugin and
# runs the suite on it (mt_impl_run_suite). A plugin is the static
# library's position-independent objects in one shared object that exports
# its entry point alone (-Bsymbolic: its own materia, whatever loads it).
PLUGINS := $(BUILD)/plugins/materia_plugin.so $(BUILD)/plugins/lambert_plugin.so $(BUILD)/tests/plugin_planted.so \
           $(BUILD)/tests/plugin-linked
PLUGIN_LINK = $(CC) -shared -Wl,-Bsymbolic $(ALL_CFLAGS) $(NO_LTO) $(ALL_LDFLAGS) -o $@ $(filter %.o,$^) \
              $(if $(filter %.a,$^),$(STATIC_LIB) $(MT_LDLIBS)) $(LDLIBS) -lm
$(BUILD)/plugins/materia_plugin.so: $(BUILD)/obj/plugins/materia_plugin.o $(BUILD)/obj/plugins/materia_entry.o $(STATIC_LIB)
	@mkdir -p $(dir $@)
	$(PLUGIN_LINK)
$(BUILD)/plugins/lambert_plugin.so: $(BUILD)/obj/examples/plugin/lambert_plugin.o
	@mkdir -p $(dir $@)
	$(PLUGIN_LINK)
$(BUILD)/tests/plugin_planted.so: $(BUILD)/obj/tests/plugin_planted.o $(BUILD)/obj/plugins/materia_plugin.o $(STATIC_LIB)
	@mkdir -p $(dir $@)
	$(PLUGIN_LINK)
$(BUILD)/tests/plugin-linked: $(BUILD)/obj/tests/plugin_linked.o $(BUILD)/obj/plugins/materia_plugin.o $(TSUP_OBJ) \
                              $(CONF_LIB) $(STATIC_LIB)
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) $(NO_LTO) $(ALL_LDFLAGS) -o $@ $(filter %.o,$^) $(CONF_LIB) $(STATIC_LIB) $(MT_LDLIBS) $(LDLIBS)
tests: $(PLUGINS)
$(BUILD)/bench/plugin: $(BUILD)/plugins/materia_plugin.so

$(IMPL_WRONG): $(BUILD)/obj/tests/impl_wrong.o $(STATIC_LIB)
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) $(NO_LTO) $(ALL_LDFLAGS) -o $@ $< $(STATIC_LIB) $(MT_LDLIBS) $(LDLIBS)

$(BUILD)/tests/%: $(BUILD)/obj/tests/%.o $(TSUP_OBJ) $(STATIC_LIB)
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) $(NO_LTO) $(ALL_LDFLAGS) -o $@ $< $(TSUP_OBJ) $(STATIC_LIB) $(MT_LDLIBS) $(LDLIBS)

$(BUILD)/tests/test_strbuf: $(BUILD)/obj/tests/test_strbuf.o $(BUILD)/obj/conformance/strbuf.o $(TSUP_OBJ) $(STATIC_LIB)
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) $(NO_LTO) $(ALL_LDFLAGS) -o $@ $(filter %.o,$^) $(STATIC_LIB) $(MT_LDLIBS) $(LDLIBS)

# the vectors' test reads the --impl catalog of configurations
$(BUILD)/tests/test_vectors: $(BUILD)/obj/tests/test_vectors.o $(BUILD)/obj/conformance/impl_catalog.o $(BUILD)/obj/conformance/strbuf.o $(TSUP_OBJ) $(STATIC_LIB)
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) $(NO_LTO) $(ALL_LDFLAGS) -o $@ $(filter %.o,$^) $(STATIC_LIB) $(MT_LDLIBS) $(LDLIBS)

$(BUILD)/fuzz/fuzz-%: $(BUILD)/obj/fuzz/target_%.o $(BUILD)/obj/fuzz/driver.o $(FUZZ_SUP) $(STATIC_LIB)
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) $(NO_LTO) $(ALL_LDFLAGS) -o $@ $(filter %.o,$^) $(STATIC_LIB) $(MT_LDLIBS) $(LDLIBS)

# the same targets with libFuzzer's main (make fuzz builds them with clang)
$(BUILD)/libfuzzer/fuzz-%: $(BUILD)/obj/fuzz/target_%.o $(FUZZ_SUP) $(STATIC_LIB)
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) $(NO_LTO) $(ALL_LDFLAGS) -fsanitize=fuzzer -o $@ $(filter %.o,$^) $(STATIC_LIB) $(MT_LDLIBS) $(LDLIBS)

$(BUILD)/obj/bench/embree/%.o: ALL_CPPFLAGS += $(EMBREE_CFLAGS)
$(BUILD)/bench/bvh-embree: $(BUILD)/obj/bench/embree/bvh_embree.o $(TSUP_OBJ) $(LTO_LIB)
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) $(ALL_LDFLAGS) -o $@ $< $(TSUP_OBJ) $(LTO_LIB) $(EMBREE_LIBS) $(MT_LDLIBS) $(LDLIBS)

$(BUILD)/bench/%: $(BUILD)/obj/bench/%.o $(TSUP_OBJ) $(LTO_LIB)
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) $(ALL_LDFLAGS) -o $@ $< $(TSUP_OBJ) $(LTO_LIB) $(MT_LDLIBS) $(LDLIBS)

$(CONF_LIB): $(filter-out %/conformance/main.o,$(CONF_OBJ))
	@rm -f $@
	$(AR) rcs $@ $^

# the trade-off programs (make tradeoff), linked as the benchmarks are
$(BUILD)/tradeoff/%: $(BUILD)/obj/tradeoff/%.o $(CONF_LIB) $(TSUP_OBJ) $(LTO_LIB)
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) $(ALL_LDFLAGS) -o $@ $< $(CONF_LIB) $(TSUP_OBJ) $(LTO_LIB) $(MT_LDLIBS) $(LDLIBS)

# A C++ program against the public headers and libmateria.a (make check):
# the headers' extern "C" guards and C++-clean inline functions. Built with
# CXX (clang++ when CC is clang), skipped with a message when it is absent.
ifeq ($(origin CXX),default)
  ifneq ($(findstring clang,$(CC)),)
    CXX := clang++
  endif
endif
ifneq ($(NEED_DEPS),)
  CXX_OK := $(shell command -v $(CXX) >/dev/null 2>&1 && echo yes)
endif
CXX_TEST := $(if $(CXX_OK),$(BUILD)/tests/test_cxx)
CXX_SKIP := $(if $(CXX_OK),,no C++ compiler ($(CXX)) found: the C++ program was not built)
MT_CXXFLAGS := -std=c++11 -Wall -Wextra -pedantic $(filter -Werror,$(CFLAGS)) -MMD -MP \
               $(if $(SANITIZE),-fsanitize=$(SANITIZE) -fno-omit-frame-pointer)
$(BUILD)/tests/test_cxx: tests/cxx/test_cxx.cpp $(STATIC_LIB) $(CONFIG_H)
	@mkdir -p $(dir $@)
	$(CXX) $(MT_CXXFLAGS) $(CXXFLAGS) -Iinclude -I$(BUILD)/include $(CPPFLAGS) $(NO_LTO) \
	    $(ALL_LDFLAGS) -o $@ $< $(STATIC_LIB) $(MT_LDLIBS) $(LDLIBS)

# docs/REFERENCE.md, generated from the parameter tables the creators read;
# make check fails when the committed file is not what they give.
REF_GEN := $(BUILD)/tests/gen-reference
$(REF_GEN): tools/reference/gen-reference.c $(STATIC_LIB) $(CONFIG_H)
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CPPFLAGS) $(ALL_CFLAGS) $(NO_LTO) $(ALL_LDFLAGS) -o $@ $< $(STATIC_LIB) $(MT_LDLIBS) $(LDLIBS)

# (after their definitions: a prerequisite is expanded where it is written)
tests: $(CXX_TEST) $(REF_GEN)

reference: $(REF_GEN)
	$(REF_GEN) > docs/REFERENCE.md.tmp && mv docs/REFERENCE.md.tmp docs/REFERENCE.md

# Every test binary, then the conformance suite; one summary line at the end.
# The suite compares this build with the other precision's (float versus
# double ULPs); under the sanitizers it runs with fewer samples (--lite): the
# point there is memory and undefined behaviour, the statistics run unsanitized.
OTHER_PRECISION := $(if $(filter double,$(PRECISION)),float,double)
# the other precision with the same compiler: build/<other>, or BUILD-<other>
# when BUILD was given (e.g. BUILD=build/clang CC=clang)
OTHER_BUILD     := $(if $(filter build/$(PRECISION),$(BUILD)),build/$(OTHER_PRECISION),$(BUILD)-$(OTHER_PRECISION))
OTHER_CONF      := $(OTHER_BUILD)/bin/materia-conformance
OTHER_QUERY     := $(OTHER_BUILD)/bin/materia-query
# A build without an image format (NO_EXR, NO_PNG) runs the suite --lite
# too, without the other precision: what it checks is that everything but
# the left-out formats works, and the full builds run the statistics.
CONF_ARGS       := $(if $(SANITIZE)$(OMIT),--lite,--ulps $(OTHER_CONF))

check: all tests $(if $(SANITIZE)$(OMIT),,benches tradeoffs other-conformance)
	@CONF_ARGS="$(CONF_ARGS)" CXX_SKIP="$(CXX_SKIP)" MAKE="$(MAKE)" CC="$(CC)" SANITIZE="$(SANITIZE)" REF_GEN="$(REF_GEN)" \
	    CXX="$(if $(CXX_OK),$(CXX))" EXAMPLE_LIBS="$(MT_LDLIBS) $(LDLIBS)" \
	    MATERIA_OTHER_QUERY="$(if $(SANITIZE)$(OMIT),,$(OTHER_QUERY))" \
	    sh tools/run-checks.sh $(BUILD) $(PRECISION) $(TESTS) $(CXX_TEST) $(FUZZ_BINS)

other-conformance:
	@$(MAKE) --no-print-directory PRECISION=$(OTHER_PRECISION) SANITIZE= BUILD=$(OTHER_BUILD) $(OTHER_CONF) $(OTHER_QUERY)

# The published conformance vectors (vectors/README.md), written by the
# float and the double build (vectors/float, vectors/double); make check
# compares those of its precision with what the build computes.
vectors:
	@$(MAKE) --no-print-directory PRECISION=float SANITIZE= BUILD=build/float build/float/tests/test_vectors
	@$(MAKE) --no-print-directory PRECISION=double SANITIZE= BUILD=build/double build/double/tests/test_vectors
	build/float/tests/test_vectors --write vectors
	build/double/tests/test_vectors --write vectors

# ThreadSanitizer: the library and tests/test_threads.c (8 threads sharing
# materials, textures, images, measured data and a scene) built with clang's
# -fsanitize=thread in build/tsan and run; a data race fails it.
TSAN_CC ?= clang
check-tsan:
	@$(MAKE) --no-print-directory BUILD=build/tsan CC=$(TSAN_CC) SANITIZE=thread LTO=no build/tsan/tests/test_threads
	TSAN_OPTIONS="halt_on_error=1 $(TSAN_OPTIONS)" build/tsan/tests/test_threads

# The conformance suite with far more samples and finer cells (slow).
check-full: all tests
	$(CONF_BIN) --full

# Every benchmark program in bench/, float and double builds alternating in
# one run, with the double/float ratio of each figure; then the default
# build's materia-render and pbrt-v2 timed side by side on the reference
# scenes (tools/bench-pbrt.sh; skipped, saying so, without the baseline).
# BENCH_SPP (default: each scene's own), BENCH_REPEAT (3), BENCH_THREADS (2)
# and BENCH_GROUPS (material subsurface real) shorten or select it.
BENCH_GROUPS ?=
bench:
	$(MAKE) PRECISION=float SANITIZE= all benches
	$(MAKE) PRECISION=double SANITIZE= all benches
	sh tools/run-bench.sh build/float/bench build/double/bench
	BENCH_SPP=$(BENCH_SPP) BENCH_REPEAT=$(BENCH_REPEAT) BENCH_THREADS=$(BENCH_THREADS) \
	    sh tools/bench-pbrt.sh build/float $(BENCH_GROUPS)

bench-pbrt:
	$(MAKE) PRECISION=float SANITIZE= BUILD=build/float all
	BENCH_SPP=$(BENCH_SPP) BENCH_REPEAT=$(BENCH_REPEAT) BENCH_THREADS=$(BENCH_THREADS) \
	    sh tools/bench-pbrt.sh build/float $(BENCH_GROUPS)

# The speed/accuracy trade (docs/TRADEOFF.md): the float and the double
# build with their trade-off programs (tradeoff/*.c), then every measurement
# script tradeoff/N-name.sh (tools/run-tradeoff.sh): CSV, PNG plots (with
# gnuplot, optional) and build/tradeoff/report.md. QUICK=1: reduced sizes
# (minutes); TRADEOFF_ONLY=1,5: only those measurements.
QUICK ?= 0
TRADEOFF_ONLY ?=
TRADEOFF_OUT ?= build/tradeoff
tradeoff:
	$(MAKE) --no-print-directory PRECISION=float SANITIZE= BUILD=build/float all tradeoffs
	$(MAKE) --no-print-directory PRECISION=double SANITIZE= BUILD=build/double all tradeoffs
	QUICK=$(QUICK) TRADEOFF_ONLY=$(TRADEOFF_ONLY) sh tools/run-tradeoff.sh build/float build/double $(TRADEOFF_OUT)

# libFuzzer on each target for FUZZ_SECONDS seconds (docs/FUZZING.md): the
# library and targets built with clang, ASan, UBSan and libFuzzer's coverage
# in build/fuzz; new inputs go to build/fuzz/work/TARGET, crashes to
# build/fuzz/artifacts. Fails when any target found one.
FUZZ_SECONDS ?= 60
FUZZ_CC      ?= clang
FUZZ_BUILD   ?= build/fuzz
# fewer comparisons traced, a cheaper rho and a lower loopsubdiv limit:
# docs/FUZZING.md, "What the fuzzing build changes"
FUZZ_CFLAGS  ?= -fsanitize-coverage-ignorelist=fuzz/coverage-ignore.txt -DMT_QUERY_RHO_TOL=1e-3 \
               -DMT_RHO_NPHI=4 -DMT_RHO_NZ=2 -DMT_RHO_WORK=1 -DMT_RHO_MAX_GRID=1 -DMT_LOOPSUBDIV_MAX_TRIANGLES=16384
fuzz:
	$(MAKE) --no-print-directory BUILD=$(FUZZ_BUILD) CC=$(FUZZ_CC) SANITIZE=address,undefined \
	    LTO=no CFLAGS="-O1 -g -fsanitize=fuzzer-no-link $(FUZZ_CFLAGS)" $(FUZZ_TARGETS:%=$(FUZZ_BUILD)/libfuzzer/fuzz-%)
	sh tools/run-fuzz.sh $(FUZZ_BUILD) $(FUZZ_SECONDS) $(FUZZ_TARGETS)

# The library as one C file and one header, as SQLite ships
# (tools/amalgamate.sh, docs/LINKING.md): AMALGAMATION/materia.c builds with
# `cc -std=c99 -c materia.c` alone. make check builds and runs programs from
# it (tools/check-amalgamation.sh).
AMALGAMATION ?= build/amalgamation
amalgamation:
	sh tools/amalgamate.sh $(AMALGAMATION) $(VERSION)

# A contact sheet of every material (golden/scenes) in demo.png.
demo: all
	sh tools/make-demo.sh $(BUILD)

# Renders the golden images again (golden/*.exr, golden/*.var.exr): after a
# change that is meant to change images. Review the difference first.
# GOLDEN_ONLY="NAME ..." renders those scenes alone.
golden: all
	GOLDEN_ONLY="$(GOLDEN_ONLY)" sh tools/make-golden.sh $(BUILD)

# Installed files: headers (include/, or include/materia-double for the
# double build), lib<LIBNAME>.a and .so, <LIBNAME>.pc and <LIBNAME>-shared.pc
# (materia.pc.in says why two), the tools (with a
# -double suffix for the double build) and the documentation with the
# licence, the vectors and the examples in share/doc/<LIBNAME>. make
# uninstall removes exactly these.
INC_DIR   := $(PREFIX)/include$(if $(filter double,$(PRECISION)),/materia-double)
LIB_DIR   := $(PREFIX)/lib
BIN_DIR   := $(PREFIX)/bin
DOC_DIR   := $(PREFIX)/share/doc/$(LIBNAME)
TOOL_SUFFIX := $(if $(filter double,$(PRECISION)),-double)
INSTALLED_TOOLS := $(notdir $(TOOLS) $(CONF_BIN))
# the documentation keeps the source tree's layout, so that its relative
# links hold: docs/, the conformance vectors with vectors/check.py, the
# examples (tools/check-install.sh checks every link of the installed docs)
DOC_FILES := README.md LICENSE conformance/ERRATA.md $(sort $(wildcard docs/*.md docs/tradeoff/*.png)) \
             $(sort $(shell find vectors examples -type f ! -name '*.pyc' ! -path '*/__pycache__/*' 2>/dev/null))
PUBLIC_HEADERS := $(sort $(notdir $(wildcard include/materia/*.h)) config.h)
TOOL_HEADERS   := $(sort $(notdir $(wildcard include/materia/tools/*.h)))

install: all
	install -d $(DESTDIR)$(INC_DIR)/materia/tools $(DESTDIR)$(LIB_DIR)/pkgconfig $(DESTDIR)$(BIN_DIR) $(DESTDIR)$(DOC_DIR)
	install -m 644 include/materia.h include/materia_tools.h $(DESTDIR)$(INC_DIR)/
	install -m 644 include/materia/*.h $(CONFIG_H) $(DESTDIR)$(INC_DIR)/materia/
	install -m 644 include/materia/tools/*.h $(DESTDIR)$(INC_DIR)/materia/tools/
	install -m 644 $(STATIC_LIB) $(DESTDIR)$(LIB_DIR)/lib$(LIBNAME).a
	install -m 755 $(SHARED_LIB) $(DESTDIR)$(LIB_DIR)/
	ln -sf $(notdir $(SHARED_LIB)) $(DESTDIR)$(LIB_DIR)/$(SONAME)
	ln -sf $(notdir $(SHARED_LIB)) $(DESTDIR)$(LIB_DIR)/lib$(LIBNAME).so
	for t in $(INSTALLED_TOOLS); do install -m 755 $(BUILD)/bin/$$t $(DESTDIR)$(BIN_DIR)/$$t$(TOOL_SUFFIX) || exit 1; done
	for f in $(DOC_FILES); do \
	    install -d $(DESTDIR)$(DOC_DIR)/$$(dirname $$f) && \
	    install -m $$([ -x $$f ] && echo 755 || echo 644) $$f $(DESTDIR)$(DOC_DIR)/$$f || exit 1; \
	done
	for pc in materia materia-shared; do \
	    sed -e 's|@PREFIX@|$(PREFIX)|g' -e 's|@VERSION@|$(VERSION)|g' -e 's|@LIBNAME@|$(LIBNAME)|g' \
	        -e 's|@INCLUDEDIR@|$(INC_DIR:$(PREFIX)/%=%)|g' -e 's|@PRECISION@|$(PRECISION)|g' \
	        -e 's|@PRIVATE_LIBS@|$(DEP_LIBS) -lpthread -lm|g' $$pc.pc.in \
	        > $(DESTDIR)$(LIB_DIR)/pkgconfig/$$(echo $$pc | sed 's|^materia|$(LIBNAME)|').pc || exit 1; \
	done

uninstall:
	rm -f $(DESTDIR)$(INC_DIR)/materia.h $(DESTDIR)$(INC_DIR)/materia_tools.h \
	      $(addprefix $(DESTDIR)$(INC_DIR)/materia/,$(PUBLIC_HEADERS)) \
	      $(addprefix $(DESTDIR)$(INC_DIR)/materia/tools/,$(TOOL_HEADERS))
	rm -f $(DESTDIR)$(LIB_DIR)/lib$(LIBNAME).a $(DESTDIR)$(LIB_DIR)/$(notdir $(SHARED_LIB)) \
	      $(DESTDIR)$(LIB_DIR)/$(SONAME) $(DESTDIR)$(LIB_DIR)/lib$(LIBNAME).so \
	      $(DESTDIR)$(LIB_DIR)/pkgconfig/$(LIBNAME).pc $(DESTDIR)$(LIB_DIR)/pkgconfig/$(LIBNAME)-shared.pc
	rm -f $(addprefix $(DESTDIR)$(BIN_DIR)/,$(addsuffix $(TOOL_SUFFIX),$(INSTALLED_TOOLS)))
	rm -f $(addprefix $(DESTDIR)$(DOC_DIR)/,$(DOC_FILES))
	-find $(DESTDIR)$(DOC_DIR) -depth -type d -empty -exec rmdir {} \; 2>/dev/null
	-rmdir $(DESTDIR)$(INC_DIR)/materia/tools $(DESTDIR)$(INC_DIR)/materia 2>/dev/null
	$(if $(filter double,$(PRECISION)),-rmdir $(DESTDIR)$(INC_DIR) 2>/dev/null)

clean:
	rm -rf $(BUILD)

distclean:
	rm -rf build

help:
	@sed -n '2,25p' Makefile

-include $(LIB_OBJ:.o=.d) $(CONF_OBJ:.o=.d) $(TSUP_OBJ:.o=.d) \
         $(TOOL_SRC:tools/%.c=$(BUILD)/obj/tools/%.d) $(TEST_SRC:tests/%.c=$(BUILD)/obj/tests/%.d) \
         $(BENCH_SRC:bench/%.c=$(BUILD)/obj/bench/%.d) $(BUILD)/obj/bench/embree/bvh_embree.d \
         $(TRADE_SRC:tradeoff/%.c=$(BUILD)/obj/tradeoff/%.d) \
         $(wildcard $(BUILD)/obj/fuzz/*.d)

# Keep test, tool and benchmark objects (they are intermediate files to make).
.SECONDARY:
