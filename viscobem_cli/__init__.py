"""The ``viscobem`` command line: scenes (TOML studies), runs, benchmarks."""
