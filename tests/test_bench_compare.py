"""The bench report compares encodings for a paper: PAR2/PAR10, a key for every mark, LaTeX
tables, cactus and scatter plots in PNG/PDF/SVG; the options of ``asprilo bench report``.

Everything here works on small synthetic results (no solving); the expected numbers are
worked out by hand in the tests.
"""

from __future__ import annotations

import re

import pytest

from asprilo.bench import plots, report
from asprilo.bench.results import append_result
from asprilo.cli import main


def run(instance, encoding="plain", status="solved", time=1.0, label="M", set_="small", robots=2, horizon=6,
        error=None):
    record = {"key": f"{set_}/{instance}/{label}/{encoding}", "set": set_, "instance": instance, "robots": robots,
              "domain": label.split("_")[0].lower(), "label": label, "encoding": encoding,
              "assign": label.endswith("_a"), "status": status, "time": time, "time_limit": 60.0,
              "horizon": horizon}
    return record if error is None else {**record, "error": error}


#: M: plain solves i1 (2 s) and i2 (4 s), times out on i3, its plan of i4 is invalid, i5 fails;
#: mine runs out of memory on i1, has no makespan for i2 and solves i3, i4, i5 (1, 0.5, 3 s)
PAR_RUNS = [run("i1", time=2.0), run("i2", time=4.0), run("i3", status="timeout", time=60.0),
            run("i4", status="invalid", time=3.0, error="the plan breaks the rules: robot 1 leaves the floor"),
            run("i5", status="error", time=1.0, error="the run's process ended without a result (exit status 3)"),
            run("i1", "mine", "memout", 60.0), run("i2", "mine", "no-makespan", 60.0, horizon=None),
            run("i3", "mine", time=1.0), run("i4", "mine", time=0.5), run("i5", "mine", time=3.0)]


def test_par2_and_par10_count_each_run_out_of_limits_at_k_times_the_limit():
    plain = [r for r in PAR_RUNS if r["encoding"] == "plain"]
    mine = [r for r in PAR_RUNS if r["encoding"] == "mine"]
    # plain: the solved 2 and 4 s, the time-out at 2 (10) x 60 s; the invalid plan and the error are not scored
    assert report.par(plain, 2) == pytest.approx((2 + 4 + 2 * 60) / 3)  # 42.0
    assert report.par(plain, 10) == pytest.approx((2 + 4 + 10 * 60) / 3)  # 202.0
    # mine: the mem-out and the unknown makespan are out of limits
    assert report.par(mine, 2) == pytest.approx((2 * 60 + 2 * 60 + 1 + 0.5 + 3) / 5)  # 48.9
    assert report.par(mine, 10) == pytest.approx((10 * 60 + 10 * 60 + 1 + 0.5 + 3) / 5)  # 240.9
    assert report.par([run("i4", status="invalid")], 2) is None
    table = report.solved_table(PAR_RUNS)
    assert table.text().splitlines()[2:6] == [
        "domain  encoding  solved  out of limits  invalid  errors  PAR2  PAR10",
        "------  --------  ------  -------------  -------  ------  ----  -----",
        "M       plain     2/5     1              1        1       42.0  202.0",
        "        mine      3/5     2              0        0       48.9  240.9",
    ]
    assert " ".join(table.text().split("\n\n")[2].split()) == (
        "Key: solved runs with a plan that passes the checker, of all runs "
        "out of limits time-outs, mem-outs and runs without a known minimal makespan: the unsolved runs of PAR "
        "invalid plans the checker rejected; errors: runs that failed; neither is in PAR "
        "PAR2, PAR10 penalised average run time in seconds over the solved runs and the unsolved runs, each "
        "unsolved run counted at 2 (10) times the time limit (60 s)")


def test_failed_runs_are_not_averaged_in_and_are_listed_with_their_reasons():
    text = report.summary(PAR_RUNS).text()
    # plain: (2 + 4 + 60) / 3 = 22 over 3 timed runs, 1 out of limits; mine: (60 + 60 + 1 + 0.5 + 3) / 5 = 24.9
    assert text.splitlines()[4:6] == ["M       6.0       plain     22(1) !1 x1",
                                      "                  mine      25(2)*"]
    failed = report.failed_runs(PAR_RUNS)
    assert failed.text().splitlines() == [
        "Failed runs (2; not in the averages, not in PAR): domain encoding, set instance, why", "",
        "  M plain: small i4: invalid plan: the plan breaks the rules: robot 1 leaves the floor",
        "  M plain: small i5: error: the run's process ended without a result (exit status 3)"]


MARKS = {"!": "!N", "x": "xN", "*": "*", "-(0)": "-(0)"}


