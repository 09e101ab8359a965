"""The LaTeX failed-runs table fits the page and the report's key names files relative to the
suite (issue 47, item 7).  No TeX is needed: the column widths are shares of ``\\linewidth``
that add up to 1, less exactly the space between the columns, so the table is as wide as
the line; the expected text is written by hand."""

from __future__ import annotations

import re
from fractions import Fraction

from asprilo.bench import report
from asprilo.bench.cli import _described
from asprilo.bench.suite import load_suite


def failed_run(instance: str, encoding: str, status: str, error: str) -> dict:
    return {"key": f"paper/{instance}/M/{encoding}", "set": "paper", "instance": instance, "robots": 2,
            "domain": "m", "label": "M", "encoding": encoding, "assign": False, "status": status,
            "time": 1.0, "time_limit": 60.0, "horizon": 6, "error": error}


def test_the_failed_runs_table_wraps_its_columns_to_the_line():
    records = [failed_run("paper-m/1x2x4/x11_y6_n66_r2_s16_ps1_pr16_u16_o2_N001.lp", "mine", "invalid",
                          "the plan breaks the rules: robot 1 leaves the floor")]
    assert report.failed_runs(records).latex() == r"""\begin{table}[tbp]
  \centering
  \caption{Failed runs (1; not in the averages, not in PAR): domain encoding, set instance, why}
  \label{tab:failed}
  \footnotesize
  \begin{tabular}{@{}p{\dimexpr 0.17\linewidth-1\tabcolsep\relax}p{\dimexpr 0.28\linewidth-2\tabcolsep\relax}p{\dimexpr 0.13\linewidth-2\tabcolsep\relax}p{\dimexpr 0.42\linewidth-1\tabcolsep\relax}@{}}
    \toprule
    run & instance & outcome & reason \tabularnewline
    \midrule
    \raggedright M mine & \raggedright paper paper-m/\allowbreak{}1x2x4/\allowbreak{}x11\_\allowbreak{}y6\_\allowbreak{}n66\_\allowbreak{}r2\_\allowbreak{}s16\_\allowbreak{}ps1\_\allowbreak{}pr16\_\allowbreak{}u16\_\allowbreak{}o2\_\allowbreak{}N001.lp & \raggedright invalid plan & \raggedright the plan breaks the rules: robot 1 leaves the floor \tabularnewline
    \bottomrule
  \end{tabular}
\end{table}
"""  # noqa: E501 - the exact text


def test_the_columns_add_up_to_the_line():
    """Shares of the line add up to 1; the spaces taken off (1 at an outer column, 2 at an inner
    one) are the 3 inner gaps of 2 \\tabcolsep each, and the outer edges have none (@{})."""
    spec = report._wrapped_columns(report.FAILED_WIDTHS)
    assert spec.startswith("@{}") and spec.endswith("@{}")
    columns = re.findall(r"p\{\\dimexpr ([\d.]+)\\linewidth-(\d)\\tabcolsep\\relax\}", spec)
    assert len(columns) == 4
    assert sum(Fraction(share) for share, _gap in columns) == 1
    assert sum(int(gap) for _share, gap in columns) == 3 * 2


def test_the_key_names_the_suites_own_encodings_relative_to_it(tmp_path):
    (tmp_path / "enc").mkdir()
    (tmp_path / "enc" / "my_enc.lp").write_text("#const horizon = 1.\n#show occurs/3.\n")
    (tmp_path / "enc" / "first.lp").write_text("#show assign/2.\n")
    (tmp_path / "x.lp").write_text("init(object(node,1),value(at,(1,1))).\n")
    suite = tmp_path / "suite.yml"
    suite.write_text("name: t\nencodings:\n  mine: {files: [enc/my_enc.lp], stage: [enc/first.lp]}\n"
                     "instances:\n  tiny: {files: [x.lp]}\nruns:\n  - {domain: m, encoding: mine}\n")
    described = _described(load_suite(suite))
    assert described == {"mine": "enc/my_enc.lp; single-shot with a horizon constant; first stage enc/first.lp"}
    key = report.summary([failed_run("x.lp", "mine", "error", "no plan")], described=described).latex()
    assert "mine: enc/my\\_enc.lp; single-shot with a horizon constant; first stage enc/first.lp" in key
    assert str(tmp_path) not in key
