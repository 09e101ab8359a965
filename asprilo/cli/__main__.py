"""``python -m asprilo.cli`` runs the ``asprilo`` command."""

import sys

from . import main

if __name__ == "__main__":  # not when a child process (multiprocessing) imports it
    sys.exit(main())
