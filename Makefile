# Prism developer commands. Python 3.11 is the only prerequisite.
PYTHON ?= python3.11
VENV := .venv
PY := $(VENV)/bin/python
STAMP := $(VENV)/.installed

.PHONY: render rainbow sky test extension bench parity venv clean inventory

# Creates .venv with the pinned requirements, once; re-running is a no-op.
$(STAMP): requirements.txt
	@test -x $(PY) || $(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip
	$(PY) -m pip install --quiet -r requirements.txt
	@touch $(STAMP)

venv: $(STAMP)

# Builds the demo scene and renders it with Prism to renders/demo.png.
render: $(STAMP)
	$(PY) demo/build_demo_scene.py renders/demo.blend
	$(PY) render.py renders/demo.blend --samples 64 --output renders/demo.png

# Builds the rainbow demo (slit lamp, prism, wall; a glass ball's caustic) and renders it to renders/rainbow.png.
rainbow: $(STAMP)
	$(PY) demo/build_rainbow_scene.py renders/rainbow.blend
	$(PY) render.py renders/rainbow.blend --samples 64 --output renders/rainbow.png

# Builds the sky demo (three balls under a Nishita sky) and renders it with Prism and with Cycles, side by side.
sky: $(STAMP)
	$(PY) demo/build_sky_scene.py renders/sky.blend
	$(PY) render.py renders/sky.blend --samples 256 --output renders/sky.png
	$(PY) demo/render_cycles.py renders/sky.blend renders/sky_cycles.png --samples 128

# Runs the test suite.
test: $(STAMP)
	$(PY) -m pytest

# Regenerates docs/bad_input.md from the tests that feed Prism bad input.
inventory: $(STAMP)
	$(PY) tools/bad_input_inventory.py

# Builds the installable extension zip(s) into dist/ and validates them.
extension: $(STAMP)
	$(PY) tools/build_extension.py

# Speed-against-error benchmarks; writes benchmarks/results/ and docs/performance.md.
# `make bench BENCH_ARGS=--quick` is the two-minute plumbing check (results in benchmarks/results/quick/).
# Mitsuba's fast variant needs libLLVM >= 19 (Debian: libllvm19; a fresh machine has no package lists
# yet, hence the update); without it the slower scalar one runs.
BENCH_ARGS ?=
bench: $(STAMP)
	@dpkg-query -W -f='$${Status}' libllvm19 2>/dev/null | grep -q "install ok installed" || \
	  (test "$$(id -u)" = 0 && (apt-get install -y -qq libllvm19 >/dev/null 2>&1 || \
	    (apt-get update -qq && apt-get install -y -qq libllvm19))) || \
	  echo "note: install libllvm19 for Mitsuba's llvm variant (apt-get install libllvm19)"
	$(PY) -m pip install --quiet -r benchmarks/requirements.txt
	$(PY) -m benchmarks.run $(BENCH_ARGS)

# Scene parity with Cycles: small scenes exercising Blender's scene settings, rendered by Prism and by Cycles;
# writes docs/parity.md and docs/images/parity/. `make parity PARITY_ARGS="--scenes clip_range holdouts"` for
# some scenes, `PARITY_ARGS="--seeds 4"` to measure each scene's noise too.
PARITY_ARGS ?=
parity: $(STAMP)
	$(PY) -m benchmarks.parity.run $(PARITY_ARGS)

clean:
	rm -rf renders dist build .pytest_cache
