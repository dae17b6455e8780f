#!/usr/bin/python3
"""A wbi recording as numpy arrays: topics, fields, one time base.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/read_recording.py run.mcap [ROBOT]

For robot ROBOT (default arm) prints what the recording holds and, when it has
the state estimate and the simulation's ground truth, the estimator's error on
the joint positions (both resampled onto the state's times).
"""

import sys

import numpy as np

import wbi


def main(argv):
    if len(argv) < 2:
        print(__doc__, file=sys.stderr)
        return 2
    rec = wbi.Recording(argv[1])
    robot = argv[2] if len(argv) > 2 else "arm"
    for warning in rec.warnings:
        print("warning:", warning)
    print(f"{rec.path}: {rec.duration_s:.3f} s")
    for name in rec.topics:
        try:
            topic = rec.topic(name)
            print(f"  {name}: {topic.type_name}, {len(topic)} messages, {len(topic.fields)} fields")
        except wbi.RecordingError as error:
            print(f"  {name}: not decoded ({error})")

    if {f"wbi/{robot}/state", f"wbi/{robot}/ground_truth"} <= set(rec.topics):
        state, truth = rec.topic(f"wbi/{robot}/state"), rec.topic(f"wbi/{robot}/ground_truth")
        true_q = truth.at(state.t, "q")  # ground truth at the state's log times
        error = np.nanmax(np.abs(state["q"] - true_q), axis=0)
        print("max |q_estimated - q_true| per joint [rad]:", np.array2string(error, precision=5))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
