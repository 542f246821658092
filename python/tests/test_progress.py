"""make_lods()'s progress callable (cancel, errors) and the GIL released while it works."""

import threading
import time

import pytest

import openmeshskinned as oms


def test_progress_sees_the_stages_in_order(wuson):
    seen = []
    oms.make_lods(wuson, ratios=[0.5], poses=2, progress=lambda stage, f: seen.append((stage, f)))
    stages = [s for s, _ in seen]
    assert stages[0] == "choosing the example poses"
    for stage in ("decimating", "fitting", "measuring the held-out error"):
        assert stage in stages
    assert all(0.0 <= f <= 1.0 for _, f in seen)
    decimating = [f for s, f in seen if s == "decimating"]
    assert len(decimating) > 2 and decimating == sorted(decimating)


def test_returning_false_cancels(wuson):
    calls = []

    def stop_while_decimating(stage, fraction):
        calls.append(stage)
        return not (stage == "decimating" and fraction > 0.2)

    with pytest.raises(oms.Cancelled):
        oms.make_lods(wuson, ratios=[0.1], poses=2, progress=stop_while_decimating)
    assert calls[-1] == "decimating" and "fitting" not in calls


def test_an_exception_in_the_callable_ends_the_call_with_it(wuson):
    def fail(stage, fraction):
        if stage == "decimating":
            raise ZeroDivisionError("from the callback")

    with pytest.raises(ZeroDivisionError, match="from the callback"):
        oms.make_lods(wuson, ratios=[0.5], poses=2, progress=fail)


def test_evaluate_can_be_cancelled(wuson, wuson_lods):
    with pytest.raises(oms.Cancelled):
        oms.evaluate(wuson, wuson_lods[0].mesh, progress=lambda s, f: False, poses=3)


def test_another_python_thread_runs_while_make_lods_works(wuson):
    stamps, stop = [], threading.Event()

    def tick():
        while not stop.is_set():
            stamps.append(time.monotonic())
            for _ in range(2000):
                pass

    t = threading.Thread(target=tick)
    t.start()
    try:
        while not stamps:
            time.sleep(0.001)
        start = time.monotonic()
        oms.make_lods(wuson, ratios=[0.25], poses=3)
        end = time.monotonic()
    finally:
        stop.set()
        t.join()
    # Holding the GIL for the whole call would leave no stamp in its middle half.
    lo, hi = start + 0.25 * (end - start), start + 0.75 * (end - start)
    assert end - start > 0.05
    assert sum(lo <= s <= hi for s in stamps) > 10
