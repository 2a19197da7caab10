"""A hand-designed learning controller for experiments/t-maze-switch.toml (issue 31): a
plastic MLP 24 -> 3 -> 2 whose one plastic synapse is a memory of the paying arm.

- Hidden units 0 and 1 are a vehicle (forward drive through the bias, whiskers turning it
  away from walls, a brake while a food detector is on so that it stays to eat), read by the
  motors with gain `gain`.
- Hidden unit 2, the memory, is tanh(w . bias): it turns the creature by +-`turn` (left motor
  +turn h, right motor -turn h), so the sign of w decides which arm it enters at the junction
  (w > 0: the right arm).
- Only w learns (per-synapse neuromodulated rule, every other synapse's eta 0):
  dw = tanh(m/2) . eta . A . pre . post with pre = 1 (the bias) and post = tanh(w), and
  m = `mod` x food detector A - `mod` x food detector C. At the paying goal (A) g > 0 drives
  w further along its sign (to the bound 4): the arm is kept. At the empty goal (C) g < 0
  pushes w the other way by eta A tanh(w), past 0 when eta A is large enough: the other arm
  next time. The empty goal holds two bites of C, so detector C is on for one tick: one flip.

The gains were tuned on the design worlds only (`compare --worlds design --trials 20`):
forward 2, whisker 5, turn 0.1, gain 3 (about 60 settings; the vehicle reaches a goal in
about 9 episodes of 10), eta A 5 (3-8 tried), mod 6, brake 2 (0-5 tried: below the forward
drive it does not stop, and eats a fifth as much).
"""
from .vehicle import vehicle
from .write import genome

COEFFICIENTS = 5  # eta, A, B, C, D


def t_maze_switch(inputs, outputs, forward=2.0, whisker=5.0, turn=0.1, gain=3.0, w0=1.0,
                  eta_a=5.0, mod=6.0, brake=2.0):
    """The genome document (plasticity per synapse, modulated by food_a and food_c)."""
    n, hidden, m = len(inputs), 3, len(outputs)
    bias = inputs.index("bias")
    memory = [0.0] * n
    memory[bias] = w0
    w_h0 = vehicle(inputs, whisker=whisker, forward=forward, eat_brake=brake) + [memory]
    w_out = [[gain, 0.0, turn], [0.0, gain, -turn]] + [[0.0] * hidden for _ in outputs[2:]]
    parameters = [w for row in w_h0 for w in row] + [0.0] * hidden
    parameters += [w for row in w_out for w in row] + [0.0] * m

    def rule(units, fan_in, plastic):
        genes = []
        for c in range(COEFFICIENTS):
            for j in range(units):
                for i in range(fan_in):
                    on = (j, i) in plastic
                    genes.append({0: 1.0, 1: eta_a}.get(c, 0.0) if on else 0.0)
        return genes

    parameters += rule(hidden, n, {(2, bias)}) + rule(m, hidden, set())
    parameters += [mod, -mod]  # mod_food_a, mod_food_c
    document = genome(inputs, outputs, parameters,
                      "hand-designed learner for experiments/t-maze-switch.toml "
                      "(python3 -m scripts.genomes t-maze-switch): a vehicle that brakes to "
                      "eat and one plastic memory synapse of the paying arm, confirmed by food detector A, "
                      "flipped by C", hidden=[hidden])
    document["brain"].update({"plasticity": "neuromodulated", "granularity": "synapse",
                              "modulators": ["food_a", "food_c"]})
    return document
