"""``python -m asprilo.cli`` runs the ``asprilo`` command."""

import sys

from . import main

sys.exit(main())
