//! What `replay`, `render`, `compare` and `summary` share about whose worlds a genome meets:
//! the named world sets (`--worlds held-out|validation|training`), how their trials are titled
//! ("held-out world 2", "validation world 2", "trial 2 of generation 5"), the experiment file
//! of a run folder's genome (`--experiment` left out), and the warning for a genome replayed in
//! another experiment than the one that evolved it.

use crate::cli::console::errln;

use anyhow::Context;
use berry_evolve::evo::validation::validation_worlds;
use berry_evolve::experiment::Experiment;
use berry_evolve::record::genome_file::GenomeFile;
use berry_evolve::run::EXPERIMENT_FILE;
use berry_evolve::seed::Generation;
use berry_evolve::sim::world::World;
use clap::ValueEnum;
use std::path::{Path, PathBuf};

/// Generation number whose trial worlds serve as the held-out test set: far beyond any run's
/// length, so no individual was ever selected on them. `--generation 1099511627776` (its
/// value, 2^40) still names them.
pub const HELD_OUT_GENERATION: u64 = 1 << 40;

/// `--worlds`: a named set of trial worlds.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum WorldsChoice {
    /// The held-out worlds: never used in training or validation (`compare`'s default).
    HeldOut,
    /// The experiment's `[validation]` worlds, on which best.json is chosen.
    Validation,
    /// A generation's training worlds (`--generation G`).
    Training,
}

/// Whose trial worlds, resolved.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum WorldSet {
    /// Generation G's training worlds ([`berry_evolve::seed::Purpose::TrialWorld`] streams).
    Training(u64),
    /// The held-out worlds: the training streams of [`HELD_OUT_GENERATION`], group 0.
    HeldOut,
    /// The experiment's validation worlds
    /// ([`berry_evolve::seed::Purpose::ValidationWorld`] streams).
    Validation,
}

impl WorldSet {
    /// Generation `g`'s worlds: the held-out set for [`HELD_OUT_GENERATION`] (so the old
    /// `--generation 1099511627776` form is named like `--worlds held-out`).
    pub fn of_generation(g: u64) -> WorldSet {
        if g == HELD_OUT_GENERATION {
            WorldSet::HeldOut
        } else {
            WorldSet::Training(g)
        }
    }

    /// The set `--worlds` and `--generation` name: `default` when neither is given, and the
    /// training worlds of `--generation` (else `default_generation`) for `training`. A
    /// generation given with another set is refused: it would be silently ignored.
    pub fn choose(
        worlds: Option<WorldsChoice>,
        generation: Option<u64>,
        default: WorldsChoice,
        default_generation: u64,
    ) -> anyhow::Result<WorldSet> {
        let choice = match (worlds, generation) {
            (Some(c @ (WorldsChoice::HeldOut | WorldsChoice::Validation)), Some(g)) => {
                anyhow::bail!(
                    "--generation {g} names a generation's training worlds, but --worlds {} \
                     names another set; leave out --generation, or give --worlds training \
                     --generation {g}",
                    c.to_possible_value()
                        .map_or_else(String::new, |v| v.get_name().into())
                )
            }
            (Some(c), _) => c,
            (None, Some(_)) => WorldsChoice::Training,
            (None, None) => default,
        };
        Ok(match choice {
            WorldsChoice::HeldOut => WorldSet::HeldOut,
            WorldsChoice::Validation => WorldSet::Validation,
            WorldsChoice::Training => {
                WorldSet::of_generation(generation.unwrap_or(default_generation))
            }
        })
    }

    /// The generation whose streams build the worlds (0 for the validation worlds, whose
    /// streams are of their own purpose).
    pub fn generation(self) -> Generation {
        Generation(match self {
            WorldSet::Training(g) => g,
            WorldSet::HeldOut => HELD_OUT_GENERATION,
            WorldSet::Validation => 0,
        })
    }

