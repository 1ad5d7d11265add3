# Prism developer commands. Python 3.11 is the only prerequisite.
PYTHON ?= python3.11
VENV := .venv
PY := $(VENV)/bin/python
STAMP := $(VENV)/.installed

.PHONY: render rainbow sky test test-fast test-numpy extension bench parity venv clean inventory

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

# Runs the test suite; the 25 slowest tests close the output (where the time goes).
test: $(STAMP)
	$(PY) -m pytest --durations=25

# The physics and tracer tests alone (no bpy, no renders through Blender): tests/tracer and
# tests/benchmarks. Under two minutes once the kernels are compiled (README, "Tests").
FAST_TESTS := tests/tracer tests/benchmarks
test-fast: $(STAMP)
	$(PY) -m pytest -q --durations=10 $(FAST_TESTS)

# The tracer's physics on both numpy lines Prism meets: numpy 1.26 (Blender 4.2-5.0, .venv) and
# numpy 2.x (.venv-numpy2: the same pins without bpy, which needs numpy<2; helpers/without_bpy.py).
# numba 0.68 accepts numpy 1.22-2.5. numpy 2.5 (no np.trapz at all) needs Python >= 3.12:
#   make test-numpy NUMPY2=2.5.5 NUMPY2_PYTHON=python3.12
# Up to 2.4 np.trapz is only deprecated: -W error makes a call of it fail the numpy 2 run.
NUMPY2 ?= 2.4.6
NUMPY2_PYTHON ?= $(PYTHON)
VENV_NUMPY2 := .venv-numpy2
NUMPY2_STAMP := $(VENV_NUMPY2)/.installed-$(NUMPY2)
# Closed forms and samplers only: the three test files that render a scene stay in test-fast.
PHYSICS_TESTS := tests/tracer/spectra tests/tracer/bsdf tests/tracer/lens \
  --ignore=tests/tracer/lens/test_camera.py --ignore=tests/tracer/lens/test_render_chromatic.py \
  --ignore=tests/tracer/spectra/test_atmosphere.py
$(NUMPY2_STAMP): requirements.txt
	@test -x $(VENV_NUMPY2)/bin/python || $(NUMPY2_PYTHON) -m venv $(VENV_NUMPY2)
	grep -vE '^(bpy|numpy|flip-evaluator)==' requirements.txt > $(VENV_NUMPY2)/requirements.txt
	$(VENV_NUMPY2)/bin/python -m pip install --quiet --upgrade pip
	$(VENV_NUMPY2)/bin/python -m pip install --quiet -r $(VENV_NUMPY2)/requirements.txt numpy==$(NUMPY2)
	@touch $@

test-numpy: $(STAMP) $(NUMPY2_STAMP)
	$(PY) -m pytest -q -p no:cacheprovider $(PHYSICS_TESTS)
	PYTHONPATH=tests PRISM_KERNEL_CACHE=$(CURDIR)/build/kernels-numpy2 $(VENV_NUMPY2)/bin/python -m pytest -q \
	  -p no:cacheprovider -p helpers.without_bpy -W "error:.*trapz:DeprecationWarning" $(PHYSICS_TESTS)

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
	rm -rf renders dist build .pytest_cache $(VENV_NUMPY2)
