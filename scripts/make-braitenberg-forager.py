#!/usr/bin/env python3
"""Writes genomes/braitenberg-forager.json: a hand-designed forager for experiments/foraging.toml.

A Braitenberg vehicle 2b/3 hybrid as a single-layer network (mlp, hidden = []):
each motor = tanh(sum of weighted inputs + bias), scaled by max_rpt.

- Crossed smell wiring steers towards food: the left motor is driven by the RIGHT smell
  sensor minus the LEFT one (and vice versa), for odour components 1-4 (food types A-D).
  A stronger smell on the right speeds up the left wheel, which turns the creature right
  (phi = (d_L - d_R)/w > 0 is clockwise on screen, towards the creature's right).
- A whisker touching on one side turns the creature away from that side.
- While a food detector is on, both motors are inhibited so the creature stays and eats.
- A constant forward drive through the bias input keeps it exploring.

Usage: python3 scripts/make-braitenberg-forager.py > genomes/braitenberg-forager.json
"""
import json
import sys

STEER = 4.0       # gain of the crossed smell difference
WHISKER = 1.5     # turn-away gain of a touching whisker
FORWARD = 0.5     # forward drive: tanh(0.5) * 0.25 RPT = 0.116 RPT = 1.45 LU per tick
EAT_BRAKE = 0.5   # food detector cancels the forward drive while eating

# Observation layout of foraging.toml (see `berry-evolve inspect experiments/foraging.toml`).
inputs = ([f"smell_left_{k}" for k in range(1, 9)] + [f"smell_right_{k}" for k in range(1, 9)]
          + ["whisker_left", "whisker_right", "food_a", "food_b", "food_c", "food_d",
             "shock", "bias"])
index = {name: i for i, name in enumerate(inputs)}


def motor_row(side):
    other = "right" if side == "left" else "left"
    row = [0.0] * len(inputs)
    for k in range(1, 5):                      # odour components of food A-D
        row[index[f"smell_{other}_{k}"]] += STEER
        row[index[f"smell_{side}_{k}"]] -= STEER
    # Left whisker touching: speed up the left wheel and slow the right one (turn right).
    row[index["whisker_left"]] = WHISKER if side == "left" else -WHISKER
    row[index["whisker_right"]] = -WHISKER if side == "left" else WHISKER
    for food in "abcd":
        row[index[f"food_{food}"]] = -EAT_BRAKE
    row[index["bias"]] = FORWARD
    return row


# mlp with no hidden layer: w_out[o][i] row by row, then b_out[o].
parameters = motor_row("left") + motor_row("right") + [0.0, 0.0]
genome = {
    "format": 1,
    "brain": {"kind": "mlp", "hidden": []},
    "inputs": inputs,
    "outputs": ["motor_left", "motor_right"],
    "parameters": parameters,
    "origin": {
        "description": "hand-designed Braitenberg forager for experiments/foraging.toml "
                       "(scripts/make-braitenberg-forager.py): crossed smell steering, "
                       "whisker avoidance, brake while eating"
    },
}
json.dump(genome, sys.stdout, indent=2)
sys.stdout.write("\n")
