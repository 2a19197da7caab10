#!/usr/bin/env python3
"""Cheap-control genomes for the shelter experiments (predator-arena, air-raid).

Writes single-layer (mlp, hidden = []) controllers to OUTDIR, using the input layout of
EXPERIMENT.toml and the steering convention of scripts/make-design2-baselines.py:
  still.json     both motors 0
  spin.json      left +max, right -max
  straight.json  both motors +max (whisker turn-away off)
  arc.json       left full, right half
  to-shelter.json  follow the safe area's smell (component 8), or its beacon's bearing where
                   the world has one (input landmark_1_sin), and stop inside it (area input)
                   and stay there: "go to the nest / a shelter and stay"
Usage: python3 scripts/shelter-controls.py EXPERIMENT.toml OUTDIR
"""
import importlib.util
import json
import os
import sys

here = os.path.dirname(os.path.abspath(__file__))
spec = importlib.util.spec_from_file_location("mdb", os.path.join(here, "make-design2-baselines.py"))
mdb = importlib.util.module_from_spec(spec)
spec.loader.exec_module(mdb)


BEACON_GAIN = 1.0   # the best of 0.5, 1 and 2 on both experiments' design sets


def save(path, names, params, what):
    g = {"format": 1, "brain": {"kind": "mlp", "hidden": []}, "inputs": names,
         "outputs": ["motor_left", "motor_right"], "parameters": params,
         "origin": {"description": f"cheap control (scripts/shelter-controls.py): {what}"}}
    json.dump(g, open(path, "w"), indent=1)


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
    names = mdb.layout(exp)
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
        p = mdb.vehicle(names, whisker=1.5, forward=0.5,
                        extra=stop + [("landmark_1_sin", BEACON_GAIN, -BEACON_GAIN)])
        what = "steer towards the safe area's beacon, stop inside and stay"
    else:
        p = mdb.vehicle(names, towards=[(8, gain)], whisker=1.5, forward=0.5, extra=stop)
        what = "follow the safe area's smell, stop inside and stay"
    save(f"{out}/to-shelter.json", names, p, what)
    return 0


if __name__ == "__main__":
    sys.exit(main())
