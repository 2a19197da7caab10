"""The hand-designed single-layer vehicles shipped in genomes/, one function each: the
gains, and the description the genome file carries (it names the script that first wrote
the file, so that the committed bytes stay as they are)."""
from .vehicle import vehicle
from .write import single_layer


def braitenberg_forager(inputs, outputs):
    """experiments/foraging.toml: a Braitenberg vehicle 2b/3 hybrid. Crossed smell wiring
    (gain 4) towards food A-D (odour components 1-4); a touching whisker turns it away; a food
    detector cancels the forward drive while eating (0.5); forward 0.5 through the bias:
    tanh(0.5) * 0.25 RPT = 1.45 LU per tick."""
    rows = vehicle(inputs, towards=[(k, 4.0) for k in range(1, 5)], whisker=1.5, forward=0.5,
                   eat_brake=0.5)
    return single_layer(inputs, outputs, rows,
                        "hand-designed Braitenberg forager for experiments/foraging.toml "
                        "(scripts/make-braitenberg-forager.py): crossed smell steering, "
                        "whisker avoidance, brake while eating")


def balanced_diet(inputs, outputs, common=0.75, scarce=8.0, whisker=1.0, forward=1.25,
                  brake=0.0):
    """experiments/balanced-diet.toml: crossed smell steering with a larger gain for the
    scarce types C and D (components 3, 4) than for A and B, so it turns harder for what it
    will otherwise lack; no brake (it eats in passing: the objects hold 8 bites); it does not
    read the metabolism inputs. The defaults are the best of about 80 settings tried on the
    design set (compare --worlds design --trials 100): forward 0.5-1.5, scarce
    4-16, common 0.25-1.5, whisker 1-3, brake 0-1."""
    gains = [(1, common), (2, common), (3, scarce), (4, scarce)]
    rows = vehicle(inputs, towards=gains, whisker=whisker, forward=forward, eat_brake=brake)
    return single_layer(inputs, outputs, rows,
                        "hand-designed diet-aware forager for experiments/balanced-diet.toml "
                        f"(scripts/make-balanced-diet-baseline.py): crossed smell steering, "
                        f"gain {scarce:g} for the scarce types C and D and {common:g} "
                        f"for A and B; whisker avoidance {whisker:g}, forward "
                        f"{forward:g}, brake {brake:g} while eating")


def shock_avoidance(inputs, outputs):
    """experiments/shock-avoidance.toml: towards the food's smell (component 1, gain 4), away
    from the nettles' (component 2, gain 2)."""
    rows = vehicle(inputs, towards=[(1, 4.0)], away=[(2, 2.0)], whisker=1.5, forward=0.5,
                   eat_brake=0.5)
    return single_layer(inputs, outputs, rows,
                        "hand-designed shock avoider for experiments/shock-avoidance.toml "
                        "(scripts/make-vehicle.py): crossed food-smell steering (4), uncrossed "
                        "nettle-smell steering away (2), whisker avoidance 1.5, forward 0.5, "
                        "brake 0.5 while eating")


def crowded_arena(inputs, outputs):
    """experiments/crowded-arena.toml: towards the food's smell (component 1, gain 4), away
    from the stinging wanderers' (component 6, gain 4)."""
    rows = vehicle(inputs, towards=[(1, 4.0)], away=[(6, 4.0)], whisker=1.5, forward=0.5,
                   eat_brake=0.5)
    return single_layer(inputs, outputs, rows,
                        "hand-designed forager that keeps clear of the stinging wanderers, for "
                        "experiments/crowded-arena.toml (scripts/make-vehicle.py): crossed "
                        "food-smell steering (4), wanderer-smell steering away (4), whisker "
                        "avoidance 1.5, forward 0.5, brake 0.5 while eating")


def eye_arena(inputs, outputs):
    """experiments/eye-arena.toml: green-minus-red pixels of the retina wired crossed (gain
    0.05 per pixel; grey walls cancel), forward 1.0."""
    rows = vehicle(inputs, whisker=1.5, forward=1.0, eat_brake=0.5, eye=(0.05, 1, 0))
    return single_layer(inputs, outputs, rows,
                        "hand-designed eye vehicle for experiments/eye-arena.toml "
                        "(scripts/make-vehicle.py): crossed green-minus-red retina wiring "
                        "(gain 0.05 per pixel), forward 1.0, whisker avoidance 1.5, brake 0.5 "
                        "while eating")


def t_maze(inputs, outputs):
    """experiments/t-maze.toml: drive up the stem, turn off walls, and steer gently towards
    the goal's odour (component 1): at the junction it appears first in the receptor on the
    goal's side (the other is still behind the corner), so it turns into the rewarded arm."""
    rows = vehicle(inputs, towards=[(1, 2.0)], whisker=0.3, forward=0.8)
    return single_layer(inputs, outputs, rows, _design2(
        "t-maze", "forward drive, whisker turn-away, steer towards the goal's smell"))


def locked_room(inputs, outputs):
    """experiments/locked-room.toml: follow the door trigger's odour (component 8) to the
    doorstep, and the food's smell (component 1, which comes through the doorway once the
    door is open) more strongly, so that it wins over the trigger's."""
    rows = vehicle(inputs, towards=[(8, 1.5), (1, 8.0)], whisker=1.0, forward=1.0)
    return single_layer(inputs, outputs, rows, _design2(
        "locked-room",
        "follow the trigger's scent, then (stronger) the food's smell, whisker turn-away"))


def landmark_arena(inputs, outputs):
    """experiments/landmark-arena.toml: a landmark compass. Landmark 1's sin(bearing) (> 0:
    on the right) drives the left motor up and the right one down (gain 1), against a turning
    bias of ±0.707 (sin 45°): it turns until the landmark lies 45° to its left, the heading
    towards the south-east patch; it forages by the food's smell on the way."""
    rows = vehicle(inputs, towards=[(1, 4.0)], whisker=1.5, forward=0.5, eat_brake=0.5,
                   extra=[("landmark_1_sin", 1.0, -1.0), ("bias", 0.707, -0.707)])
    return single_layer(inputs, outputs, rows, _design2(
        "landmark-arena",
        "landmark compass towards the south-east patch, forage by smell, whisker turn-away"))


def _design2(name, what):
    return (f"hand-designed baseline for experiments/{name}.toml "
            f"(scripts/make-design2-baselines.py): {what}")
