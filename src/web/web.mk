# The teaching page (src/web/, issue "live page"): dflab's 2D library parts
# (core, geom, field, rfunc) compiled with Debian's emscripten into
# build/web/ (index.html, dflab.js with the wasm inlined so that the page
# also opens from file://, and dflab.wasm beside it, the same module, for
# its size).  Included by the Makefile; `make web` builds it, `make
# web-test` (run by `make test`) drives it in headless Chromium.
#
# The sanitizer build does not build or test the page: ASan/UBSan cover
# the same C sources natively, and the browser test only checks that the
# wasm build agrees with the native `dflab probe`.
#
# solve/ (Ceres, C++) is not compiled: src/web/lsq_stub.c stands in for
# solve/lsq.h (every call fails with a message), which geom's footpoint
# code names for its Ceres backend only; the page uses the Newton backend.
# The library is linked as an archive, so only the objects the API reaches
# come in.

EMCC     ?= emcc
EMAR     ?= emar
NODE     ?= node
NPM      ?= npm
# Debian's emscripten finds its node modules (acorn) under /usr/share/nodejs.
WEB_ENV  := NODE_PATH=/usr/share/nodejs
WEB_DIR  := $(BUILD)/web
# gridpeer.c stores half floats through the host's Imath, which emscripten's
# sysroot lacks; the page does not use it.
# vdb.c is the C side of the OpenVDB adapter (field/vdb_grid.cc, C++ and
# OpenVDB), which the page neither builds nor uses; the mesh shape (Embree)
# is native only: the page has no meshes.
WEB_SKIP := src/field/gridpeer.c src/field/vdb.c src/geom/mesh_bvh.c src/geom/mesh.c
WEB_SRCS := $(filter-out $(WEB_SKIP),$(shell find src/core src/geom src/field src/rfunc -name '*.c' | sort))
WEB_OBJ  := $(WEB_SRCS:%.c=$(WEB_DIR)/obj/%.o)
WEB_API  := $(WEB_DIR)/obj/src/web/dflweb.o $(WEB_DIR)/obj/src/web/lsq_stub.o
WEB_LIB  := $(WEB_DIR)/obj/libdfl-web.a
WEB_PAGE := $(wildcard src/web/page/*)
WEB_CFLAGS := -std=c11 -O2 -Wall -Wextra -Wno-unknown-pragmas -Isrc -D_POSIX_C_SOURCE=200809L -MMD -MP
WEB_FUNCS := malloc free dflw_scene_new dflw_scene_free dflw_scene_error dflw_two_segments dflw_two_bisector \
  dflw_scene_polyline dflw_scene_exact dflw_scene_curve dflw_scene_nvertices dflw_scene_vertices dflw_eval \
  dflw_grid dflw_dist dflw_jet dflw_order dflw_bounds dflw_ring dflw_bulge dflw_curve_bulge
WEB_COMMA := ,
WEB_EXPORTS := $(subst $(eval) ,$(WEB_COMMA),$(strip $(WEB_FUNCS:%=_%)))
WEB_LDFLAGS := -O2 -sMODULARIZE=1 -sEXPORT_NAME=createDflab -sENVIRONMENT=web \
  -sALLOW_MEMORY_GROWTH=1 -sEXPORTED_FUNCTIONS=$(WEB_EXPORTS) \
  -sEXPORTED_RUNTIME_METHODS=UTF8ToString

web: | deps
web: $(WEB_DIR)/dflab.js $(WEB_DIR)/dflab.wasm $(WEB_PAGE:src/web/page/%=$(WEB_DIR)/%)

$(WEB_DIR)/obj/%.o: %.c
	@mkdir -p $(dir $@)
	$(WEB_ENV) $(EMCC) $(WEB_CFLAGS) -c $< -o $@

$(WEB_LIB): $(WEB_OBJ)
	@rm -f $@
	$(WEB_ENV) $(EMAR) rcs $@ $^

$(WEB_DIR)/dflab.js: $(WEB_API) $(WEB_LIB)
	$(WEB_ENV) $(EMCC) $(WEB_LDFLAGS) -sSINGLE_FILE=1 -o $@ $^

# The same module as a separate file: its size is the page's wasm size.
$(WEB_DIR)/dflab.wasm: $(WEB_API) $(WEB_LIB)
	@mkdir -p $(WEB_DIR)/sized
	$(WEB_ENV) $(EMCC) $(WEB_LDFLAGS) -o $(WEB_DIR)/sized/dflab.js $^
	cp $(WEB_DIR)/sized/dflab.wasm $@

$(WEB_DIR)/%: src/web/page/%
	@mkdir -p $(dir $@)
	cp $< $@

# playwright-core from package-lock.json (no browser download: the test
# drives Debian's /usr/bin/chromium).
tests/web/node_modules/.installed: tests/web/package.json tests/web/package-lock.json
	cd tests/web && PLAYWRIGHT_SKIP_BROWSER_DOWNLOAD=1 $(NPM) ci --no-audit --no-fund
	@touch $@

web-test: web $(DFLAB) tests/web/node_modules/.installed
	DFL_DFLAB=$(abspath $(DFLAB)) DFL_WEB=$(abspath $(WEB_DIR)) DFL_OUT=$(abspath $(BUILD))/web-test \
	  $(NODE) tests/web/page.test.mjs

-include $(shell find $(WEB_DIR)/obj -name '*.d' 2>/dev/null)

# The two-segment panel's frame rate at 256^2 in headless chromium (run by
# `make bench`; printed and written to build/web-test/web_bench.txt).
web-bench: web tests/web/node_modules/.installed
	DFL_WEB=$(abspath $(WEB_DIR)) DFL_OUT=$(abspath $(BUILD))/web-test $(NODE) tests/web/page.test.mjs --bench
