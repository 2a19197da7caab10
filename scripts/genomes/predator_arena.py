"""The hand-designed baseline of experiments/predator-arena.toml.

A hand-wired logic circuit as an MLP with two tanh hidden layers (a Braitenberg vehicle with
a switch): each unit is tanh(w . x + b) with large gains, so the units act as signs and ANDs.

Layer 1 (features, each about -1 or +1):
  D    danger: the predator's smell (component 7, left + right) above THRESHOLD
  S    the nest is on the right: its beacon's bearing (landmark_1_sin > 0), or, in a world
       without the beacon, its smell (component 8) stronger on the right than on the left
  A    inside the nest (area input)
  F    the food's smell (component 1) is stronger on the right than on the left
  W    the left whisker touches more than the right
  E    eating (any food detector on)
Layer 2 (modes, each about -1 = off or +1 = on):
  home_right / home_left   D and not A and the nest on that side: turn that way at full speed
  hide                     D and A: brake (stay in the nest while the predator is about)
  food_right / food_left   not D and the food on that side: turn that way (forage by smell)
  run                      D and not A: both wheels faster (the predator is faster still)
  whisker, eat             passed on: turn away from a touch; (no brake while eating)
Outputs: forward drive plus the turns and brakes of the modes that are on.

So it forages by the food's smell while the predator is not smelt (asleep, or far), and when
the predator's smell rises above the threshold it steers up the nest's smell and stops inside
the nest until the smell falls again.

(The description in the genome file names scripts/make-predator-arena-baseline.py, the
builder's old path, so that the committed file keeps its bytes.)
"""
from .write import genome

G = 20.0          # gain of the AND units (layer 2)
KN = 100.0        # gain on the nest's smell difference (chosen on the design set: 30-300)
KB = 3.0          # gain on the beacon's bearing (sin), when there is one (1, 3, 10, 20 tried)
TH = 2.0          # turn towards the nest (1-4 tried; 4 zigzags, 1 is too slow)


def home_unit(beacon, kn=KN):
    """S's weights: by the nest's beacon where the world has one, else by the nest's smell."""
    if beacon:
        return [("landmark_1_sin", KB)]
    return [("smell_right_8", kn), ("smell_left_8", -kn)]


def build(names, threshold=None, kn=KN):
    """The genome document over the input names `names` (threshold: the predator's smell,
    left + right, above which it heads home; default 0.1 with the nest's beacon, 0.3 without;
    kn: the gain on the nest's smell difference where there is no beacon)."""
    beacon = "landmark_1_sin" in names
    thr = threshold if threshold is not None else (0.1 if beacon else 0.3)
    n = len(names)
    ix = {name: i for i, name in enumerate(names)}

    # Layer 1: (weights over the inputs, bias)
    def unit(pairs, bias=0.0):
        w = [0.0] * n
        for name, g in pairs:
            w[ix[name]] += g
        return w, bias

    sd = 50.0 / thr                      # danger gate: sharp around the threshold
    l1 = [
        unit([("smell_left_7", sd), ("smell_right_7", sd)], -50.0),          # D: sd * (P - thr)
        unit(home_unit(beacon, kn)),                                                 # S (graded)
        unit([("area_1", 20.0)], -10.0),                                     # A
        unit([("smell_right_1", 200.0), ("smell_left_1", -200.0)]),          # F
        unit([("whisker_left", 3.0), ("whisker_right", -3.0)]),              # W
        unit([(f"food_{c}", 20.0) for c in "abcd" if f"food_{c}" in ix], -10.0),  # E
    ]
    D, S, A, F, W, E = range(6)

    def and2(terms, bias):
        w = [0.0] * len(l1)
        for k, g in terms:
            w[k] += g
        return w, bias

    # +1 inputs summed; an AND of m literals fires when their sum exceeds m - 1.
    l2 = [
        and2([(D, G), (S, 1.0), (A, -G)], -2 * G),   # home_right (graded by S)
        and2([(D, G), (S, -1.0), (A, -G)], -2 * G),  # home_left
        and2([(D, G), (A, G)], -G),                  # hide
        and2([(D, -G), (F, G)], -G),                 # food_right
        and2([(D, -G), (F, -G)], -G),                # food_left
        and2([(W, 1.5)], 0.0),                       # whisker (graded)
        and2([(D, -G), (E, G)], -G),                 # eat (not while in danger)
        and2([(D, G), (A, -G)], -G),                 # run: D and not A, full speed
    ]
    HR, HL, HIDE, FR, FL, WH, EAT, RUN = range(8)
    # Outputs: motor = tanh(bias + sum w * u), with a mode u in {-1, +1}: on = (u + 1) / 2.
    forward, turn_home, turn_food, whisk, run = 0.8, TH, 0.8, 2.0, 2.0
    brake_hide = forward    # cancels the forward drive (more would reverse)
    brake_eat = 0.0         # no brake while eating: braking parks it on one food
    left = [0.0] * len(l2)
    right = [0.0] * len(l2)
    bl = br = forward

    def on(k, gl, gr):
        nonlocal bl, br
        left[k] += gl / 2
        right[k] += gr / 2
        bl += gl / 2
        br += gr / 2

    on(HR, turn_home, -turn_home)     # nest on the right: left wheel faster turns right
    on(HL, -turn_home, turn_home)
    on(HIDE, -brake_hide, -brake_hide)
    on(FR, turn_food, -turn_food)
    on(FL, -turn_food, turn_food)
    on(EAT, -brake_eat, -brake_eat)
    on(RUN, run, run)
    left[WH] += whisk                 # left whisker touched: left wheel faster, turn away
    right[WH] -= whisk

    params = []
    for w, b in l1:
        params += w
    params += [b for _, b in l1]
    for w, b in l2:
        params += w
    params += [b for _, b in l2]
    params += left + right + [bl, br]
    return genome(
        names, ["motor_left", "motor_right"], params,
        "hand-designed baseline for experiments/predator-arena.toml "
        "(scripts/make-predator-arena-baseline.py): forage by the food's smell; "
        f"when the predator's smell (left + right) is above {thr}, steer "
        + ("towards the nest's beacon" if beacon else "up the nest's smell")
        + " and stop inside the nest; whisker turn-away; brake while eating unless in danger",
        hidden=[len(l1), len(l2)])
