"""A periodic loop for Python controllers: absolute deadlines and timing statistics.

    loop = PeriodicLoop(rate_hz=1000)
    loop.run(step, duration_s=5.0)      # step(t) each period; return False to stop
    print(loop.statistics)              # period mean/jitter, overruns, step time

Deadlines are absolute (start + k * period), so a late wake-up does not shift
every later tick. A step that ends after the next deadline is an overrun: the
next step starts at once, and deadlines a whole period or more in the past are
skipped (never run in a burst to catch up) and counted.
"""

import math
import time
from dataclasses import dataclass

__all__ = ["LoopStatistics", "PeriodicLoop"]


@dataclass
class LoopStatistics:
    """Timing of a PeriodicLoop run; periods are measured between step starts."""

    rate_hz: float = 0.0  # configured rate
    iterations: int = 0
    period_mean_s: float = 0.0
    period_jitter_s: float = 0.0  # standard deviation of the measured periods
    period_max_s: float = 0.0
    overruns: int = 0  # steps that ended after the next deadline
    missed_deadlines: int = 0  # deadlines skipped because of overruns
    step_mean_s: float = 0.0  # time spent inside step()
    step_max_s: float = 0.0

    @property
    def measured_rate_hz(self):
        return 1.0 / self.period_mean_s if self.period_mean_s > 0 else 0.0

    def __str__(self):
        return (f"loop: {self.iterations} iterations at {self.measured_rate_hz:.1f} Hz "
                f"(target {self.rate_hz:g} Hz), period mean {self.period_mean_s * 1e3:.3f} ms "
                f"jitter {self.period_jitter_s * 1e6:.1f} us max {self.period_max_s * 1e3:.3f} ms, "
                f"step mean {self.step_mean_s * 1e6:.1f} us max {self.step_max_s * 1e6:.1f} us, "
                f"overruns {self.overruns} (missed deadlines {self.missed_deadlines})")


class _Running:
    """Mean and variance without storing samples (Welford)."""

    def __init__(self):
        self.count = 0
        self.mean = 0.0
        self.m2 = 0.0
        self.max = 0.0

    def add(self, value):
        self.count += 1
        delta = value - self.mean
        self.mean += delta / self.count
        self.m2 += delta * (value - self.mean)
        self.max = max(self.max, value)

    @property
    def std(self):
        return math.sqrt(self.m2 / self.count) if self.count > 1 else 0.0


class PeriodicLoop:
    """Calls a step function at a fixed rate on the monotonic clock."""

    def __init__(self, rate_hz):
        if not rate_hz > 0 or not math.isfinite(rate_hz):
            raise ValueError(f"PeriodicLoop: rate_hz is {rate_hz!r}; expected a positive number")
        self.rate_hz = float(rate_hz)
        self.period_ns = int(round(1e9 / self.rate_hz))
        self._stop = False
        self.statistics = LoopStatistics(rate_hz=self.rate_hz)

    def stop(self):
        """Ends run() after the current step (e.g. from a signal handler)."""
        self._stop = True

    def run(self, step, duration_s=None, iterations=None):
        """Runs step(t) every period, t the seconds since the first step.

        Stops when step returns False, after duration_s seconds or `iterations`
        steps, or on stop(). Returns the LoopStatistics (also in .statistics).
        """
        periods, steps = _Running(), _Running()
        overruns = missed = 0
        self._stop = False
        start = time.monotonic_ns()
        end = None if duration_s is None else start + int(duration_s * 1e9)
        deadline = start
        previous = None
        while not self._stop:
            now = time.monotonic_ns()
            if deadline > now:
                time.sleep((deadline - now) * 1e-9)
                now = time.monotonic_ns()
            if end is not None and now >= end:
                break
            if previous is not None:
                periods.add((now - previous) * 1e-9)
            previous = now
            keep_going = step((now - start) * 1e-9)
            finished = time.monotonic_ns()
            steps.add((finished - now) * 1e-9)
            deadline += self.period_ns
            if finished > deadline:
                # Late: the next step starts at once; whole periods already past are skipped.
                overruns += 1
                late = (finished - deadline) // self.period_ns
                missed += late
                deadline += late * self.period_ns
            if keep_going is False or (iterations is not None and steps.count >= iterations):
                break
        self.statistics = LoopStatistics(
            rate_hz=self.rate_hz, iterations=steps.count, period_mean_s=periods.mean,
            period_jitter_s=periods.std, period_max_s=periods.max, overruns=overruns,
            missed_deadlines=missed, step_mean_s=steps.mean, step_max_s=steps.max)
        return self.statistics
