"""The viewer's state without Qt: the document and its undo history, checked edits, the plan's
states (track), goals, atoms, loading, words for tooltips, whether a window can open here.

Nothing in this package imports Qt (an import-linter contract names the package)."""
