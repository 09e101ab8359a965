"""The large-neighbourhood search keeps a plan as good as the present one (a move on a
plateau, issue 45), and only a better one counts as better.

The floor of ``test_anytime_readings``, read as C: station (1,1), highway (2,1), the robot on
(3,1), shelf 1 on (2,2) holding both products of the station's one order.  Derived by hand:
the first plan fetches the shelf (W, S, lift at 3), brings it (N, W) and delivers at 6, then
takes it two moves off the station (a first plan never parks on a station): 8.  Routed again
alone, every other track known, the robot may stay on the station: 6, better.  Routed alone
once more it finds 6 again: as good, not better; the new track is kept when plateaus are
allowed, and the old one comes back when they are not.
"""

from __future__ import annotations

from test_anytime_readings import one_shelf

from asprilo.bounds import Floor
from asprilo.domain import Domain
from asprilo.encodings.anytime import improve
from asprilo.encodings.anytime.grid import Grid
from asprilo.encodings.anytime.improve import Improver
from asprilo.encodings.anytime.prioritized import first_tracks
from asprilo.encodings.anytime.reservations import Reservations
from asprilo.encodings.anytime.router import Router
from asprilo.encodings.anytime.work import Work


def _improver() -> Improver:
    instance = one_shelf()
    grid = Grid(Floor(instance.cells))
    work = Work(instance, Domain.C, grid, 6)
    assert work.assign(1.0, lambda: False)
    table = Reservations(instance, work.homes)
    router = Router(grid, table)
    assert first_tracks(work, router, table, lambda: False) is not None
    return Improver(work, router, table)


def _again(improver: Improver) -> str | None:
    return improver._repair([1], 0, False, lambda: False, improver.work.save())


def test_a_plan_as_good_is_kept_on_a_plateau():
    improver = _improver()
    assert improver.score() == (8, 8)
    assert _again(improver) == "better" and improver.score() == (6, 6)
    before = improver.table.tracks[1]
    assert _again(improver) == "same" and improver.score() == (6, 6)
    assert improver.table.tracks[1] is not before


def test_without_plateaus_the_old_track_comes_back(monkeypatch):
    monkeypatch.setattr(improve, "PLATEAU", False)
    improver = _improver()
    assert _again(improver) == "better"
    before = improver.table.tracks[1]
    assert _again(improver) is None and improver.table.tracks[1] is before
