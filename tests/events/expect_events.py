#!/usr/bin/env python3
"""Whether `wbi events --json` output holds the given events, in order.

  expect_events.py FILE FROM_LINE SPEC [SPEC...]
  expect_events.py --count FILE FROM_LINE SPEC      prints how many events match SPEC

SPEC is SOURCE/KIND[/SEVERITY[/TEXT]]: the event's source, its kind, its
severity (empty: any) and a piece of its text or subject (empty: any). The
events after line FROM_LINE of FILE are searched for the first SPEC, then
after it for the second, and so on (the order in which the reader got them).
Exit 0 when all are found; 1 otherwise, naming the first one missing.
"""
import json
import sys


def matches(event, spec):
    parts = spec.split("/", 3) + ["", ""]
    source, kind, severity, text = parts[0], parts[1], parts[2], parts[3]
    return (event.get("source") == source and event.get("kind") == kind
            and (not severity or event.get("severity") == severity)
            and (not text or text in event.get("text", "") or text in event.get("subject", "")))


def events_after(path, from_line):
    events = []
    with open(path, encoding="utf-8", errors="replace") as lines:
        for number, line in enumerate(lines, start=1):
            if number > from_line and line.endswith("\n"):  # a line being written: not yet
                events.append(json.loads(line))
    return events


def main(argv):
    count = argv[:1] == ["--count"]
    argv = argv[1:] if count else argv
    if len(argv) < 3 or (count and len(argv) != 3):
        print(__doc__, file=sys.stderr)
        return 2
    events = events_after(argv[0], int(argv[1]))
    if count:
        print(sum(1 for event in events if matches(event, argv[2])))
        return 0
    at = 0
    for spec in argv[2:]:
        while at < len(events) and not matches(events[at], spec):
            at += 1
        if at == len(events):
            print(f"missing: {spec}", file=sys.stderr)
            return 1
        at += 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
