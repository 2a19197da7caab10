"""`python3 -m scripts.genomes NAME`: writes the hand-designed genome NAME (see __init__)."""
import argparse
import sys

from . import air_raid, baselines, learner, predator_arena
from .layout import BINARY, layout, motor_layout
from .vehicle import vehicle
from .write import dump, single_layer

# name: (builder, default experiment, default output file)
GENOMES = {
    "braitenberg-forager": (baselines.braitenberg_forager, "foraging",
                            "braitenberg-forager"),
    "balanced-diet": (baselines.balanced_diet, "balanced-diet", "balanced-diet-baseline"),
    "shock-avoidance": (baselines.shock_avoidance, "shock-avoidance",
                        "shock-avoidance-baseline"),
    "crowded-arena": (baselines.crowded_arena, "crowded-arena", "crowded-arena-baseline"),
    "eye-arena": (baselines.eye_arena, "eye-arena", "eye-arena-baseline"),
    "t-maze": (baselines.t_maze, "t-maze", "t-maze-baseline"),
    "locked-room": (baselines.locked_room, "locked-room", "locked-room-baseline"),
    "landmark-arena": (baselines.landmark_arena, "landmark-arena", "landmark-arena-baseline"),
    "predator-arena": (None, "predator-arena", "predator-arena-baseline"),
    "air-raid": (None, "air-raid", "air-raid-baseline"),
    "t-maze-switch": (learner.t_maze_switch, "t-maze-switch", "t-maze-switch-baseline"),
}

# Tuning options, per genome: (option, default); None = the builder's own default.
TUNING = {
    "balanced-diet": [("common", 0.75), ("scarce", 8.0), ("whisker", 1.0), ("forward", 1.25),
                      ("brake", 0.0)],
    "predator-arena": [("threshold", None), ("kn", predator_arena.KN)],
    "air-raid": [("gf", 6.0), ("gs", None), ("b", 20.0), ("c", 0.5), ("home", None),
                 ("forward", 1.1), ("whisker", 1.5), ("brake", 1.0)],
}


def build(name, experiment, binary, gains):
    """The genome document of `name` for `experiment`'s layout."""
    inputs, outputs = motor_layout(experiment, binary)
    if name == "predator-arena":
        return predator_arena.build(inputs, **gains)
    if name == "air-raid":
        return air_raid.build(inputs, outputs, **gains)
    return GENOMES[name][0](inputs, outputs, **gains)


def vehicle_main(argv):
    """`vehicle EXPERIMENT [gains]`: any vehicle or cheap control, to standard output."""
    ap = argparse.ArgumentParser(prog="python3 -m scripts.genomes vehicle")
    ap.add_argument("experiment")
    ap.add_argument("--binary", default=BINARY)
    ap.add_argument("--out", default="-")
    for g in ["forward", "spin", "steer", "whisker", "brake", "shock_back", "eye"]:
        ap.add_argument("--" + g.replace("_", "-"), type=float, default=0.0)
    ap.add_argument("--odours", default="1,2,3,4")
    ap.add_argument("--avoid-odours", action="append", default=[])
    ap.add_argument("--eye-channel", type=int, default=1)
    ap.add_argument("--eye-opponent", type=int, default=None,
                    help="a colour channel subtracted from --eye-channel (e.g. 0: green - red, "
                         "so grey walls cancel)")
    ap.add_argument("--description", default="hand-designed vehicle (scripts/genomes)")
    a = ap.parse_args(argv)
    inputs, outputs = layout(a.experiment, a.binary)
    if outputs[:2] != ["motor_left", "motor_right"]:
        sys.exit(f"{a.experiment}: expected outputs motor_left, motor_right first, "
                 f"got {outputs}")
    present = {n for n in inputs}
    towards = [(int(k), a.steer) for k in a.odours.split(",") if k
               and f"smell_left_{k}" in present]
    away = [(int(k), float(g)) for k, g in (s.split(":") for s in a.avoid_odours)
            if f"smell_left_{k}" in present]
    rows = vehicle(inputs, towards=towards, away=away, whisker=a.whisker, forward=a.forward,
                   eat_brake=a.brake, spin=a.spin, shock_back=a.shock_back,
                   eye=(a.eye, a.eye_channel, a.eye_opponent) if a.eye else None)
    dump(single_layer(inputs, outputs, rows, a.description), a.out)


def main(argv):
    if argv[:1] == ["vehicle"]:
        return vehicle_main(argv[1:])
    ap = argparse.ArgumentParser(prog="python3 -m scripts.genomes",
                                 description="Writes a hand-designed genome of genomes/.")
    ap.add_argument("name", choices=[*GENOMES, "all", "vehicle"])
    ap.add_argument("--experiment", help="default experiments/<its experiment>.toml")
    ap.add_argument("--out", help="default genomes/<its file>.json; - for standard output")
    ap.add_argument("--binary", default=BINARY)
    for opt in sorted({o for options in TUNING.values() for o, _ in options}):
        ap.add_argument("--" + opt, type=float, help="tuning (see the builder's docs)")
    a = ap.parse_args(argv)
    names = list(GENOMES) if a.name == "all" else [a.name]
    if len(names) > 1 and (a.experiment or a.out):
        sys.exit("--experiment and --out name one genome's files; give a genome's name")
    for name in names:
        _, experiment, out = GENOMES[name]
        gains = {}
        for opt, default in TUNING.get(name, []):
            value = getattr(a, opt)
            if value is not None:
                gains[opt] = value
            elif default is not None:
                gains[opt] = default
        given = {o for o in vars(a) if o not in ("name", "experiment", "out", "binary")
                 and getattr(a, o) is not None}
        unknown = given - {o for o, _ in TUNING.get(name, [])}
        if unknown:
            sys.exit(f"{name} has no tuning option {', '.join('--' + u for u in sorted(unknown))}")
        document = build(name, a.experiment or f"experiments/{experiment}.toml", a.binary, gains)
        dump(document, a.out or f"genomes/{out}.json")


if __name__ == "__main__":
    main(sys.argv[1:])
