#!/usr/bin/env python3
"""Writes a hand-designed vehicle (a Braitenberg vehicle or a cheap control) as a genome file.

The vehicle is a single-layer network (mlp, hidden = []): each motor = tanh(w . inputs + b),
scaled by max_rpt. Its input layout is read from `berry-evolve inspect EXPERIMENT` (the
"[ n] name" lines), so the same gains fit any experiment's observation.

Gains (all default 0):
  --forward F     both motors get F through the bias input (tanh(F) * max_rpt forward)
  --spin S        left motor +S, right motor -S through the bias (turns on the spot)
  --steer G       crossed smell wiring, left motor += G * (right - left smell) and mirrored,
                  for the odour components listed in --odours (1-based, default 1,2,3,4):
                  turns towards the stronger smell (phi = (d_L - d_R)/w > 0 turns right)
  --avoid-odours K:G  crossed smell wiring with the opposite sign for component K: turns
                  away from that odour (repeatable)
  --whisker W     a touching whisker speeds up its own side's wheel and slows the other's
                  (turns away from the touch)
  --brake E       every food detector subtracts E from both motors (stays while eating)
  --shock-back S  the shock input drives both motors backwards by S
  --eye G         crossed eye wiring for colour channel --eye-channel (0 r, 1 g, 2 b) of a
                  1-row retina: pixels on the right half drive the left motor (turn towards)
  --description TEXT

Usage: python3 scripts/make-vehicle.py EXPERIMENT.toml [gains] > genomes/NAME.json
"""
import argparse
import json
import re
import subprocess
import sys


def layout(experiment, binary):
    text = subprocess.run([binary, "inspect", experiment], check=True, capture_output=True,
                          text=True).stdout
    names = [m.group(2) for m in re.finditer(r"^\s*\[\s*(\d+)\]\s+(\S+)\s*$", text, re.M)]
    outs = re.search(r"^outputs: (.*)$", text, re.M).group(1).split(", ")
    return names, outs


def motor_layout(experiment, binary):
    """`layout`, for a vehicle driving the two motors only: exits unless the outputs are
    motor_left, motor_right."""
    names, outs = layout(experiment, binary)
    if outs != ["motor_left", "motor_right"]:
        sys.exit(f"expected outputs motor_left, motor_right, got {outs}")
    return names, outs


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("experiment")
    ap.add_argument("--binary", default="target/release/berry-evolve")
    for g in ["forward", "spin", "steer", "whisker", "brake", "shock_back", "eye"]:
        ap.add_argument("--" + g.replace("_", "-"), type=float, default=0.0)
    ap.add_argument("--odours", default="1,2,3,4")
    ap.add_argument("--avoid-odours", action="append", default=[])
    ap.add_argument("--eye-channel", type=int, default=1)
    ap.add_argument("--eye-opponent", type=int, default=None,
                    help="a colour channel subtracted from --eye-channel (e.g. 0: green - red, "
                         "so grey walls cancel)")
    ap.add_argument("--description", default="hand-designed vehicle (scripts/make-vehicle.py)")
    a = ap.parse_args()
    inputs, outputs = layout(a.experiment, a.binary)
    if outputs[:2] != ["motor_left", "motor_right"]:
        sys.exit(f"expected outputs motor_left, motor_right first, got {outputs}")
    index = {n: i for i, n in enumerate(inputs)}
    odours = [int(k) for k in a.odours.split(",") if k]
    avoid = [(int(k), float(g)) for k, g in (s.split(":") for s in a.avoid_odours)]
    # Eye inputs are named eye_<channel>_<row>_<column>, columns from left to right.
    eye = [n for n in inputs if re.fullmatch(r"eye_[rgb]_\d+_\d+", n)]

    def add(row, name, w):
        if name in index:
            row[index[name]] += w

    def motor_row(side):
        other = "right" if side == "left" else "left"
        row = [0.0] * len(inputs)
        for k in odours:
            add(row, f"smell_{other}_{k}", a.steer)
            add(row, f"smell_{side}_{k}", -a.steer)
        for k, g in avoid:
            add(row, f"smell_{other}_{k}", -g)
            add(row, f"smell_{side}_{k}", g)
        add(row, "whisker_left", a.whisker if side == "left" else -a.whisker)
        add(row, "whisker_right", -a.whisker if side == "left" else a.whisker)
        for f in "abcd":
            add(row, f"food_{f}", -a.brake)
        add(row, "shock", -a.shock_back)
        add(row, "bias", a.forward + (a.spin if side == "left" else -a.spin))
        if eye:
            chan = "rgb"[a.eye_channel]
            width = 1 + max(int(n.split("_")[3]) for n in eye)
            opp = None if a.eye_opponent is None else "rgb"[a.eye_opponent]
            for n in eye:
                _, c, _, col = n.split("_")
                if c == chan:
                    sign = 1.0
                elif c == opp:
                    sign = -1.0
                else:
                    continue
                right_half = int(col) >= width / 2.0
                # A pixel on the other side from this motor speeds it up: turn towards it.
                toward = (right_half and side == "left") or (not right_half and side == "right")
                row[index[n]] += sign * (a.eye if toward else -a.eye)
        return row

    write_vehicle(inputs, outputs, [motor_row("left"), motor_row("right")], a.description)


def write_vehicle(inputs, outputs, rows, description):
    """Prints the genome of a single-layer network (mlp, hidden = []) whose first outputs'
    weight rows are `rows` (any further outputs and every bias 0)."""
    extra = [[0.0] * len(inputs) for _ in outputs[len(rows):]]
    parameters = [w for r in rows + extra for w in r] + [0.0] * len(outputs)
    genome = {
        "format": 1,
        "brain": {"kind": "mlp", "hidden": []},
        "inputs": inputs,
        "outputs": outputs,
        "parameters": parameters,
        "origin": {"description": description},
    }
    json.dump(genome, sys.stdout, indent=2)
    sys.stdout.write("\n")


if __name__ == "__main__":
    main()
