"""``python -m asprilo`` runs the ``asprilo`` command."""

import sys

from .cli import main

sys.exit(main())
