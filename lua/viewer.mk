# The replay viewer (build/rigid --html): its page compiled into the host, its browser test
# (make test, when Chromium is installed), its frame-rate bench and the README's screenshot.
LUA_VIEWER_JS := lua/viewer/decode.js lua/viewer/raster.js lua/viewer/draw.js lua/viewer/ui.js
CHROMIUM := $(shell command -v chromium 2>/dev/null || command -v chromium-browser 2>/dev/null)
TEST_RUNS += check-viewer
.PHONY: check-viewer bench-viewer readme-pictures

# The page: viewer.html with the scripts in place of its marker line.
$(B)/lua/viewer.html: lua/viewer/viewer.html $(LUA_VIEWER_JS)
	@mkdir -p $(@D)
	@{ echo '<script>'; cat $(LUA_VIEWER_JS); echo '</script>'; } > $@.js
	@sed -e '/^<!-- rigid:scripts -->$$/{r $@.js' -e 'd;}' $< > $@.tmp
	@grep -q '^<!-- rigid:recording -->$$' $@.tmp || { echo "$<: no recording marker"; exit 1; }
	@mv $@.tmp $@
	@rm -f $@.js

# Each line of the page becomes one string literal (C99 promises literals of 4095 bytes);
# backslashes, quotes and question marks (trigraphs) escaped.
$(B)/lua/lviewer_html.c: $(B)/lua/viewer.html
	@awk 'length($$0) > 4000 { print FILENAME ":" NR ": line too long for a C string literal"; bad = 1 } END { exit bad }' $<
	@{ echo '/* generated from lua/viewer/: do not edit */'; \
	  echo 'extern const char *const lviewer_html[];'; \
	  echo 'const char *const lviewer_html[] = {'; \
	  sed -e 's/\\/\\\\/g' -e 's/"/\\"/g' -e 's/?/\\?/g' -e 's/^/    "/' -e 's/$$/\\n",/' $<; \
	  echo '    0'; echo '};'; } > $@.tmp
	@mv $@.tmp $@

$(LUA_VIEWER): $(B)/lua/lviewer_html.c
	$(CC) $(CFLAGS) -c $< -o $@

# The browser test: headless Chromium, no network.  Skipped, and said so, without Chromium.
check-viewer: $(LUA_HOST)
	@echo "== tests/viewer"
	@if [ -z "$(CHROMIUM)" ]; then \
	  echo "SKIPPED: the replay viewer's browser test needs Chromium (tools/install-deps.sh --browser)"; \
	else $(PYTHON) tests/viewer/test_viewer.py --host $(LUA_HOST) --out $(B)/viewer-tests; fi

# The big scene's page: its size, and the frame rate it plays at in Chromium.
bench: bench-viewer
bench-viewer: $(LUA_HOST)
	@echo "== replay viewer: rain 4000 over 600 steps"
	@tools/install-deps.sh --browser
	@$(LUA_HOST) lua/examples/rain.lua --html $(B)/rain.html > /dev/null
	@$(PYTHON) tools/viewer_bench.py --fps $(B)/rain.html

# The README's pictures of make run: the replay viewer at a moment in the air, and the SVG.
readme-pictures: $(LUA_HOST)
	@tools/install-deps.sh --browser
	@$(LUA_HOST) lua/examples/platformer.lua --svg $(B)/run.svg --html $(B)/run.html > /dev/null
	$(PYTHON) tools/viewer_bench.py --shot "$(B)/run.html#frame=250&velocities=1" tools/charts/viewer.png \
	  --svg-shot $(B)/run.svg tools/charts/run.png
