"""Hand-designed genomes (scripts/genomes/): the builders of the baselines in genomes/.

Python standard library only. Each builder reads the experiment's input layout from
`berry-evolve inspect EXPERIMENT --json` (its observation groups' names), so the weights land
on the right inputs whatever sensor groups the experiment turns on. Run from the repository
root, after `cargo build --release`; each command writes the committed file byte for byte:

  python3 -m scripts.genomes braitenberg-forager   # genomes/braitenberg-forager.json
  python3 -m scripts.genomes balanced-diet         # genomes/balanced-diet-baseline.json
  python3 -m scripts.genomes shock-avoidance       # genomes/shock-avoidance-baseline.json
  python3 -m scripts.genomes crowded-arena         # genomes/crowded-arena-baseline.json
  python3 -m scripts.genomes eye-arena             # genomes/eye-arena-baseline.json
  python3 -m scripts.genomes t-maze                # genomes/t-maze-baseline.json
  python3 -m scripts.genomes locked-room           # genomes/locked-room-baseline.json
  python3 -m scripts.genomes landmark-arena        # genomes/landmark-arena-baseline.json
  python3 -m scripts.genomes predator-arena        # genomes/predator-arena-baseline.json
  python3 -m scripts.genomes air-raid              # genomes/air-raid-baseline.json
  python3 -m scripts.genomes t-maze-switch         # genomes/t-maze-switch-baseline.json
  python3 -m scripts.genomes all                   # every one of them

Options: `--experiment FILE` (another experiment's layout, e.g. an ablation), `--out FILE`
(`-` for standard output), `--binary BIN` (default target/release/berry-evolve); tuning
options of balanced-diet (--common --scarce --whisker --forward --brake), predator-arena
(--threshold --kn) and air-raid (--gf --gs --b --c --home --forward --whisker --brake), as
used to choose them on the design set (`compare --worlds design`).

  python3 -m scripts.genomes vehicle EXPERIMENT [--forward F --spin S --steer G
      --odours 1,2 --avoid-odours K:G --whisker W --brake E --shock-back S --eye G
      --eye-channel C --eye-opponent C --description TEXT] [--out FILE]

writes any Braitenberg vehicle or cheap control (standing, spinning, driving straight) for
an experiment's layout, to standard output by default.

Modules: layout (inspect --json), write (the genome document and its bytes), vehicle (the
single-layer wiring), baselines (the single-layer baselines), predator_arena and air_raid
(the two hand-wired hidden-layer networks).
"""
