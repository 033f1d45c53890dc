# The accuracy lab (issue 5): tools/accuracy in this build, its test's shared sources, and
# `make charts` (the lab in the float and the double build, rendered by gnuplot).
ACC_SHARED := tools/accuracy_scenes.c
ACC_HDR := tools/accuracy_scenes.h tools/accuracy_collision.h
# The collision scenes (tunnelling, pile) need the library's shapes and its continuous
# collision switch; until src/ implements them the lab and its test build without them.
ACC_COLLISION := $(shell grep -qs rg_body_set_circle src/*.c && grep -qs rg_world_set_continuous src/*.c && echo 1)
ifeq ($(ACC_COLLISION),1)
ACC_SHARED += tools/accuracy_collision.c tools/accuracy_soup.c tools/accuracy_contacts.c
ACC_DEFS := -DACC_COLLISION
endif
ALL_TARGETS += $(B)/accuracy

$(B)/accuracy: tools/accuracy.c $(ACC_SHARED) $(ACC_HDR) $(LIB_A)
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $(ACC_DEFS) -Itools $(LDFLAGS) -o $@ tools/accuracy.c $(ACC_SHARED) $(LIB_A) $(LDLIBS)

# tests/test_accuracy.c measures with the lab's own scene code.
$(B)/tests/test_accuracy: tests/test_accuracy.c tests/testutil.h $(ACC_SHARED) $(ACC_HDR) $(LIB_A)
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $(ACC_DEFS) -Itests -Itools $(LDFLAGS) -o $@ $< $(ACC_SHARED) $(LIB_A) \
	  $(CMOCKA_LIBS) $(LDLIBS)

# Both builds of the lab: the float one in $(ACC_FB), the double one in $(ACC_DB).
ifeq ($(REAL),double)
ACC_DB := $(B)
ACC_FB ?= build
else
ACC_FB := $(B)
ACC_DB ?= $(B)/double
endif
ACC_CHARTS ?= $(ACC_FB)/charts
# The charts the README shows, committed under tools/charts/.
ACC_README_CHARTS := pareto energy60 convergence stability framerate dissipation \
                     $(if $(ACC_COLLISION),tunnel pile)

.PHONY: charts-accuracy charts-accuracy-copy
charts: charts-accuracy

charts-accuracy:
	@tools/install-deps.sh --charts
	@$(MAKE) --no-print-directory REAL=float B=$(ACC_FB) $(ACC_FB)/accuracy
	@$(MAKE) --no-print-directory REAL=double B=$(ACC_DB) $(ACC_DB)/accuracy
	@mkdir -p $(ACC_CHARTS)
	@rm -f $(ACC_CHARTS)/tunnel_*.csv $(ACC_CHARTS)/pile_*.csv
	$(ACC_FB)/accuracy --out $(ACC_CHARTS) | tee $(ACC_CHARTS)/accuracy_float.txt
	$(ACC_DB)/accuracy --out $(ACC_CHARTS) | tee $(ACC_CHARTS)/accuracy_double.txt
	gnuplot -e "dir='$(ACC_CHARTS)'" tools/charts/accuracy.gp
	@echo "charts: $(ACC_CHARTS)/*.svg and *.png"

# Refreshes the README's copies from the last `make charts`.
charts-accuracy-copy:
	for c in $(ACC_README_CHARTS); do cp $(ACC_CHARTS)/$$c.png $(ACC_CHARTS)/$$c.svg tools/charts/; done

# Every chart held against its CSV (tests/pictures/check_charts.py): the lab's quick sweep in
# both builds, gnuplot in table mode (the points each curve draws), the checker.  Skipped,
# and said so, without gnuplot (tools/install-deps.sh --charts installs it).
TEST_RUNS += check-charts
.PHONY: check-charts
ACC_CHECK := $(B)/chart-check
check-charts:
	@echo "== tests/pictures/check_charts.py"
	@if ! command -v gnuplot >/dev/null 2>&1; then \
	  echo "SKIPPED: the chart check needs gnuplot (tools/install-deps.sh --charts)"; exit 0; fi; \
	 $(MAKE) --no-print-directory REAL=float B=$(ACC_FB) $(ACC_FB)/accuracy >/dev/null && \
	 $(MAKE) --no-print-directory REAL=double B=$(ACC_DB) $(ACC_DB)/accuracy >/dev/null && \
	 rm -rf $(ACC_CHECK) && mkdir -p $(ACC_CHECK)/tables && \
	 $(ACC_FB)/accuracy --quick --out $(ACC_CHECK) >/dev/null && \
	 $(ACC_DB)/accuracy --quick --out $(ACC_CHECK) >/dev/null && \
	 gnuplot -e "dir='$(ACC_CHECK)'; check='$(ACC_CHECK)/tables'" tools/charts/accuracy.gp 2>/dev/null && \
	 $(PYTHON) tests/pictures/check_charts.py --csv $(ACC_CHECK) --tables $(ACC_CHECK)/tables
