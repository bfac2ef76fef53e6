"""For the tests: the two-runtime harness (runtimes, a pytest plugin) and the float reference oracle (reference)."""
