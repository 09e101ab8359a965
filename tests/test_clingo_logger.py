"""clingo's logger callback: a stop request (SIGTERM made Ctrl-C) that arrives while clingo
is inside it cannot leave clingo's nothrow scope (the process would abort with "PANIC:
exception in nothrow scope", as a generation stopped at the wrong moment once did); it is
raised again once out of it, and any other exception is not a stop."""

from __future__ import annotations

import pytest

from asprilo.clingo_logger import stop_again


def test_a_stop_inside_the_logger_is_raised_again_out_of_it():
    with pytest.raises(KeyboardInterrupt):
        assert stop_again(KeyboardInterrupt)
        for _ in range(10_000):  # the next Python steps run the SIGINT handler
            pass


def test_another_exception_is_not_a_stop():
    assert not stop_again(ValueError)
