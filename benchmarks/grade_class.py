"""The grader on a class of 30 generated submissions (issue 47, item 3): is every verdict right?

Ten submissions are correct domain M encodings (two styles, tests/students/m-cells-base.lp and
m-moves-base.lp, with their rules written in different but equivalent ways); twenty forget or
break one classic rule each: the swap (edge) constraint, the vertex constraint, or (moves
style) that a move stays on the floor -- dropped, or altered so that it no longer holds.
Each submission is graded by ``asprilo grade FILE --domain m --json`` in a fresh process (the
whole M ladder and its probes, clingo's default configuration); its verdict is the set of
rules the probes found forgotten, and it is right when that is exactly the rule the
submission was made without (none for a correct one).  Prints a line per submission, the
count of right verdicts and the total time.

Run: python benchmarks/grade_class.py [--keep DIR] [--options "--configuration=frumpy ..."]
"""

from __future__ import annotations

import argparse
import json
import shlex
import subprocess
import sys
import tempfile
import time
from pathlib import Path

STUDENTS = Path(__file__).resolve().parent.parent / "tests" / "students"
CELLS = f'#include "{STUDENTS / "m-cells-base.lp"}".\n'
MOVES = f'#include "{STUDENTS / "m-moves-base.lp"}".\n'

SWAP_CELLS = ":- moveto(B,C,T), moveto(C,B,T), B < C."
SWAP_CELLS_PAIRS = ":- position(R1,B,T-1), position(R1,C,T), position(R2,C,T-1), position(R2,B,T), R1 != R2, B != C."
VERTEX_CELLS = ":- node(C), time(T), #count{ R : position(R,C,T) } > 1."
VERTEX_PAIRS = ":- position(R1,C,T), position(R2,C,T), R1 < R2."
FLOOR_MOVES = ":- position(R,C,T), not node(C)."
FLOOR_MOVES_BY_MOVE = ":- move(R,(DX,DY),T), position(R,(X,Y),T-1), not node((X+DX,Y+DY))."
#: the moves style has its swap and vertex rules in its base file: a student's copy without them
MOVES_OWN = """#const horizon = 0.
time(1..horizon).
node(C)  :- init(object(node,_),value(at,C)).
robot(R) :- init(object(robot,R),value(at,_)).
goal(C)  :- init(object(order,_),value(line,(P,_))), init(object(product,P),value(on,(S,_))),
            init(object(shelf,S),value(at,C)).
direction((1,0);(-1,0);(0,1);(0,-1)).
position(R,C,0) :- init(object(robot,R),value(at,C)).
{ move(R,D,T) : direction(D) } 1 :- robot(R), time(T).
position(R,(X+DX,Y+DY),T) :- position(R,(X,Y),T-1), move(R,(DX,DY),T).
position(R,C,T) :- position(R,C,T-1), time(T), not move(R,_,T).
:- goal(C), not position(_,C,horizon).
#show occurs(object(robot,R),action(move,D),T) : move(R,D,T).
"""
SWAP_MOVES = ":- position(R1,C,T-1), position(R1,D,T), position(R2,D,T-1), position(R2,C,T), R1 != R2, C != D."


