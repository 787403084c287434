# dflab — plain Makefile.  `make` builds build/dflab and build/libdfl.a.
# Sources are found by wildcard: drop a .c into src/ (library), experiments/
# (studies) or tests/ (Criterion tests) and it is built.
#
# Include paths enforce the dependency direction: library objects (src/
# except src/cli) see only src/, so a study header included from the
# library fails to compile; experiments, the CLI and tests also see
# experiments/ (and tests see tests/).  `make check-layout` (run by
# `make test`) rejects any src/ file that names experiments/ or tests/.

CC      ?= cc
CXX     ?= c++
PYTHON  ?= /usr/bin/python3
# parallel compile jobs of the targets that build first (reproduce, test,
# check-threads): the machine's cores unless given (make reproduce JOBS=2)
JOBS    ?= $(shell nproc 2>/dev/null || echo 2)
BUILD   ?= build
OPT     ?= -O2
SAN     ?=

EXR_CFLAGS := $(shell pkg-config --cflags OpenEXR 2>/dev/null)
DEPFLAGS = -MMD -MP
CPPFLAGS += -Isrc $(EXR_CFLAGS) -D_POSIX_C_SOURCE=200809L -DIMATH_HALF_NO_LOOKUP_TABLE
# -ffp-contract=off: no FMA contraction anywhere (ISO C mode implies it; stated
# so that the per-ISA kernels, core/isa.h, give the same bytes on every ISA).
CFLAGS   += -std=c11 -Wall -Wextra $(OPT) -ffp-contract=off -fopenmp $(SAN) -g
CXXFLAGS += -std=c++17 -Wall -Wextra $(OPT) -fopenmp $(SAN) -g -I/usr/include/eigen3
# OpenVDB 10 (field/vdb_grid.cc) and the TBB it is built on: its headers
# instantiate TBB templates, so the program links libtbb itself.
# Meshes: Assimp (pkg-config) reads mesh files (src/io/meshfile.c); Embree 3
# (no .pc file in Debian 12) answers closest-point queries (src/geom/mesh_bvh.c).
MESH_LIBS := $(shell pkg-config --libs assimp 2>/dev/null || echo -lassimp) -lembree3
LDLIBS   += -linih -lceres -lglog -lopenvdb -ltbb -lOpenEXRCore-3_1 $(MESH_LIBS) -lz -lm
LDFLAGS  += -fopenmp $(SAN)

# The git revision goes into one generated header, rewritten only when it
# changes, so that -MMD recompiles just the files that print it.
GIT_REV := $(shell git rev-parse --short HEAD 2>/dev/null || echo unknown)$(shell git diff --quiet HEAD 2>/dev/null || echo +dirty)
VERSION_H := $(BUILD)/gen/dfl_version.h
INIH_VERSION := $(shell pkg-config --modversion inih 2>/dev/null || echo unknown)
$(shell mkdir -p $(BUILD)/gen && printf '#define DFL_GIT_REV "%s"\n#define DFL_INIH_VERSION "%s"\n' '$(GIT_REV)' '$(INIH_VERSION)' > $(VERSION_H).new && \
  (cmp -s $(VERSION_H).new $(VERSION_H) || mv $(VERSION_H).new $(VERSION_H)); rm -f $(VERSION_H).new)
CPPFLAGS += -I$(BUILD)/gen

LIB_C   := $(shell find src -name '*.c' ! -path 'src/cli/*' ! -path 'src/web/*' | sort)
LIB_CC  := $(shell find src -name '*.cc' | sort)
EXP_C   := $(shell find experiments -name '*.c' | sort)
CLI_C   := $(shell find src/cli -name '*.c' | sort)
TEST_C  := $(shell find tests -name '*.c' ! -path 'tests/bench/*' ! -path 'tests/fuzz/*' | sort)
BENCH_C := $(shell find tests/bench -name '*.c' 2>/dev/null | sort)

