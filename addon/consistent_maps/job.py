"""A computation running in a worker thread, polled from the main thread.

The native library releases the GIL while it works, so Blender's interface
keeps running; the worker only touches the copied-out arrays. Cancellation is
a flag the progress callback reports back to the library. One job at a time.
"""
import threading

from . import api

_current = None


class Job:
    def __init__(self, tasks, names, options):
        self.tasks = tasks
        self.fraction = 0.0
        self.stage = "starting"
        self.error = None
        self._outcome = None
        self._cancel_requested = False
        self._thread = threading.Thread(target=self._work, args=(names, options), name="consistent_maps",
                                        daemon=True)

    def _progress(self, fraction, stage):
        self.fraction, self.stage = fraction, stage
        return not self._cancel_requested

    def _work(self, names, options):
        try:
            self._outcome = api.run(self.tasks, names, progress=self._progress, **options)
        except api.Cancelled:
            pass  # only a cancel request stops it: `cancelled` says so
        except Exception as e:  # reported to the user by the operator, on the main thread
            self.error = e

    def start(self):
        self._thread.start()

    def cancel(self):
        self._cancel_requested = True

    # A cancel counts even when it comes after the last progress report, or
    # after the computation ended but before its result was applied: the
    # user asked for nothing to change, so the result is dropped.
    @property
    def cancelled(self):
        return self._cancel_requested

    @property
    def outcome(self):
        return None if self._cancel_requested else self._outcome

    @property
    def done(self):
        return not self._thread.is_alive()


def start(tasks, names, options):
    global _current
    if _current is not None:
        raise RuntimeError("a computation is already running")
    _current = Job(tasks, names, options)
    _current.start()
    return _current


def current():
    """The job started and not yet finished, or None."""
    return _current


def finish():
    """Forgets the current job (after its results were applied or dropped)."""
    global _current
    _current = None
