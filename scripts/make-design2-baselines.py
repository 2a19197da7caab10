#!/usr/bin/env python3
"""Writes the hand-designed baselines of the design2 experiments to genomes/<name>-baseline.json.

Each is a Braitenberg vehicle as a single-layer network (mlp, hidden = []): every motor is
tanh(sum of weighted inputs + bias) scaled by max_rpt; the layout of inputs comes from
`berry-evolve inspect EXPERIMENT.toml` (the names must match the experiment's inputs).

Steering convention (as in scripts/make-braitenberg-forager.py): a stronger input on the right
that speeds up the LEFT wheel turns the creature right. So "towards odour k" is crossed wiring
(left motor += g * right_k - g * left_k) and "away from odour k" is the opposite sign.

Usage: python3 scripts/make-design2-baselines.py   (writes all five files under genomes/)
"""
import json
import os
import subprocess
import sys

BIN = os.environ.get("BERRY_EVOLVE", "target/release/berry-evolve")


def layout(experiment):
    out = subprocess.run([BIN, "inspect", experiment], capture_output=True, text=True,
                         check=True).stdout
    names = []
    for line in out.splitlines():
        line = line.strip()
        if line.startswith("[") and "]" in line:
            names.append(line.split("]", 1)[1].strip())
    return names


def vehicle(names, towards=(), away=(), whisker=1.5, forward=0.5, eat_brake=0.0,
            extra=()):
    """towards/away: (odour component 1..8, gain); extra: (input, left weight, right weight)."""
    index = {n: i for i, n in enumerate(names)}
    rows = {}
    for side in ("left", "right"):
        other = "right" if side == "left" else "left"
        row = [0.0] * len(names)
        for k, g in towards:
            row[index[f"smell_{other}_{k}"]] += g
            row[index[f"smell_{side}_{k}"]] -= g
        for k, g in away:
            row[index[f"smell_{other}_{k}"]] -= g
            row[index[f"smell_{side}_{k}"]] += g
        row[index["whisker_left"]] = whisker if side == "left" else -whisker
        row[index["whisker_right"]] = -whisker if side == "left" else whisker
        for food in "abcd":
            if f"food_{food}" in index:
                row[index[f"food_{food}"]] = -eat_brake
        row[index["bias"]] = forward
        rows[side] = row
    for name, wl, wr in extra:
        rows["left"][index[name]] += wl
        rows["right"][index[name]] += wr
    return rows["left"] + rows["right"] + [0.0, 0.0]


def write(name, names, parameters, description):
    genome = {
        "format": 1,
        "brain": {"kind": "mlp", "hidden": []},
        "inputs": names,
        "outputs": ["motor_left", "motor_right"],
        "parameters": parameters,
        "origin": {"description": f"hand-designed baseline for experiments/{name}.toml "
                                  f"(scripts/make-design2-baselines.py): {description}"},
    }
    with open(f"genomes/{name}-baseline.json", "w") as f:
        json.dump(genome, f, indent=2)
        f.write("\n")


def main():
    n = layout("experiments/t-maze.toml")
    # Drive up the stem, turn off walls, and steer gently towards the goal's odour (component
    # 1): at the junction it appears first in the receptor on the goal's side (the other one
    # is still behind the corner), so the creature turns into the rewarded arm.
    write("t-maze", n,
          vehicle(n, towards=[(1, 2.0)], whisker=0.3, forward=0.8),
          "forward drive, whisker turn-away, steer towards the goal's smell")
    n = layout("experiments/predator-arena.toml")
    # Forage by smell (component 1), a strong pull towards the nest's smell (component 8) so
    # that it forages round the nest, a mild turn away from the predator's smell (component 7),
    # turn off walls, brake while eating and slow right down inside the nest (area input).
    write("predator-arena", n,
          vehicle(n, towards=[(1, 3.0), (8, 8.0)], away=[(7, 2.0)], whisker=1.5, forward=1.0,
                  eat_brake=0.5, extra=[("area_1", -1.0, -1.0)]),
          "forage by smell round the nest's smell, turn from the predator's smell, whisker "
          "turn-away, brake while eating, slow in the nest")
    n = layout("experiments/air-raid.toml")
    # Forage by smell (component 1); while an air predator's smell (component 7) is on, head for
    # a shelter's smell (component 8) and stop inside a shelter (area input).
    write("air-raid", n,
          vehicle(n, towards=[(1, 4.0), (8, 6.0)], whisker=1.5, forward=0.5, eat_brake=0.5,
                  extra=[("area_1", -0.4, -0.4), ("area_2", -0.4, -0.4)]),
          "forage by smell, drift towards shelters' smell, whisker turn-away, slow in a shelter")
    n = layout("experiments/locked-room.toml")
    # Follow the door trigger's odour (component 8) to the doorstep, and the food's smell
    # (component 1, which comes through the doorway once the door is open) more strongly, so
    # that it wins over the trigger's; whisker turn-away.
    write("locked-room", n,
          vehicle(n, towards=[(8, 1.5), (1, 8.0)], whisker=1.0, forward=1.0),
          "follow the trigger's scent, then (stronger) the food's smell, whisker turn-away")
    return 0


if __name__ == "__main__":
    sys.exit(main())
