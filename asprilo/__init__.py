"""asprilo: Answer Set Programming for robotic intra-logistics."""

__version__ = "0.1.0"