LIB_OBJ   := $(LIB_C:%.c=$(BUILD)/%.o) $(LIB_CC:%.cc=$(BUILD)/%.o)
EXP_OBJ   := $(EXP_C:%.c=$(BUILD)/%.o)
CLI_OBJ   := $(CLI_C:%.c=$(BUILD)/%.o)
TEST_OBJ  := $(TEST_C:%.c=$(BUILD)/%.o)
BENCH_OBJ := $(BENCH_C:%.c=$(BUILD)/%.o)

# Study-level code may include experiments/ headers; the library may not.
$(EXP_OBJ) $(CLI_OBJ): CPPFLAGS += -Iexperiments
$(TEST_OBJ) $(BENCH_OBJ): CPPFLAGS += -Iexperiments -Itests
# Batched rfunc kernels: gcc vectorizes sqrt() only without errno semantics and
# the triangle/region selects only without trapping math; both leave IEEE results
# unchanged (src/rfunc/batch_seg.c strip_term, batch_tri.c).
$(BUILD)/src/rfunc/batch_seg.o: CFLAGS += -fno-math-errno
$(BUILD)/src/rfunc/batch_tri.o $(BUILD)/src/rfunc/batch_region.o: CFLAGS += -fno-math-errno -fno-trapping-math
# The nearest filter's lane loop (src/proxy/filter.c nearest_block): sqrt and
# the clip's selects vectorize under the same two flags.
$(BUILD)/src/proxy/filter.o: CFLAGS += -fno-math-errno -fno-trapping-math
# The implicit cap test's lane loop (src/proxy/input_implicit_fast.c cap_run): the same.
$(BUILD)/src/proxy/input_implicit_fast.o: CFLAGS += -fno-math-errno -fno-trapping-math


LIB     := $(BUILD)/libdfl.a
EXPLIB  := $(BUILD)/libdflexp.a
DFLAB   := $(BUILD)/dflab
TESTS   := $(BUILD)/dflab-tests
BENCH_BIN := $(BUILD)/dflab-bench

APT_PKGS := libinih-dev libceres-dev libopenexr-dev libimath-dev libcriterion-dev zlib1g-dev \
            python3-matplotlib python3-numpy python3-vtk9 openexr pkg-config \
            emscripten chromium python3-scipy parallel slurm-wlm munge clang-14 libomp-14-dev \
            libopenvdb-dev libtbb-dev libassimp-dev libembree-dev assimp-testmodels

.PHONY: all deps test sanitize bench reproduce figures clean check-layout web web-test web-bench check-threads check-isa mutate
all: $(DFLAB) $(LIB)

$(BUILD)/%.o: %.c
	@mkdir -p $(dir $@)
	$(CC) $(CPPFLAGS) $(CFLAGS) $(DEPFLAGS) -c $< -o $@

$(BUILD)/%.o: %.cc
	@mkdir -p $(dir $@)
	$(CXX) $(CPPFLAGS) $(CXXFLAGS) $(DEPFLAGS) -c $< -o $@

$(LIB): $(LIB_OBJ)
	@rm -f $@
	ar rcs $@ $^

$(EXPLIB): $(EXP_OBJ)
	@rm -f $@
	ar rcs $@ $^

$(DFLAB): $(CLI_OBJ) $(EXPLIB) $(LIB)
	$(CXX) $(LDFLAGS) -o $@ $(CLI_OBJ) $(EXPLIB) $(LIB) $(LDLIBS)

# The web page's C API (src/web, not in the library) is linked into the
# tests natively, so that make sanitize checks it too.
WEB_API_OBJ := $(BUILD)/src/web/dflweb.o
$(TESTS): $(TEST_OBJ) $(WEB_API_OBJ) $(EXPLIB) $(LIB)
	$(CXX) $(LDFLAGS) -o $@ $(TEST_OBJ) $(WEB_API_OBJ) $(EXPLIB) $(LIB) $(LDLIBS) -lcriterion