def submissions() -> list[tuple[str, str, str]]:
    """(name, program text, the rule it lacks or "" for a correct one): 10 correct, 20 not."""
    correct = [
        ("cells", CELLS + SWAP_CELLS + "\n" + VERTEX_CELLS),
        ("cells-reordered", CELLS + VERTEX_CELLS + "\n" + SWAP_CELLS),
        ("cells-pairs", CELLS + SWAP_CELLS + "\n" + VERTEX_PAIRS),
        ("cells-swap-pairs", CELLS + SWAP_CELLS_PAIRS + "\n" + VERTEX_CELLS),
        ("cells-redundant", CELLS + SWAP_CELLS + "\n" + VERTEX_CELLS + "\n:- position(R,C,T), not node(C)."),
        ("moves", MOVES + FLOOR_MOVES),
        ("moves-by-move", MOVES + FLOOR_MOVES_BY_MOVE),
        ("moves-own", MOVES_OWN + SWAP_MOVES + "\n" + VERTEX_PAIRS + "\n" + FLOOR_MOVES),
        ("moves-own-count", MOVES_OWN + SWAP_MOVES + "\n" + VERTEX_CELLS.replace("node(C), ", "node(C), ") + "\n"
         + FLOOR_MOVES),
        ("moves-own-both-floor", MOVES_OWN + VERTEX_PAIRS + "\n" + SWAP_MOVES + "\n" + FLOOR_MOVES + "\n"
         + FLOOR_MOVES_BY_MOVE),
    ]
    broken = [
        ("cells-no-swap", CELLS + VERTEX_CELLS, "swap"),
        ("cells-pairs-no-swap", CELLS + VERTEX_PAIRS, "swap"),
        ("cells-swap-same-cell", CELLS + SWAP_CELLS.replace("B < C", "B = C") + "\n" + VERTEX_CELLS, "swap"),
        ("cells-swap-one-way", CELLS + ":- moveto(B,C,T), moveto(C,B,T+1), B < C.\n" + VERTEX_CELLS, "swap"),
        ("cells-no-vertex", CELLS + SWAP_CELLS, "vertex"),
        ("cells-swap-pairs-no-vertex", CELLS + SWAP_CELLS_PAIRS, "vertex"),
        ("cells-vertex-over-two", CELLS + SWAP_CELLS + "\n" + VERTEX_CELLS.replace("> 1", "> 2"), "vertex"),
        ("cells-vertex-same-robot", CELLS + SWAP_CELLS + "\n" + VERTEX_PAIRS.replace("R1 < R2", "R1 = R2, R1 < R2"),
         "vertex"),
        ("moves-no-floor", MOVES, "off-floor"),
        ("moves-floor-at-start", MOVES + ":- position(R,C,0), not node(C).", "off-floor"),
        ("moves-floor-at-horizon", MOVES + ":- position(R,C,horizon), not node(C).", "off-floor"),
        ("moves-floor-x-only", MOVES + ":- position(R,(X,Y),T), X > 99.", "off-floor"),
        ("moves-own-no-swap", MOVES_OWN + VERTEX_PAIRS + "\n" + FLOOR_MOVES, "swap"),
        ("moves-own-no-swap-count", MOVES_OWN + VERTEX_CELLS + "\n" + FLOOR_MOVES, "swap"),
        ("moves-own-swap-same-robot", MOVES_OWN + SWAP_MOVES.replace("R1 != R2", "R1 = R2") + "\n" + VERTEX_PAIRS
         + "\n" + FLOOR_MOVES, "swap"),
        ("moves-own-no-vertex", MOVES_OWN + SWAP_MOVES + "\n" + FLOOR_MOVES, "vertex"),
        ("moves-own-vertex-at-start", MOVES_OWN + SWAP_MOVES + "\n:- position(R1,C,0), position(R2,C,0), R1 < R2.\n"
         + FLOOR_MOVES, "vertex"),
        ("moves-own-vertex-over-two", MOVES_OWN + SWAP_MOVES + "\n" + VERTEX_CELLS.replace("> 1", "> 2") + "\n"
         + FLOOR_MOVES, "vertex"),
        ("moves-own-no-floor", MOVES_OWN + SWAP_MOVES + "\n" + VERTEX_PAIRS, "off-floor"),
        ("moves-own-floor-at-start", MOVES_OWN + SWAP_MOVES + "\n" + VERTEX_PAIRS
         + "\n:- position(R,C,0), not node(C).", "off-floor"),
    ]
    return [(name, text, "") for name, text in correct] + broken


def grade(path: Path, options: list[str]) -> dict:
    """``asprilo grade PATH --domain m --json`` in a fresh process: its report."""
    command = [sys.executable, "-m", "asprilo.cli", "grade", str(path), "--domain", "m", "--json", "-q", *options]
    done = subprocess.run(command, capture_output=True, text=True, check=False)
    if done.returncode == 2 or not done.stdout:
        raise SystemExit(f"{path.name}: bad input: {done.stderr.strip()}")
    return json.loads(done.stdout)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--keep", metavar="DIR", help="write the submissions to DIR (default: a temporary folder)")
    parser.add_argument("--options", default="", help="clingo options for every grade, e.g. '--seed=3 --rand-freq=1'")
    args = parser.parse_args()
    folder = Path(args.keep) if args.keep else Path(tempfile.mkdtemp(prefix="grade-class-"))
    folder.mkdir(parents=True, exist_ok=True)
    options = shlex.split(args.options)
    started = time.perf_counter()
    right = 0
    made = submissions()
    for name, text, lacks in made:
        path = folder / f"{name}.lp"
        path.write_text(f"% {name}: generated by benchmarks/grade_class.py\n{text}\n")
        began = time.perf_counter()
        report = grade(path, options)
        forgot = sorted(entry["name"] for entry in report["probes"] if entry["forgot"])
        summary = report["summary"]
        verdict = f"forgot {', '.join(forgot)}" if forgot else "clean"
        ok = forgot == ([lacks] if lacks else []) and summary["probes"]["undecided"] == 0
        right += ok
        print(f"{name:<28} {'lacks ' + lacks if lacks else 'correct':<16} {verdict:<22} "
              f"{summary['valid']:>2}/{summary['instances']} valid  {time.perf_counter() - began:5.1f} s  "
              f"{'right' if ok else 'WRONG'}", flush=True)
    print(f"{right}/{len(made)} verdicts right; {time.perf_counter() - started:.1f} s in all")
    return 0 if right == len(made) else 1


if __name__ == "__main__":
    sys.exit(main())
