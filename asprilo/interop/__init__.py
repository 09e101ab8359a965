"""Interoperability with the MAPF world: MovingAI maps and scenarios, LaCAM/PIBT results,
and conversion between domains M and Md (``asprilo convert``)."""
