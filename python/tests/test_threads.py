"""Heavy calls release the GIL: another Python thread runs while a fit is solved."""

import threading
import time

import rbfsurf
from conftest import sphere_points


def test_a_python_thread_makes_progress_during_a_long_fit():
    p = sphere_points(3500)  # 7000 rows, solved densely: about a second
    ticks = []
    stop = threading.Event()

    def count():
        while not stop.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.001)

    worker = threading.Thread(target=count)
    worker.start()
    time.sleep(0.05)
    start = time.perf_counter()
    model = rbfsurf.from_oriented_points(p, p, method="dense")
    end = time.perf_counter()
    stop.set()
    worker.join()
    assert model.report["rows"] == 7000
    assert end - start > 0.3, "the fit must be long enough to tell"
    # Ticks well inside the fit's window: the thread ran while the fit held no GIL.
    inside = [t for t in ticks if start + 0.1 < t < end - 0.1]
    assert len(inside) > 0.2 * (end - start - 0.2) / 0.0015, (len(inside), end - start)
