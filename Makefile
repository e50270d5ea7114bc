# make demo: venv + pinned deps, build the demo scene headless, render out/demo.png
# make test: venv + pinned deps, ruff, then the whole pytest suite
PYTHON ?= python3.11
VENV := .venv
PY := $(VENV)/bin/python
STAMP := $(VENV)/.installed

.PHONY: demo test lint bench clean

$(STAMP): requirements.txt
	test -x $(PY) || $(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --disable-pip-version-check -q -r requirements.txt
	touch $(STAMP)

demo: $(STAMP)
	$(PY) devtools/demo.py --output out/demo.png

lint: $(STAMP)
	$(VENV)/bin/ruff check .

test: lint
	$(PY) -m pytest

bench: $(STAMP)
	$(PY) -m pip install --disable-pip-version-check -q -r requirements-bench.txt
	$(PY) bench/glints.py
	$(PY) bench/footprints.py
	$(PY) bench/footprint_dicing.py
	$(PY) bench/atmosphere.py
	$(PY) bench/optimize.py
	$(PY) bench/quality.py

clean:
	rm -rf out build .pytest_cache .ruff_cache
