"""`python -m hexapod_host ARGS`: the `hexapod` command."""

import sys

from hexapod_host.commands.cli import main

sys.exit(main())
