"""``python -m synthesis`` runs the ``assur`` command."""

import sys

from synthesis.cli import main

sys.exit(main())
