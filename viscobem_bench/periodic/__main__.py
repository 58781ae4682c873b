"""``python -m viscobem_bench.periodic``: the command line of :mod:`viscobem_bench.periodic.benchmark`."""

import sys

from viscobem_bench.periodic.benchmark import main

sys.exit(main())