$(BENCH_BIN): $(BENCH_OBJ) $(EXPLIB) $(LIB)
	$(CXX) $(LDFLAGS) -o $@ $(BENCH_OBJ) $(EXPLIB) $(LIB) $(LDLIBS)

# Installs the Debian packages dflab needs; a no-op when all are present.
# python3-paraview conflicts with python3-vtk9 and ships the same vtkmodules
# package (what dflab's VTK checks import), so either satisfies dflab.
deps:
	@missing=""; for p in $(APT_PKGS); do \
	  if [ $$p = python3-vtk9 ] && dpkg-query -W -f='$${Status}' python3-paraview 2>/dev/null | grep -q 'install ok installed'; then continue; fi; \
	  dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q 'install ok installed' || missing="$$missing $$p"; \
	done; \
	if [ -z "$$missing" ]; then echo "deps: all packages present"; \
	elif [ "$$(id -u)" = 0 ]; then \
	  echo "deps: installing$$missing"; \
	  apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq $$missing; \
	else echo "deps: missing packages; run as root:"; \
	  echo "  apt-get install -y$$missing"; exit 1; fi

# src/ is the library: it must not reach into experiments/ or tests/ (src/cli,
# the top of the dependency chain, is the one exception).
# The folder names are those of experiments/ (harness, cfg and every study
# folder), so a new study folder is covered without an edit here.
EMPTY :=
SPACE := $(EMPTY) $(EMPTY)
STUDY_DIRS := $(sort $(notdir $(patsubst %/,%,$(wildcard experiments/*/))))
LAYOUT_RE := $(subst $(SPACE),|,experiments tests $(STUDY_DIRS))
check-layout:
	@bad=$$(grep -rnE '#[[:space:]]*include[[:space:]]*"[^"]*($(LAYOUT_RE))/' src --exclude-dir=cli || true); \
	if [ -n "$$bad" ]; then echo "check-layout: src/ includes study code:"; echo "$$bad"; exit 1; fi; \
	echo "check-layout: src/ includes no study code"

# The test binary runs from the repository root; DFL_PYTHON and DFL_DFLAB
# let tests call the VTK validator and the CLI.
test: deps check-layout
	$(MAKE) --no-print-directory -j$(JOBS) $(DFLAB) $(TESTS)
	DFL_PYTHON=$(PYTHON) DFL_DFLAB=$(abspath $(DFLAB)) $(TESTS) -j2 --timeout 600
	$(MAKE) --no-print-directory -j$(JOBS) web-test
	$(MAKE) --no-print-directory -j$(JOBS) fuzz-short

sanitize: deps
	$(MAKE) --no-print-directory BUILD=build-san OPT=-O1 \
	  SAN="-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined" \
	  build-san/dflab build-san/dflab-tests
	ASAN_OPTIONS=detect_leaks=1:abort_on_error=0 UBSAN_OPTIONS=print_stacktrace=1 \
	  LSAN_OPTIONS=suppressions=$(abspath tests/lsan.supp) \
	  DFL_PYTHON=$(PYTHON) DFL_DFLAB=$(abspath build-san/dflab) DFL_SANITIZE=1 \
	  build-san/dflab-tests -j2 --timeout 1200
	@echo "== key sweep: every study key given a value its expects refuses (tests/cli/key_sweep.py)"
	ASAN_OPTIONS=detect_leaks=1:abort_on_error=0 UBSAN_OPTIONS=print_stacktrace=1 \
	  LSAN_OPTIONS=suppressions=$(abspath tests/lsan.supp) \
	  $(PYTHON) tests/cli/key_sweep.py build-san/dflab --jobs 2

include src/web/web.mk
include tests/fuzz/fuzz.mk

# The floor (this CPU's measured FMA, mul/add, divide and sqrt throughput per
# ISA) first, then every group; build/bench/summary.csv holds issue 19's
# measures (measure,dflab,peer,peer_value,ratio,floor_fraction).
# The bench is built with the program's own OPT (-O2 unless given), so that
# its rates are those of the code dflab runs, not of a faster build.
bench: deps
	$(MAKE) --no-print-directory OPT="$(OPT)" BUILD=build-bench build-bench/dflab-bench
	@mkdir -p build/bench
	DFL_PYTHON=$(PYTHON) build-bench/dflab-bench --summary build/bench/summary.csv $(BENCH)
	$(if $(BENCH),,$(MAKE) --no-print-directory web-bench)

# One folder per paper under configs/paper/; results/<config name>/ each.
# Then every peer script scripts/peers/*.py (baselines from other libraries)
# with --results results, then the report.  Reruns are incremental: `dflab
# run` skips every sweep point whose config (with its included shape files)
# and dflab binary are unchanged (results/<name>.points/), so only changed
# configs compute.  `make figures STUDY=name` redraws one section.
# Every study config: configs/paper/<paper>/*.ini and the configs of the
# study folders beside it (configs/<folder>/*.ini, e.g. configs/compare/),
# not the shared shape files nor the smoke configs.
PAPER_CONFIGS := $(sort $(wildcard configs/paper/*/*.ini) \
  $(filter-out configs/shapes/% configs/fields/% configs/smoke/% configs/paper/%,$(wildcard configs/*/*.ini)))
# Wall time of every config and peer goes to $(BUILD)/reproduce_times.txt and
# is printed at the end, slowest first.
REPRO_TIMES := $(BUILD)/reproduce_times.txt
reproduce: deps
	$(MAKE) --no-print-directory -j$(JOBS) $(DFLAB)
	@: > $(REPRO_TIMES)
	@set -e; for c in $(PAPER_CONFIGS); do echo "== $$c"; t0=$$(date +%s.%N); \
	  $(DFLAB) run $$c; echo "$$c $$t0 $$(date +%s.%N)" >> $(REPRO_TIMES); done
	@set -e; for p in $(sort $(wildcard scripts/peers/*.py)); do echo "== peer $$p"; \
	  t0=$$(date +%s.%N); $(PYTHON) $$p --results results; \
	  echo "peer:$$p $$t0 $$(date +%s.%N)" >> $(REPRO_TIMES); done
	$(PYTHON) scripts/report.py --results results --out results/REPORT.md
	@echo "== wall time per config (s), slowest first"; \
	  awk '{ printf "%9.1f  %s\n", $$3 - $$2, $$1 }' $(REPRO_TIMES) | sort -rn; \
	  awk '{ s += $$3 - $$2 } END { printf "%9.1f  total\n", s }' $(REPRO_TIMES)

# Every paper and smoke config at --threads 1, --threads 2 and
# OMP_NUM_THREADS=1, compared byte for byte (make test runs a quick subset).
check-threads: deps
	$(MAKE) --no-print-directory -j$(JOBS) $(DFLAB)
	$(PYTHON) scripts/check_threads.py $(DFLAB)

# Every paper and smoke config once per ISA this CPU runs (DFL_ISA, core/isa.h),
# compared byte for byte with the sse2 run (make test runs a quick subset).
check-isa: deps
	$(MAKE) --no-print-directory $(DFLAB)
	$(PYTHON) scripts/check_isa.py $(DFLAB)

figures:
	@test -n "$(STUDY)" || { echo "usage: make figures STUDY=<study, results folder name, runs/ folder name or path of a results folder>"; exit 2; }
	$(PYTHON) scripts/report.py --results results --only $(STUDY)

# Mutation testing: tests/mutate/mutants/$(MODULE).ini applied one at a time
# to a private copy of the tree (build-mutate/), each with its suites.
mutate: deps
	@test -n "$(MODULE)" || { echo "usage: make mutate MODULE=<name of tests/mutate/mutants/*.ini>"; exit 2; }
	$(PYTHON) tests/mutate/mutate.py $(MODULE)

clean:
	rm -rf build build-san build-bench build-fuzz build-mutate

-include $(shell find $(BUILD) -name '*.d' 2>/dev/null)
