"""The portable core (integers only, no I/O, no clock)."""

# The firmware's version: `selftest` and `hexapod doctor` report it; keep pyproject.toml's in step
# (tests/test_selftest.py checks).
VERSION = "0.1.0"
