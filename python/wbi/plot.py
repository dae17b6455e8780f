"""wbi-plot: the "scope" — fields of a recorded topic against time, into a PNG.

    wbi-plot run.mcap wbi/arm/state q dq[3] header.seq -o state.png
    wbi-plot run.mcap --list                 # topics, their types and fields

One panel per field, all against the recording's log time [s]; a vector field
draws one line per element (FIELD[i] picks one, FIELD[i,j] several in one panel). Elements are named where the
recording says what they are: `values` of a Signals topic by its `names`
(`wbi-plot run.mcap wbi/icub3/signals/balance values[4,1]`: the CoM reference
and the CoM along y, in one panel), and the joint vectors of a robot's topics (q, dq,
ddq, tau, encoder_position, …: one element per joint) by the joint names of
its recorded `wbi/<robot>/description`. `--events` marks the recording's
wbi/events (a windowed recorder's file holds them) on the time axis: a line at
each event's stamp, coloured by severity, named by its kind. Uses matplotlib's
Agg backend (no display needed). Exit codes: 0 success, 1 error (one line on stderr).
"""

import argparse
import os
import re
import sys

from .mcap import McapError
from .recording import Recording, RecordingError

_FIELD = re.compile(r"^(?P<path>[A-Za-z_][\w.]*)(?:\[(?P<index>\d+(?:,\d+)*)\])?$")


def element_names(recording, data, path):
    """What the elements of a vector field are, or None: a Signals topic's names for
    its values, the robot's joint names (from its recorded description) for a field
    with one element per joint."""
    if path == "values" and "names" in data.fields and len(data):
        return [str(name) for name in data["names"][0]]
    parts = data.topic.split("/")
    description = "/".join(parts[:2] + ["description"]) if len(parts) >= 3 else None
    if description is None or description == data.topic or description not in recording.topics:
        return None
    joints = [str(name) for name in recording.topic(description)["joint_names"][0]]
    values = data.field(path)
    if values.dtype != object and values.ndim == 2 and values.shape[1] == len(joints):
        return joints
    return None


def _series(data, spec, recording=None):
    """(label, values as (N,) or (N, k) floats, a label per column or None) of one
    FIELD, FIELD[i] or FIELD[i,j,...] argument."""
    match = _FIELD.match(spec)
    if not match:
        raise RecordingError(f"field '{spec}' is not a field path or FIELD[index]")
    values = data.field(match.group("path"))
    if values.dtype == object:
        raise RecordingError(f"{data.topic}: field '{spec}' is text, not numbers")
    values = values.astype(float)
    names = element_names(recording, data, match.group("path")) if recording else None
    if match.group("index") is None:
        return spec, values, names
    indices = [int(index) for index in match.group("index").split(",")]
    width = values.shape[1] if values.ndim == 2 else 1
    for index in indices:
        if values.ndim != 2 or index >= width:
            raise RecordingError(f"{data.topic}: field '{match.group('path')}' has {width} "
                                 f"element(s); index {index} is out of range")
    labels = [f"{match.group('path')}[{index}]" + (f" {names[index]}" if names else "")
              for index in indices]
    if len(indices) == 1:
        return labels[0], values[:, indices[0]], None
    return spec, values[:, indices], labels


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


_SEVERITY_COLOURS = {"DEBUG": "grey", "INFO": "tab:blue", "WARNING": "tab:orange",
                     "ERROR": "tab:red", "FATAL": "black"}


def recorded_events(recording):
    """[(time [s] on the recording's time base, severity, kind, source)] of its wbi/events:
    the time is the event's stamp (when it happened), not when it was recorded."""
    if "wbi/events" not in recording.topics:
        return []
    data = recording.topic("wbi/events")
    kinds = data.enum_names("kind")
    severities = data.enum_names("severity")
    t = data.t + (data["header.stamp_ns"] - data.log_time_ns) * 1e-9
    return [(float(t[i]), severities.get(int(data["severity"][i]), "?"),
             kinds.get(int(data["kind"][i]), "?"), str(data["source"][i]))
            for i in range(len(data))]


def _mark_events(axes, events):
    for row, ax in enumerate(axes[:, 0]):
        for time, severity, kind, source in events:
            ax.axvline(time, color=_SEVERITY_COLOURS.get(severity, "grey"), linestyle="--",
                       linewidth=0.8, alpha=0.8)
            if row == 0:
                ax.text(time, 1.0, f" {kind} {source}", transform=ax.get_xaxis_transform(),
                        rotation=90, va="top", ha="right", fontsize="x-small")


def plot(recording, topic, fields, output, title=None, events=None):
    """Writes the PNG; returns the TopicData plotted. events: recorded_events() to mark."""
    data = recording.topic(topic)
    series = [_series(data, spec, recording) for spec in fields]
    import matplotlib  # here: slow to import, and not needed for --list or a bad field
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    figure, axes = plt.subplots(len(series), 1, sharex=True, squeeze=False,
                                figsize=(10, 2.2 + 2.0 * len(series)))
    for ax, (label, values, names) in zip(axes[:, 0], series):
        if values.ndim == 1:
            ax.plot(data.t, values, linewidth=1.0, label=label)
        else:
            for column in range(values.shape[1]):
                name = names[column] if names else f"{label}[{column}]"
                ax.plot(data.t, values[:, column], linewidth=1.0, label=name)
        ax.set_ylabel(label)
        ax.grid(True, alpha=0.3)
        if values.ndim == 1 or values.shape[1] <= 12:
            ax.legend(loc="upper right", fontsize="small", ncol=4)
    if events:
        _mark_events(axes, events)
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
    parser.add_argument("--events", action="store_true",
                        help="mark the recording's wbi/events on the time axis")
    args = parser.parse_args(argv)
    try:
        recording = Recording(args.file)
        for warning in recording.warnings:
            print(f"wbi-plot: warning: {warning}", file=sys.stderr)
        if args.list:
            _list(recording, sys.stdout)
            sys.stdout.flush()  # a closed pipe shows here, where it is handled
            return 0
        if not args.topic or not args.fields or not args.output:
            parser.error("give TOPIC, at least one FIELD and -o OUT.png (or --list)")
        events = recorded_events(recording) if args.events else None
        data = plot(recording, args.topic, args.fields, args.output, args.title, events)
        print(f"wrote {args.output}: {args.topic}, {len(data)} messages over "
              f"{(data.t[-1] - data.t[0]) if len(data) else 0.0:.3f} s; fields "
              + ", ".join(args.fields)
              + (f"; {len(events)} events marked" if events is not None else ""))
        return 0
    except BrokenPipeError:
        # The reader left (`wbi-plot run.mcap --list | head`): not an error. Later writes
        # to the closed pipe at exit would raise again, so stdout goes nowhere from here.
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 0
    except (McapError, RecordingError, OSError) as error:
        print(f"wbi-plot: {error}", file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main())