    /// `training`, `held-out` or `validation` (as `--worlds` spells it).
    pub fn name(self) -> &'static str {
        match self {
            WorldSet::Training(_) => "training",
            WorldSet::HeldOut => "held-out",
            WorldSet::Validation => "validation",
        }
    }

    /// The title of trial `t`: `held-out world 2`, `validation world 2`, `trial 2 of
    /// generation 5`.
    pub fn trial_title(self, t: u64) -> String {
        match self {
            WorldSet::Training(g) => format!("trial {t} of generation {g}"),
            WorldSet::HeldOut | WorldSet::Validation => format!("{} world {t}", self.name()),
        }
    }

    /// A trial's line label: `trial 2` for training worlds (as replay always printed),
    /// `held-out world 2` and `validation world 2` for the named sets.
    pub fn trial_label(self, t: u64) -> String {
        match self {
            WorldSet::Training(_) => format!("trial {t}"),
            _ => self.trial_title(t),
        }
    }

    /// `n` trials of this set: `3 trial(s) of generation 5`, `3 held-out world(s)`.
    pub fn count_text(self, n: usize) -> String {
        match self {
            WorldSet::Training(g) => format!("{n} trial(s) of generation {g}"),
            _ => format!("{n} {} world(s)", self.name()),
        }
    }

    /// `the held-out worlds (...)`, `the validation worlds (...)` or `generation G's training
    /// worlds`, as compare's first line says it.
    pub fn description(self) -> String {
        match self {
            WorldSet::HeldOut => {
                "the held-out worlds (never used in training or validation)".to_string()
            }
            WorldSet::Validation => {
                "the validation worlds (the [validation] table's, on which best.json is chosen)"
                    .to_string()
            }
            WorldSet::Training(g) => format!("generation {g}'s training worlds"),
        }
    }

    /// Refuses the validation worlds of an experiment without validation: it has none.
    pub fn check(self, experiment: &Experiment, path: &Path) -> anyhow::Result<()> {
        if self == WorldSet::Validation && !experiment.validation.enabled() {
            anyhow::bail!(
                "--worlds validation: experiment `{}` ({}) has no [validation] table (or its \
                 `every` is 0), so it has no validation worlds; add one (e.g. `[validation]` \
                 with every = 10, top = 3, trials = 10) or choose --worlds held-out",
                experiment.name,
                path.display()
            );
        }
        Ok(())
    }

    /// How many worlds the set has in `experiment`: `[validation] trials` for the validation
    /// worlds, `[evaluation] trials` for the others.
    pub fn trials(self, experiment: &Experiment) -> u64 {
        match self {
            WorldSet::Validation => experiment.validation.trials,
            _ => experiment.evaluation.trials,
        }
    }

    /// The validation worlds (for one creature each) of `experiment`, exactly those a run's
    /// validation evaluates on; None for the other sets, whose trial worlds are built trial by
    /// trial from their generation's streams.
    pub fn built_worlds(self, experiment: &Experiment) -> anyhow::Result<Option<Vec<World>>> {
        match self {
            WorldSet::Validation => Ok(Some(validation_worlds(experiment)?)),
            _ => Ok(None),
        }
    }

    /// `experiment` with `trials` worlds in this set (the validation table's `trials` for
    /// the validation worlds, `[evaluation] trials` for the others), validated again.
    pub fn with_trials(self, experiment: &Experiment, trials: u64) -> anyhow::Result<Experiment> {
        let overrides = experiment.with_overrides();
        let overrides = match self {
            WorldSet::Validation => overrides.edit(|c| c.validation.trials = trials),
            _ => overrides.trials(trials),
        };
        overrides
            .build()
            .with_context(|| format!("--trials {trials}"))
    }
}

