"""`asprilo demo`: the whole tool chain on a small warehouse."""

from __future__ import annotations

import os

from asprilo.checker import check
from asprilo.cli import main
from asprilo.reader import read_instance, read_plan


def test_demo_generates_solves_checks_and_renders(tmp_path, capsys):
    os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
    assert main(["demo", "-o", str(tmp_path)]) == 0
    out = capsys.readouterr().out.splitlines()
    assert out[0].startswith(f"1. generated  {tmp_path}/x11_y6_n66_r3_s8_ps2_pr4_u16_o2_N001.lp: 11x6 floor, "
                             "3 robots, 8 shelves, 2 picking stations, 2 orders")
    assert any(line.startswith(f"2. solved     {tmp_path}/plan.lp: horizon ") and "(proven minimal)" in line
               for line in out)
    assert "3. checked    the plan is valid in domain A" in out
    instance = read_instance(tmp_path / "x11_y6_n66_r3_s8_ps2_pr4_u16_o2_N001.lp")
    assert check(instance, read_plan(tmp_path / "plan.lp")).valid
    assert (tmp_path / "final.png").read_bytes()[:4] == b"\x89PNG"
    assert (tmp_path / "plan.gif").read_bytes()[:6] == b"GIF89a"


def test_demo_in_domain_m_without_pictures(tmp_path, capsys):
    assert main(["demo", "--domain", "m", "--no-pictures", "-o", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert "3. checked    the plan is valid in domain M" in out
    assert not (tmp_path / "final.png").exists()
