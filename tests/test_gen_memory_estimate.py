"""gen refuses, before grounding anything, a floor that would take more than ``gen-mb`` to
make (issue 46, item 7): ``gen -x 1000 -y 1000 -r 1``, exactly ``gen-cells``, ran 40 s and
failed on ``gen-mb``.  The estimate: 60 MB, and per cell 1.4 kB for the floor and for each
stage that places objects on it, 7 kB more for -R (measured, ``benchmarks/limits_edges.py``)."""

from __future__ import annotations

import pytest

from asprilo.errors import InputError
from asprilo.generator.config import GeneratorConfig
from asprilo.generator.plan import estimated_mb, make_plan
from asprilo.limits import Limits, using


def test_the_issues_edge_is_refused_up_front(capsys, tmp_path):
    from asprilo.cli import main
    code = main(["gen", "-x", "1000", "-y", "1000", "-r", "1", "-d", str(tmp_path / "out"),
                 "--limit", "gen-cells=1000000"])  # beyond gen-cells since it was lowered to 700,000
    # 60 + 1,000,000 x 2 x 1.4 / 1024 = 2,794.4
    assert (code, capsys.readouterr().err) == (2, "error: a floor of 1,000x1,000 cells takes about 2,794 MB to "
                                                  "generate, beyond the limit gen-mb=2,048 (raise it with "
                                                  "--limit gen-mb=N)\n")
    assert not (tmp_path / "out").exists()


def test_the_estimate_counts_the_floor_the_placing_stages_and_reachability():
    one_robot = make_plan(GeneratorConfig(width=100, height=100, robots=1))
    assert estimated_mb(one_robot) == 87  # 60 + 10,000 x 2 x 1.4 / 1024 = 87.34
    everything = GeneratorConfig(width=100, height=100, stations=1, robots=1, shelves=1, products=1, orders=1,
                                 reachable=True)
    assert estimated_mb(make_plan(everything)) == 183  # 60 + 10,000 x (4 x 1.4 + 7) / 1024 = 183.05
    with using(Limits(gen_mb=100)):
        assert make_plan(GeneratorConfig(width=100, height=100, robots=1)).robots == 1
        with pytest.raises(InputError, match=r"^a floor of 100x100 cells with -R takes about 183 MB to generate, "
                                             r"beyond the limit gen-mb=100 \(raise it with --limit gen-mb=N\)$"):
            make_plan(everything)