/// The experiment file to use: `given`, or else the one run folder's `experiment.toml` beside
/// the genome files (a run's best.json, or a genome extracted into the run folder), said in a
/// note line. Refuses when there is none, or several that differ (the worlds would depend on
/// which was taken).
pub fn experiment_file(given: Option<&Path>, genomes: &[PathBuf]) -> anyhow::Result<PathBuf> {
    if let Some(path) = given {
        return Ok(path.to_path_buf());
    }
    let mut found: Vec<(&PathBuf, PathBuf, Vec<u8>)> = Vec::new();
    for genome in genomes {
        let dir = match genome.parent() {
            Some(d) if !d.as_os_str().is_empty() => d,
            _ => Path::new("."),
        };
        let candidate = dir.join(EXPERIMENT_FILE);
        if !candidate.is_file() {
            continue;
        }
        let bytes = std::fs::read(&candidate)
            .with_context(|| format!("cannot read {}", candidate.display()))?;
        if !found.iter().any(|(_, _, b)| *b == bytes) {
            found.push((genome, candidate, bytes));
        }
    }
    match found.as_slice() {
        [] => {
            let whose = genomes
                .first()
                .map_or("no genome file was given".to_string(), |g| {
                    format!("there is no {EXPERIMENT_FILE} beside {}", g.display())
                });
            anyhow::bail!(
                "which experiment? {whose}; give --experiment EXPERIMENT.toml (a genome in a \
                 run folder, such as RUN/best.json, uses its run's {EXPERIMENT_FILE} by itself)"
            )
        }
        [(genome, path, _)] => {
            errln!(
                "note: experiment file {} (beside {}); --experiment chooses another",
                path.display(),
                genome.display()
            );
            Ok(path.clone())
        }
        [(_, a, _), (_, b, _), ..] => anyhow::bail!(
            "which experiment? the genome files lie beside different experiment files ({} and \
             {}, e.g. runs with other seeds), and the worlds depend on which; give --experiment \
             EXPERIMENT.toml for the worlds they should all meet",
            a.display(),
            b.display()
        ),
    }
}

/// The first 12 characters of a config hash.
fn short(hash: &str) -> &str {
    &hash[..hash.len().min(12)]
}

/// Warns when `file`'s origin names another experiment than `experiment` (by name; the config
/// hashes are shown when known), even when their observation layouts match so that the genome
/// runs: its fitness there answers another task than the one it was selected for. Returns true
/// when it warned.
pub fn warn_other_experiment(
    file: &GenomeFile,
    genome: &Path,
    experiment: &Experiment,
    experiment_path: &Path,
) -> bool {
    let Some(origin) = &file.origin.experiment else {
        return false;
    };
    if *origin == experiment.name {
        return false;
    }
    let evolved = file
        .origin
        .config_hash
        .as_deref()
        .map_or(String::new(), |h| format!(", config hash {}", short(h)));
    errln!(
        "warning: {} was evolved in experiment `{origin}`{evolved}, but is evaluated here in \
         experiment `{}` ({}, config hash {}): another task, so its fitness here is not the one \
         it was selected for; give --experiment with `{origin}`'s file to meet its own worlds",
        genome.display(),
        experiment.name,
        experiment_path.display(),
        short(&experiment.config_hash())
    );
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn named_sets_and_the_old_generation_agree() {
        let choose = |w, g| WorldSet::choose(w, g, WorldsChoice::Training, 7).unwrap();
        assert_eq!(choose(None, None), WorldSet::Training(7));
        assert_eq!(choose(None, Some(3)), WorldSet::Training(3));
        assert_eq!(choose(None, Some(HELD_OUT_GENERATION)), WorldSet::HeldOut);
        assert_eq!(choose(Some(WorldsChoice::HeldOut), None), WorldSet::HeldOut);
        assert_eq!(
            choose(Some(WorldsChoice::Training), Some(5)),
            WorldSet::Training(5)
        );
        assert_eq!(
            choose(Some(WorldsChoice::Validation), None),
            WorldSet::Validation
        );
        let e = WorldSet::choose(
            Some(WorldsChoice::HeldOut),
            Some(3),
            WorldsChoice::HeldOut,
            0,
        )
        .unwrap_err()
        .to_string();
        assert!(
            e.contains("--worlds held-out") && e.contains("--worlds training"),
            "{e}"
        );
        assert_eq!(WorldSet::HeldOut.trial_title(2), "held-out world 2");
        assert_eq!(WorldSet::Validation.trial_title(2), "validation world 2");
        assert_eq!(
            WorldSet::Training(5).trial_title(2),
            "trial 2 of generation 5"
        );
        assert_eq!(
            WorldSet::HeldOut.generation(),
            Generation(HELD_OUT_GENERATION)
        );
    }
}
