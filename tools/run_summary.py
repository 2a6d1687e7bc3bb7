"""Reading a finished run's summary.json, shared by the comparison tools."""

import json
import os
import sys


def read_summary(directory, required=True):
    """summary.json of a run directory. If it is missing or not JSON (a run
    still under way has none), exits with a message naming the file, or
    returns None when the caller does not require it."""
    name = os.path.join(directory, "summary.json")
    try:
        with open(name) as f:
            return json.load(f)
    except OSError as e:
        if not required:
            return None
        sys.exit(f"{name}: {e.strerror} (a run still under way has no "
                 "summary yet)")
    except json.JSONDecodeError as e:
        if not required:
            return None
        sys.exit(f"{name}: not JSON ({e})")


def onset_time(directory):
    """Absolute time of the failure onset: the start of the collapse stage
    plus the onset the cliff diagnostics measured from it. Summaries
    written before stages recorded their start time give it as the end of
    the stage before."""
    summary = read_summary(directory)
    name = os.path.join(directory, "summary.json")
    onset = summary.get("cliff", {}).get("failure_onset_s")
    stages = summary.get("stages", {})
    if onset is None or "collapse" not in stages:
        sys.exit(f"{name}: no failure onset (has the cliff failed?)")
    start = stages["collapse"].get("start_time")
    if start is None:
        names = list(stages)
        i = names.index("collapse")
        start = stages[names[i - 1]]["end_time"] if i > 0 else 0.0
    return start + onset
