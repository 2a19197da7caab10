"""Braitenberg vehicles as weight rows of a single-layer network (mlp, hidden = []): each
motor = tanh(w . inputs + b), scaled by max_rpt.

Steering convention: a stronger input on the right that speeds up the LEFT wheel turns the
creature right (phi = (d_L - d_R)/w > 0 is clockwise on screen). So "towards odour k" is
crossed wiring (left motor += g * right_k - g * left_k) and "away from odour k" the opposite
sign.
"""
import re


def vehicle(inputs, towards=(), away=(), whisker=1.5, forward=0.5, eat_brake=0.0, spin=0.0,
            shock_back=0.0, eye=None, extra=()):
    """The two motor rows (left, right) of a vehicle over the input names `inputs`:

    towards/away  (odour component 1..8, gain): steer towards / away from that smell
    whisker       a touching whisker speeds up its own side's wheel and slows the other's
    forward       both motors get it through the bias input (tanh(F) * max_rpt forward)
    eat_brake     every food detector subtracts it from both motors (stays while eating)
    spin          left motor +S, right motor -S through the bias (turns on the spot)
    shock_back    the shock input drives both motors backwards by it
    eye           (gain, channel, opponent or None): crossed retina wiring of colour channel
                  0 r, 1 g, 2 b (minus the opponent channel): a pixel on the right half
                  drives the left motor (turns towards it)
    extra         (input, left weight, right weight) added last
    Inputs a vehicle has no use for in this experiment are skipped; a named smell component
    must exist.
    """
    index = {n: i for i, n in enumerate(inputs)}
    rows = {}
    for side in ("left", "right"):
        other = "right" if side == "left" else "left"
        row = [0.0] * len(inputs)
        for k, g in towards:
            row[index[f"smell_{other}_{k}"]] += g
            row[index[f"smell_{side}_{k}"]] -= g
        for k, g in away:
            row[index[f"smell_{other}_{k}"]] -= g
            row[index[f"smell_{side}_{k}"]] += g
        if "whisker_left" in index:
            row[index["whisker_left"]] = whisker if side == "left" else -whisker
            row[index["whisker_right"]] = -whisker if side == "left" else whisker
        for food in "abcd":
            if f"food_{food}" in index:
                row[index[f"food_{food}"]] = -eat_brake
        if shock_back and "shock" in index:
            row[index["shock"]] -= shock_back
        row[index["bias"]] = forward + (spin if side == "left" else -spin) if spin else forward
        if eye is not None:
            wire_eye(row, inputs, index, side, *eye)
        rows[side] = row
    for name, wl, wr in extra:
        rows["left"][index[name]] += wl
        rows["right"][index[name]] += wr
    return [rows["left"], rows["right"]]


def wire_eye(row, inputs, index, side, gain, channel, opponent=None):
    """Adds crossed eye wiring to `side`'s motor row. Eye inputs are named
    eye_<channel>_<row>_<column>, columns from left to right."""
    eye = [n for n in inputs if re.fullmatch(r"eye_[rgb]_\d+_\d+", n)]
    if not eye:
        return
    chan = "rgb"[channel]
    opp = None if opponent is None else "rgb"[opponent]
    width = 1 + max(int(n.split("_")[3]) for n in eye)
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
        row[index[n]] += sign * (gain if toward else -gain)
