# libFuzzer harnesses (clang-14, ASan + UBSan) for the readers and the
# config -> field path; included by the Makefile.
#
#   make fuzz          each harness for FUZZ_SECONDS (default 300), corpora
#                      kept in build-fuzz/corpus/<name>/ between runs
#   make fuzz-short    the regression cases, then each harness for
#                      FUZZ_SHORT seconds (default 30); part of make test
#
# The library is built a second time with clang into build-fuzz/.  Seeds:
# configs/**/*.ini (config, sweep, field), and tests/fuzz/seeds/<name>/
# (points; record: point.json records, fuzz_record.c merges each; field:
# besides the configs, one small single-valued field of every kind, pht and
# proxy inputs included, as most configs are sweeps the harness skips).
# The INI harnesses get a dictionary of every key a getter reads and every
# name a kind, storage or filter takes (tests/fuzz/make_dict.py, made from
# the sources: build-fuzz/dflab.dict);
# every input that ever crashed a harness is kept in
# tests/fuzz/regress/<name>/ and run first, so a regression fails at once.

FUZZ_BUILD   := build-fuzz
FUZZ_SAN     := -fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined
FUZZERS      := config sweep points field record
FUZZ_SECONDS ?= 300
FUZZ_SHORT   ?= 30
FUZZ_SHORT_RECORD ?= 10
FUZZ_BINS    := $(FUZZERS:%=$(FUZZ_BUILD)/fuzz_%)
FUZZ_ENV     := ASAN_OPTIONS=detect_leaks=1:allocator_may_return_null=1 OMP_NUM_THREADS=1 \
                UBSAN_OPTIONS=print_stacktrace=1
FUZZ_FLAGS   := -timeout=20 -rss_limit_mb=2048 -max_len=8192 -print_final_stats=1

.PHONY: fuzz fuzz-short fuzz-build
fuzz-build:
	$(MAKE) --no-print-directory BUILD=$(FUZZ_BUILD) CC=clang-14 CXX=clang++-14 OPT=-O1 \
	  SAN="$(FUZZ_SAN)" $(FUZZ_BUILD)/libdfl.a $(FUZZ_BUILD)/libdflexp.a
	$(MAKE) --no-print-directory $(FUZZ_BINS)

$(FUZZ_BUILD)/fuzz_%: tests/fuzz/fuzz_%.c tests/fuzz/fuzz_util.h $(FUZZ_BUILD)/libdfl.a $(FUZZ_BUILD)/libdflexp.a
	clang-14 -Isrc -Iexperiments -D_POSIX_C_SOURCE=200809L -std=c11 -g -O1 \
	  -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined -c $< -o $@.o
	clang++-14 -fsanitize=fuzzer,address,undefined -fopenmp -o $@ $@.o \
	  $(FUZZ_BUILD)/libdflexp.a $(FUZZ_BUILD)/libdfl.a $(LDLIBS)

# corpus/<name>: seeds copied in once; libFuzzer adds what it finds
$(FUZZ_BUILD)/corpus/%/.seeded:
	@mkdir -p $(dir $@)
	@if [ -d tests/fuzz/seeds/$* ]; then cp tests/fuzz/seeds/$*/* $(dir $@); fi
	@if [ ! -d tests/fuzz/seeds/$* ] || [ $* = field ]; then \
	 for f in $$(find configs -name '*.ini'); do cp $$f $(dir $@)/$$(echo $$f | tr / _); done; fi
	@touch $@

fuzz-regress: fuzz-build
	@set -e; for f in $(FUZZERS); do \
	  if ls tests/fuzz/regress/$$f/* >/dev/null 2>&1; then \
	    $(FUZZ_ENV) $(FUZZ_BUILD)/fuzz_$$f $(FUZZ_FLAGS) tests/fuzz/regress/$$f/* </dev/null 2>$(FUZZ_BUILD)/regress_$$f.log \
	      || { echo "fuzz regression: $$f"; tail -30 $(FUZZ_BUILD)/regress_$$f.log; exit 1; }; fi; done; \
	  echo "fuzz-regress: all regression cases pass"

# One harness for $(1) seconds; fails on any finding (the input is left in
# $(FUZZ_BUILD)/ as crash-*, leak-*, timeout-*: add it to tests/fuzz/regress/).
FUZZ_DICT := $(FUZZ_BUILD)/dflab.dict
$(FUZZ_DICT): tests/fuzz/make_dict.py $(wildcard src/*/*.c src/*/*.h experiments/*/*.c)
	@mkdir -p $(dir $@)
	$(PYTHON) tests/fuzz/make_dict.py $@
fuzz_dict = $(if $(filter config sweep field,$(1)),-dict=$(FUZZ_DICT))
fuzz_run = ( $(FUZZ_ENV) $(FUZZ_BUILD)/fuzz_$(2) $(FUZZ_FLAGS) $(call fuzz_dict,$(2)) -max_total_time=$(1) \
	  -artifact_prefix=$(FUZZ_BUILD)/ $(FUZZ_BUILD)/corpus/$(2) </dev/null \
	  >$(FUZZ_BUILD)/fuzz_$(2).log 2>&1 || { echo "fuzz: $(2) found a crash"; tail -40 $(FUZZ_BUILD)/fuzz_$(2).log; exit 1; }; \
	  grep -E 'stat::number_of_executed_units|DONE' $(FUZZ_BUILD)/fuzz_$(2).log | tail -2 | sed 's/^/fuzz $(2): /' )

fuzz-short: fuzz-regress $(FUZZ_DICT) $(FUZZERS:%=$(FUZZ_BUILD)/corpus/%/.seeded)
	@set -e; $(call fuzz_run,$(FUZZ_SHORT),config) & p1=$$!; $(call fuzz_run,$(FUZZ_SHORT),points) & p2=$$!; \
	  wait $$p1 && wait $$p2; \
	  $(call fuzz_run,$(FUZZ_SHORT_RECORD),record); \
	  $(call fuzz_run,$(FUZZ_SHORT),sweep) & p1=$$!; $(call fuzz_run,$(FUZZ_SHORT),field) & p2=$$!; \
	  wait $$p1 && wait $$p2

fuzz: fuzz-regress $(FUZZ_DICT) $(FUZZERS:%=$(FUZZ_BUILD)/corpus/%/.seeded)
	@set -e; for f in $(FUZZERS); do $(call fuzz_run,$(FUZZ_SECONDS),$$f); done