def test_every_mark_a_table_prints_is_in_its_key():
    records = [*PAR_RUNS, run("j1", "mine", "invalid", label="A", set_="large", horizon=9),
               run("j1", label="A", set_="large", horizon=9, robots=5)]
    for table in report.tables(records, ["small", "large"]):
        if table.name == "failed":
            continue
        marks = {mark for mark, _meaning in table.key}
        cells = [text for row in table.rows for text in row[2:]]
        printed = {"!" if re.search(r" !\d", text) else None for text in cells} \
            | {"x" if re.search(r" x\d", text) else None for text in cells} \
            | {"*" if text.endswith("*") else None for text in cells} \
            | {"-(0)" if text.startswith("-(0)") else None for text in cells} - {None}
        assert {MARKS[mark] for mark in printed - {None}} <= marks, table.name
        if any(text == "-" for text in cells):
            assert "-" in marks, table.name
        if any("/" in row[1] for row in table.rows if table.name != "solved"):
            assert "a/b" in marks, table.name


def test_the_latex_table_is_booktabs():
    records = [run("i1", time=2.0), run("i2", status="timeout", time=60.0, horizon=7),
               run("i1", "mine", time=1.0), run("i2", "mine", "invalid", 3.0, horizon=7),
               run("i1", label="M_a", time=5.0, horizon=8)]
    latex = report.summary(records, described={"mine": "enc/my_enc.lp; single-shot with a horizon constant"}).latex()
    assert latex == r"""\begin{table}[tbp]
  \centering
  \caption{Average run time in seconds (runs out of limits); runs out of limits count at the time limit, failed runs apart}
  \label{tab:summary}
  \begin{tabular}{lllr}
    \toprule
    domain & makespan & encoding & small \\
    \midrule
    M & 6.5 & plain & 31(1)* \\
     &  & mine & 1.0(0) x1 \\
    \addlinespace
    M\_a & 8.0 & plain & 5.0(0) \\
    \bottomrule
  \end{tabular}
  \par\smallskip\footnotesize
  Key. T(N): T: average run time in seconds over the solved runs and the runs out of limits, these at the time limit (60 s); N: how many ran out of limits (time-out, mem-out, or no known minimal makespan); xN: N plans the checker rejected: not in the average (why: under Failed runs); *: the best encoding of the domain in this column: fewest unsolved runs of any kind, then least average time (never one with an invalid plan); makespan: the average minimal makespan of the instances; - unknown; mine: enc/my\_enc.lp; single-shot with a horizon constant.
\end{table}
"""  # noqa: E501 - the exact text
    assert "|" not in latex and r"\hline" not in latex  # no vertical rules, booktabs rules only


def test_latex_special_characters_are_escaped():
    assert report.latex_text(r"50% of a_b & {c} #1 $x ~^\ ") == \
        r"50\% of a\_b \& \{c\} \#1 \$x \textasciitilde{}\textasciicircum{}\textbackslash{} "


# --- plots -------------------------------------------------------------------------------

MAGIC = {"png": b"\x89PNG\r\n\x1a\n", "pdf": b"%PDF-"}


def _kind(data: bytes) -> str:
    if data.startswith(MAGIC["png"]):
        return "png"
    if data.startswith(MAGIC["pdf"]):
        return "pdf"
    if data.lstrip().startswith(b"<?xml") and b"<svg" in data[:2000]:
        return "svg"
    return "?"


def _labelled(axis) -> list[str]:
    return [line.get_label() for line in axis.get_lines() if not line.get_label().startswith("_")]


COMPARED = [run(f"i{n}", encoding, status, time, label, robots=robots)
            for n, (encoding, status, time, label, robots) in enumerate([
                ("plain", "solved", 2.0, "M", 2), ("mine", "solved", 1.0, "M", 2),
                ("plain", "solved", 8.0, "M", 5), ("mine", "timeout", 60.0, "M", 5),
                ("plain", "solved", 3.0, "C", 8), ("mine", "solved", 30.0, "C", 8),
                ("plain", "solved", 1.0, "A", 2), ("dl", "solved", 2.0, "M", 2),
                ("plain", "solved", 4.0, "B", 5)])]
for _record, _pair in zip(COMPARED, [0, 0, 1, 1, 2, 2, 3, 0, 5], strict=True):
    _record["instance"] = f"i{_pair}"  # plain, mine (and dl) ran on the same instances
del _record, _pair


def test_plots_are_written_in_every_format(tmp_path):
    paths = plots.plot(COMPARED, tmp_path, formats=("png", "pdf", "svg"), pairs=[("plain", "mine")])
    names = ("cactus", "time-by-robots", "scatter-plain-mine")
    assert [path.name for path in paths] == [f"{name}.{kind}" for name in names for kind in ("png", "pdf", "svg")]
    for path in paths:
        data = path.read_bytes()
        assert len(data) > 1000 and _kind(data) == path.suffix[1:], path.name


