"""wbi-plot: the "scope" — fields of a recorded topic against time, into a PNG.

    wbi-plot run.mcap wbi/arm/state q dq[3] header.seq -o state.png
    wbi-plot run.mcap --list                 # topics, their types and fields

One panel per field, all against the recording's log time [s]; a vector field
draws one line per element (FIELD[i] picks one). Uses matplotlib's Agg
backend (no display needed). Exit codes: 0 success, 1 error (one line on stderr).
"""

import argparse
import re
import sys

from .mcap import McapError
from .recording import Recording, RecordingError

_FIELD = re.compile(r"^(?P<path>[A-Za-z_][\w.]*)(?:\[(?P<index>\d+)\])?$")


def _series(data, spec):
    """(label, values as (N,) or (N, k) floats) of one FIELD or FIELD[i] argument."""
    match = _FIELD.match(spec)
    if not match:
        raise RecordingError(f"field '{spec}' is not a field path or FIELD[index]")
    values = data.field(match.group("path"))
    if values.dtype == object:
        raise RecordingError(f"{data.topic}: field '{spec}' is text, not numbers")
    values = values.astype(float)
    if match.group("index") is not None:
        index = int(match.group("index"))
        if values.ndim != 2 or index >= values.shape[1]:
            width = values.shape[1] if values.ndim == 2 else 1
            raise RecordingError(f"{data.topic}: field '{match.group('path')}' has {width} "
                                 f"element(s); index {index} is out of range")
        values = values[:, index]
    return spec, values


def _list(recording, out):
    out.write(f"{recording.path}: {recording.duration_s:.3f} s\n")
    for topic in recording.topics:
        try:
            data = recording.topic(topic)
            out.write(f"{topic}  ({data.type_name}, {len(data)} messages)\n")
            for field in data.fields:
                shape = data[field].shape
                out.write(f"    {field}" + (f"  [{shape[1]}]" if len(shape) == 2 else "") + "\n")
        except RecordingError as error:
            out.write(f"{topic}  (not decoded: {error})\n")


def plot(recording, topic, fields, output, title=None):
    """Writes the PNG; returns the TopicData plotted."""
    data = recording.topic(topic)
    series = [_series(data, spec) for spec in fields]
    import matplotlib  # here: slow to import, and not needed for --list or a bad field
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    figure, axes = plt.subplots(len(series), 1, sharex=True, squeeze=False,
                                figsize=(10, 2.2 + 2.0 * len(series)))
    for ax, (label, values) in zip(axes[:, 0], series):
        if values.ndim == 1:
            ax.plot(data.t, values, linewidth=1.0, label=label)
        else:
            for column in range(values.shape[1]):
                ax.plot(data.t, values[:, column], linewidth=1.0, label=f"{label}[{column}]")
        ax.set_ylabel(label)
        ax.grid(True, alpha=0.3)
        if values.ndim == 1 or values.shape[1] <= 12:
            ax.legend(loc="upper right", fontsize="small", ncol=4)
    axes[-1, 0].set_xlabel("log time [s]")
    figure.suptitle(title or f"{topic}  ({recording.path})", fontsize="medium")
    figure.tight_layout()
    figure.savefig(output, dpi=100)
    plt.close(figure)
    return data


def main(argv=None):
    parser = argparse.ArgumentParser(
        prog="wbi-plot", description="Plot fields of a topic of a wbi recording (.mcap) "
        "against time into a PNG.")
    parser.add_argument("file", help="the recording (.mcap)")
    parser.add_argument("topic", nargs="?", help="the topic, e.g. wbi/arm/state")
    parser.add_argument("fields", nargs="*", help="field paths, e.g. q, dq[3], header.seq")
    parser.add_argument("-o", "--output", help="the PNG to write")
    parser.add_argument("--title", help="figure title (default: topic and file)")
    parser.add_argument("--list", action="store_true", help="print topics and fields, and exit")
    args = parser.parse_args(argv)
    try:
        recording = Recording(args.file)
        for warning in recording.warnings:
            print(f"wbi-plot: warning: {warning}", file=sys.stderr)
        if args.list:
            _list(recording, sys.stdout)
            return 0
        if not args.topic or not args.fields or not args.output:
            parser.error("give TOPIC, at least one FIELD and -o OUT.png (or --list)")
        data = plot(recording, args.topic, args.fields, args.output, args.title)
        print(f"wrote {args.output}: {args.topic}, {len(data)} messages over "
              f"{(data.t[-1] - data.t[0]) if len(data) else 0.0:.3f} s; fields "
              + ", ".join(args.fields))
        return 0
    except (McapError, RecordingError, OSError) as error:
        print(f"wbi-plot: {error}", file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main())
