"""The progress of ``Scene.render(progress=True)``: a tqdm bar when tqdm is installed
(terminals and notebooks alike), else one plain line per update on stderr."""

import sys
import time


class _Lines:
    def __init__(self, total: int, unit: str):
        self.total, self.unit, self.start = total, unit, time.monotonic()

    def __call__(self, done: int, total: int, passes: int) -> None:
        elapsed = time.monotonic() - self.start
        print(f"render: {done}/{total} {self.unit} ({passes} passes) after {elapsed:.1f} s",
              file=sys.stderr, flush=True)

    def close(self) -> None:
        pass


class _Tqdm:
    def __init__(self, bar):
        self.bar = bar

    def __call__(self, done: int, total: int, passes: int) -> None:
        self.bar.update(done - self.bar.n)
        self.bar.set_postfix_str(f"{passes} passes", refresh=False)

    def close(self) -> None:
        self.bar.close()


def bar(total: int, unit: str):
    try:
        from tqdm.auto import tqdm
    except ImportError:
        return _Lines(total, unit)
    return _Tqdm(tqdm(total=total, unit=unit, desc="render"))