def test_the_cactus_plot_has_a_panel_per_domain_on_one_log_axis():
    figure = plots.cactus_figure(COMPARED)
    panels = [axis for axis in figure.axes if axis.get_visible()]
    assert [axis.get_title() for axis in panels] == ["M", "C", "B", "A"]  # the paper's order
    assert len(figure.axes) == 6  # a grid of 2 x 3, two hidden
    assert [_labelled(axis) for axis in panels] == [["plain", "dl", "mine"], ["plain", "mine"], ["plain"], ["plain"]]
    assert all(axis.get_yscale() == "log" for axis in panels)
    assert all(panels[0].get_shared_y_axes().joined(panels[0], axis) for axis in panels[1:])
    solved = {line.get_label(): list(line.get_ydata()) for line in panels[0].get_lines()}
    assert solved["plain"] == [2.0, 8.0] and solved["mine"] == [1.0]  # solved runs only, sorted


def test_the_plot_by_robots_has_integer_robot_ticks():
    figure = plots.robots_figure(COMPARED)
    (axis,) = [axis for axis in figure.axes if axis.get_visible()]
    assert list(axis.get_xticks()) == [2, 5, 8]
    assert _labelled(axis) == ["M plain", "M dl", "M mine", "C plain", "C mine", "B plain", "A plain"]


def test_the_scatter_plot_marks_runs_out_of_limits_at_the_limit():
    records = [*COMPARED, run("i9", "plain", time=5.0), run("i9", "mine", "error", 1.0)]  # left out: a failure
    figure = plots.scatter_figure(records, "plain", "mine")
    panels = [axis for axis in figure.axes if axis.get_visible()]
    assert [axis.get_title() for axis in panels] == ["M (1 with a failed run left out)", "C"]
    m = panels[0]
    assert (m.get_xscale(), m.get_yscale(), m.get_xlabel(), m.get_ylabel()) == (
        "log", "log", "plain: time (s)", "mine: time (s)")
    diagonal = [line for line in m.get_lines() if list(line.get_xdata()) == list(line.get_ydata())]
    assert len(diagonal) == 1
    points = {collection.get_label(): collection.get_offsets().tolist() for collection in m.collections}
    assert points == {"both solved": [[2.0, 1.0]], "out of limits (at the limit)": [[8.0, 60.0]]}
    assert plots.scatter_figure(records, "plain", "nobody") is None


def test_the_default_scatter_plots_compare_the_first_encoding_with_every_other():
    assert plots.scatter_pairs(COMPARED) == [("plain", "dl"), ("plain", "mine")]
    assert plots.scatter_pairs([run("i1", "zeta"), run("i1", "alpha")]) == [("alpha", "zeta")]


# --- asprilo bench report's options ------------------------------------------------------

@pytest.fixture
def results(tmp_path):
    folder = tmp_path / "out"
    folder.mkdir()
    for record in COMPARED:
        append_result(folder, record)
    return folder


def test_the_report_writes_latex_and_pdf_and_png_by_default(results, capsys):
    assert main(["bench", "report", str(results)]) == 0
    written = sorted(path.name for path in (results / "report").iterdir())
    assert written == sorted(["summary.txt", "results.csv", "summary.tex", "solved.tex", "robots-small.tex",
                              *(f"{name}.{kind}" for name in ("cactus", "time-by-robots", "scatter-plain-dl",
                                                              "scatter-plain-mine") for kind in ("png", "pdf"))])
    assert (results / "report/summary.tex").read_text() == report.summary(COMPARED).latex()


def test_the_report_s_options_choose_formats_pairs_and_no_latex(results, capsys):
    assert main(["bench", "report", str(results), "--plots", "svg", "--scatter", "mine:dl", "--no-latex"]) == 0
    written = sorted(path.name for path in (results / "report").iterdir())
    assert written == ["cactus.svg", "results.csv", "scatter-mine-dl.svg", "summary.txt", "time-by-robots.svg"]
    assert main(["bench", "report", str(results), "--plots", "none", "--no-latex"]) == 0


@pytest.mark.parametrize("option, message", [
    (["--plots", "gif"], "argument --plots: 'gif': choose among png, pdf, svg (comma-separated), or none"),
    (["--scatter", "plain"], "argument --scatter: 'plain': expected ENCODING:ENCODING, e.g. plain:mine"),
])
def test_bad_report_options_are_refused(results, capsys, option, message):
    with pytest.raises(SystemExit) as exited:
        main(["bench", "report", str(results), *option])
    assert exited.value.code == 2
    assert capsys.readouterr().err.splitlines()[-1].endswith(f"error: {message}")


def test_a_scatter_of_an_encoding_without_runs_is_refused(results, capsys):
    assert main(["bench", "report", str(results), "--scatter", "plain:nope"]) == 2
    assert capsys.readouterr().err == (
        "error: --scatter plain:nope: no runs of encoding 'nope' in these results (encodings: plain, dl, mine)\n")
