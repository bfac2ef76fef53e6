import hexapod_host  # noqa: F401  (puts firmware, boards and shims on sys.path)

pytest_plugins = ["hexapod_host.testing"]
