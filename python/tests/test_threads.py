"""Long solves release the interpreter lock: another Python thread keeps running meanwhile."""

import threading
import time

import ringcontact as rc


def test_a_long_solve_leaves_other_threads_running():
    done = threading.Event()
    answer = {}

    def work():
        started = time.perf_counter()
        answer["result"] = rc.solve("sphere", depth=[1.0, 1.5], method="grid-bem", grid=256)
        answer["seconds"] = time.perf_counter() - started
        done.set()

    worker = threading.Thread(target=work)
    ticks = []
    worker.start()
    while not done.is_set():
        ticks.append(time.perf_counter())
        time.sleep(0.005)
    worker.join()
    # The solve takes seconds; had it held the lock, this thread would have stood still for
    # all of it. Allow a generous 0.5 s between two of its ticks on a loaded machine.
    assert answer["seconds"] > 1.0
    gaps = [b - a for a, b in zip(ticks, ticks[1:])]
    assert len(ticks) > 20
    assert max(gaps) < 0.5, f"the main thread stood still for {max(gaps):.2f} s"
    assert len(answer["result"]["force"]) == 2
