"""Progress of long per-p phases (issue 13, item 5): the p reached and an estimate of the time left."""
import io

from derivations.core.options import BuildOptions
from derivations.output.pipeline import Progress, derive, time_left


class Terminal(io.StringIO):
    def isatty(self):
        return True


def test_time_left_extrapolates_the_growth():
    assert time_left(1.0, 1, 10) is None                      # nothing to go on yet
    assert abs(time_left(2.0, 10, 20) - 2.0) < 1e-12          # linear without history: as long again
    # cumulative time ~ i^3 (per-p cost ~ p^2): 1 s at 10 of 20 with 1/8 s at 5 -> 8 s in all, 7 s left
    assert abs(time_left(1.0, 10, 20, elapsed_at_half=0.125) - 7.0) < 1e-9


def test_terminal_shows_p_and_time_left():
    stream = Terminal()
    derive(BuildOptions(pmax=9), ["residue"], Progress(stream=stream))
    text = stream.getvalue()
    assert "Frobenius logarithms at t0: p = 9 (" in text and "s left" in text
    assert text.endswith("\n") and "[4/4] residue:" in text.splitlines()[-1]


def test_pipe_gets_one_line_per_derivation():
    stream = io.StringIO()
    derive(BuildOptions(pmax=5), ["residue"], Progress(stream=stream))
    lines = stream.getvalue().splitlines()
    assert [line.split(":")[0] for line in lines] == ["[1/4] model", "[2/4] special_case", "[3/4] kovalevskaya",
                                                      "[4/4] residue"]
    assert "\r" not in stream.getvalue() and "left" not in stream.getvalue()


def test_sweep_estimate_excludes_the_workers_start_up(monkeypatch):
    """A 16-chunk sweep whose first chunk finished after 2 s of worker start-up and the rest every 0.05 s:
    the time left after the third chunk is 13 x 0.05 s; the old estimate (elapsed / done) said 9 s."""
    from suslov import executor

    clock = iter([0.0, 2.0, 2.05, 2.10])
    monkeypatch.setattr(executor.time, "perf_counter", lambda: next(clock))
    progress = executor._Progress(16, None)
    for _ in range(3):
        progress.tick()
    true_left = 13 * 0.05
    assert true_left / 2 <= progress.left(2.10) <= 2 * true_left
