# make demo: venv + pinned deps, build the demo scene headless, save out/demo.blend, render out/demo.png
# make demo-blend: regenerate the committed demo.blend (after a change to the demo or a node group)
# make test: venv + pinned deps, ruff, then the pytest suite but its stress tests, on up to 4 workers
# (work-stealing: a worker left idle at the end takes tests queued on the other), its 15 slowest listed
# make stress: the stress tests (settings at their extremes, the largest maps) and the further
# settings of checks make test runs at one or two (EEVEE's other sun elevations), on the same workers;
# CI runs both
#
# BLENDER picks the bpy the commands run on, each in its own venv:
#   5.2 (default, the current LTS): bpy 5.2.3 on Python 3.13, .venv, requirements.txt
#   5.0:                            bpy 5.0.1 on Python 3.11, .venv-5.0, requirements-5.0.txt
# PYTHON=/path/to/pythonX.Y overrides the interpreter devtools/find-python finds.
BLENDER ?= 5.2
ifeq ($(BLENDER),5.2)
PYTHON_VERSION := 3.13
VENV := .venv
REQUIREMENTS := requirements.txt
else ifeq ($(BLENDER),5.0)
PYTHON_VERSION := 3.11
VENV := .venv-5.0
REQUIREMENTS := requirements-5.0.txt
else
$(error BLENDER must be 5.2 or 5.0, got '$(BLENDER)')
endif
PYTHON ?= $(shell sh devtools/find-python $(PYTHON_VERSION))
PY := $(VENV)/bin/python
STAMP := $(VENV)/.installed

.PHONY: demo demo-blend test stress lint bench clean

# A venv made by another Python (an older checkout's, or the other Blender's) is made anew.
$(STAMP): $(REQUIREMENTS)
	@test -n "$(PYTHON)" || { echo "make: no Python $(PYTHON_VERSION) for Blender $(BLENDER); pass PYTHON=/path/to/python$(PYTHON_VERSION)" >&2; exit 2; }
	@[ "$$($(PY) -c 'import sys; print("%d.%d" % sys.version_info[:2])' 2>/dev/null)" = "$(PYTHON_VERSION)" ] \
		|| { rm -rf $(VENV) && echo "$(PYTHON) -m venv $(VENV)" && $(PYTHON) -m venv $(VENV); }
	$(PY) -m pip install --disable-pip-version-check -q -r $(REQUIREMENTS)
	touch $(STAMP)

# QUALITY: draft (default, minutes), preview, or final (the 1280x720 poster frame).
QUALITY ?= draft

demo: $(STAMP)
	$(PY) devtools/demo.py --quality $(QUALITY) --output out/demo.png

demo-blend: $(STAMP)
	$(PY) devtools/demo.py --blend demo.blend --build-only

lint: $(STAMP)
	$(VENV)/bin/ruff check .

test: lint
	$(PY) -m pytest -m "not stress and not sweep" -n auto --maxprocesses=4 --dist worksteal --durations=15

stress: $(STAMP)
	$(PY) -m pytest -m "stress or sweep" -n auto --maxprocesses=4 --dist worksteal --durations=15

bench: $(STAMP)
	$(PY) -m pip install --disable-pip-version-check -q -r requirements-bench.txt
	$(PY) bench/looks.py
	$(PY) bench/footprints.py
	$(PY) bench/footprint_dicing.py
	$(PY) bench/atmosphere.py
	$(PY) bench/dunes.py
	$(PY) bench/effects.py
	$(PY) bench/optimize.py
	$(PY) bench/quality.py

clean:
	rm -rf out build .pytest_cache .ruff_cache
