"""The benchmarks behind `hexapod bench NAME --json` (ik, i2c, tick, guard): each returns a dict of figures."""
