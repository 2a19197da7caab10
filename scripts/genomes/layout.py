"""The input and output layout of an experiment, from `berry-evolve inspect --json`.

The inputs are the observation groups' names in order (`observation[*].names`), the outputs
`outputs`: the same names a genome file's `inputs` and `outputs` carry.
"""
import json
import subprocess
import sys

BINARY = "target/release/berry-evolve"


def layout(experiment, binary=BINARY):
    """(input names, output names) of `experiment`."""
    out = subprocess.run([binary, "inspect", experiment, "--json", "--no-estimate"],
                         capture_output=True, text=True, check=True).stdout
    report = json.loads(out)
    inputs = [name for group in report["observation"] for name in group["names"]]
    return inputs, report["outputs"]


def motor_layout(experiment, binary=BINARY):
    """`layout`, for a vehicle driving the two motors only: exits unless the outputs are
    motor_left, motor_right."""
    inputs, outputs = layout(experiment, binary)
    if outputs != ["motor_left", "motor_right"]:
        sys.exit(f"{experiment}: expected outputs motor_left, motor_right, got {outputs}")
    return inputs, outputs
