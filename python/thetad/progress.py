"""progress=True: a tqdm bar (tqdm.auto: a widget in Jupyter, text in a terminal) when tqdm is
installed (Debian's python3-tqdm), plain lines on stderr otherwise."""

import sys


class ProgressBar:
    """A callable progress(done, total) that opens a bar per task: a task starts when `done` falls
    back or `total` changes (a benchmark's recording, then its timing; an optimum's flights, then
    Ipopt's iterations), and closes when done reaches total."""

    def __init__(self, description=""):
        self.description = description
        self.total = None
        self.done = 0.0
        self.bar = None
        self.shown = -1  # the last tenth printed without tqdm
        try:
            from tqdm.auto import tqdm
            self.tqdm = tqdm
        except ImportError:
            self.tqdm = None

    def __call__(self, done, total):
        if self.total is None or total != self.total or done < self.done:
            self.close()
            self.total = total
            if self.tqdm is not None:
                self.bar = self.tqdm(total=total, desc=self.description, unit_scale=True, leave=False)
        if self.bar is not None:
            self.bar.update(done - self.done)
        elif int(10 * done / total if total else 10) > self.shown:
            self.shown = int(10 * done / total if total else 10)
            print(f"{self.description}{done:g} of {total:g} ({100.0 * done / total if total else 100:.0f} %)",
                  file=sys.stderr, flush=True)
        self.done = done
        if done >= total:
            self.close()

    def close(self):
        if self.bar is not None:
            self.bar.close()
        self.bar, self.total, self.done, self.shown = None, None, 0.0, -1


def progress_bar(description=""):
    """What progress=True passes: progress(done, total) drawing a bar (or plain lines)."""
    return ProgressBar(description)
