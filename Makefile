# Two commands for a newcomer: `make book` builds the static site, `make test` runs every test
# (after building both editions and their PDFs: `make pdf`).
# Each creates .venv if it is missing and installs what it needs (Python 3.11 and pip suffice).

PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed
SITE   := _build/html
STUDENT := _build/student

.PHONY: book book-student pdf test notebooks sources typecheck cpu-levels clean

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)

$(STAMP): pyproject.toml | $(BIN)/python
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -e ".[book,test,dev]"
	touch $(STAMP)

# MathJax 3 is served by the site itself (no CDN): copied from the PyPI package at build time.
_mathjax/mathjax/es5/tex-chtml.js: $(STAMP)
	rm -rf _mathjax && mkdir -p _mathjax
	cp -r "$$($(BIN)/python -c 'import mathjax, os; print(os.path.dirname(mathjax.__file__))')/static/mathjax/es5" _mathjax/mathjax-es5
	mkdir -p _mathjax/mathjax && mv _mathjax/mathjax-es5 _mathjax/mathjax/es5

book: $(STAMP) _mathjax/mathjax/es5/tex-chtml.js
	$(BIN)/python tools/status_page.py
	$(BIN)/jupyter-book build . --all --builder html --warningiserror --keep-going

# The student edition: the same book without the exercises' solutions (sphinx-exercise's
# hide_solutions), its configuration generated from _config.yml; the site is in $(STUDENT)/_build/html.
book-student: $(STAMP) _mathjax/mathjax/es5/tex-chtml.js
	$(BIN)/python tools/status_page.py
	$(BIN)/python tools/student_config.py $(STUDENT)/_config.yml
	$(BIN)/jupyter-book build . --all --builder html --warningiserror --keep-going \
		--config $(STUDENT)/_config.yml --path-output $(STUDENT)

# The printable book: one PDF per edition (_build/pdf/mechanisms-book.pdf and mechanisms-book-student.pdf),
# the built sites printed by Chromium through Playwright in the order of _toc.yml (tools/make_pdf.py).
pdf: book book-student
	$(BIN)/python tools/make_pdf.py

test: book book-student pdf
	$(BIN)/mypy
	$(BIN)/python -m pytest

# Re-execute notebooks in place and store their outputs (NB=path/to/one.ipynb for one).
notebooks: $(STAMP)
	$(BIN)/python tools/run_notebooks.py $(NB)

# The notebooks' text, paired by jupytext as MyST Markdown (book/NN-*.md, exercises/NN-*.md): after editing
# either file of a pair, sync them (the newer file wins), then re-execute with `make notebooks NB=…`.
sources: $(STAMP)
	$(BIN)/jupytext --sync book/[0-9][0-9]-*.ipynb exercises/[0-9][0-9]-*.ipynb

# Every notebook re-executed (strict nbval) at each numpy CPU level this machine can imitate besides its own
# (NPY_DISABLE_CPU_FEATURES: without AVX-512, baseline): stored outputs must not depend on the processor.
# `make test` runs it too; run it before committing a notebook.
cpu-levels: $(STAMP)
	MECHANISMS_NUDGE_SEED=$${MECHANISMS_NUDGE_SEED:-1} $(BIN)/python -m pytest tests/test_cpu_levels.py -v

# Type checking of the package (configuration in pyproject.toml); `make test` runs it too.
typecheck: $(STAMP)
	$(BIN)/mypy

clean:
	rm -rf _build _mathjax
