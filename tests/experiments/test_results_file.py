"""The results CSV of the runner: append, reopen, and repair of a torn last line."""

import io

import pytest

from harvest.experiments import results


def _row(seed, method="fov", **kw):
    r = {c: None for c in results.COLUMNS}
    r.update(
        distribution="uniform",
        alpha=1.0,
        seed=seed,
        method=method,
        n_left=50,
        n_right=50,
        stops=9,
        makespan_s=123.5,
        throughput_fruit_per_s=0.81,
        runtime_s=0.02,
        status="heuristic",
        plan="plans/x.json",
        finished_utc="2026-01-01T00:00:00Z",
        error="",
    )
    r.update(kw)
    return r


def test_rows_survive_reopen_with_types(tmp_path):
    p = str(tmp_path / "results.csv")
    f = results.ResultsFile(p)
    f.append(_row(0))
    f.append(_row(0, "milp", gap=0.0125, error='a "quoted", comma'))
    again = results.ResultsFile(p)
    assert set(again.done) == {("uniform", 1.0, 0, "fov"), ("uniform", 1.0, 0, "milp")}
    rows = results.read(p)
    assert rows[1]["gap"] == pytest.approx(0.0125) and rows[0]["gap"] is None
    assert rows[1]["error"] == 'a "quoted", comma' and rows[0]["stops"] == 9


def test_torn_last_line_is_cut_and_reported(tmp_path):
    p = str(tmp_path / "results.csv")
    f = results.ResultsFile(p)
    f.append(_row(0))
    f.append(_row(1))
    with open(p, "a") as fh:
        fh.write("uniform,1.0,2,fov,50,50,9,12")  # a kill in the middle of a write
    log = io.StringIO()
    again = results.ResultsFile(p, log=log)
    assert "dropping an unfinished last line" in log.getvalue()
    assert set(k[2] for k in again.done) == {0, 1}
    assert open(p).read().endswith("\n")
    again.append(_row(2))
    assert [r["seed"] for r in results.read(p)] == [0, 1, 2]


def test_foreign_header_is_refused(tmp_path):
    p = tmp_path / "results.csv"
    p.write_text("a,b,c\n1,2,3\n")
    with pytest.raises(results.ResultsError, match="header is not this runner's columns"):
        results.ResultsFile(str(p))


def test_duplicate_keys_are_refused(tmp_path):
    p = str(tmp_path / "results.csv")
    f = results.ResultsFile(p)
    f.append(_row(0))
    with open(p) as fh:
        last = fh.read().splitlines()[-1]
    with open(p, "a") as fh:
        fh.write(last + "\n")
    with pytest.raises(results.ResultsError, match="appears twice"):
        results.ResultsFile(p)


def test_failed_rows_can_be_dropped_for_a_retry(tmp_path):
    p = str(tmp_path / "results.csv")
    f = results.ResultsFile(p)
    f.append(_row(0))
    f.append(_row(1, status="error", error="exit 1: solver crashed", makespan_s=None))
    f.append(_row(2))
    assert f.drop_errors() == 1
    assert [r["seed"] for r in results.read(p)] == [0, 2]
    assert ("uniform", 1.0, 1, "fov") not in f.done
    assert results.ResultsFile(p).drop_errors() == 0
