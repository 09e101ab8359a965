"""The Qt visualizer and layout editor.

Its rooms: ``state`` (no Qt), ``scene``, ``panels``, ``editor``, ``jobs``, ``export``; the
window (``window``) and the ``viz`` command (``cli``) sit above them.  ``render`` draws
pictures and animations of a plan without a window (Qt is loaded when it runs).
"""

from .export.render import render

__all__ = ["render"]
