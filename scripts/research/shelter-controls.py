#!/usr/bin/env python3
"""Cheap-control genomes for the shelter experiments (predator-arena, air-raid).

Writes single-layer (mlp, hidden = []) controllers to OUTDIR, using the input layout of
EXPERIMENT.toml (`inspect --json`) and the wiring of scripts/genomes/vehicle.py:
  still.json     both motors 0
  spin.json      left +max, right -max
  straight.json  both motors +max (whisker turn-away off)
  arc.json       left full, right half
  to-shelter.json  follow the safe area's smell (component 8), or its beacon's bearing where
                   the world has one (input landmark_1_sin), and stop inside it (area input)
                   and stay there: "go to the nest / a shelter and stay"
Usage: python3 scripts/research/shelter-controls.py EXPERIMENT.toml OUTDIR  (from the repo root)
"""
import json
import os
import sys

# The genome builders' package, scripts/genomes/, from the repository root.
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
from scripts.genomes.layout import BINARY, layout  # noqa: E402
from scripts.genomes.vehicle import vehicle  # noqa: E402


BEACON_GAIN = 1.0   # the best of 0.5, 1 and 2 on both experiments' design sets


def save(path, names, params, what):
    g = {"format": 1, "brain": {"kind": "mlp", "hidden": []}, "inputs": names,
         "outputs": ["motor_left", "motor_right"], "parameters": params,
         "origin": {"description": f"cheap control (scripts/research/shelter-controls.py): {what}"}}
    json.dump(g, open(path, "w"), indent=1)


def flat(rows):
    """A single-layer network's parameters: the two motor rows, then two zero biases."""
    return rows[0] + rows[1] + [0.0, 0.0]


def bias_only(names, left, right):
    n = len(names)
    b = names.index("bias")
    p = [0.0] * (2 * n + 2)
    p[b] = left
    p[n + b] = right
    return p


def main():
    exp, out = sys.argv[1], sys.argv[2]
    os.makedirs(out, exist_ok=True)
    names, _ = layout(exp, os.environ.get("BERRY_EVOLVE", BINARY))
    save(f"{out}/still.json", names, bias_only(names, 0.0, 0.0), "stand still")
    save(f"{out}/spin.json", names, bias_only(names, 5.0, -5.0), "spin on the spot")
    save(f"{out}/straight.json", names, bias_only(names, 5.0, 5.0), "drive straight")
    save(f"{out}/arc.json", names, bias_only(names, 5.0, 0.55), "drive in an arc")
    areas = [n for n in names if n.startswith("area_")]
    # Both shelters smell strongly (air-raid's at intensity 5, predator-arena's nest at 10):
    # a gain of 6 follows the gradient, 60 saturates the motors and spins on the spot.
    gain = 6.0
    stop = [(a, -0.5, -0.5) for a in areas]
    if "landmark_1_sin" in names:
        # The beacon's sin(bearing) is +1 with the shelter to the right: left wheel faster.
        p = flat(vehicle(names, whisker=1.5, forward=0.5,
                         extra=stop + [("landmark_1_sin", BEACON_GAIN, -BEACON_GAIN)]))
        what = "steer towards the safe area's beacon, stop inside and stay"
    else:
        p = flat(vehicle(names, towards=[(8, gain)], whisker=1.5, forward=0.5, extra=stop))
        what = "follow the safe area's smell, stop inside and stay"
    save(f"{out}/to-shelter.json", names, p, what)
    return 0


if __name__ == "__main__":
    sys.exit(main())
