//! What `replay`, `render`, `compare` and `summary` share about whose worlds a genome meets,
//! on the command line: `--worlds held-out|validation|training|design` and `--generation` resolved to
//! a library [`WorldSet`] (the sets themselves, their titles and their evaluation live in
//! [`berry_evolve::evo::worlds`], which the Python package uses too), the experiment file of a
//! run folder's genome (`--experiment` left out), and the warning for a genome replayed in
//! another experiment than the one that evolved it.

use crate::cli::console::errln;

use anyhow::Context;
pub use berry_evolve::evo::worlds::WorldSet;
use berry_evolve::experiment::Experiment;
use berry_evolve::record::genome_file::GenomeFile;
use berry_evolve::run::EXPERIMENT_FILE;
use clap::ValueEnum;
use std::path::{Path, PathBuf};

/// `--worlds`: a named set of trial worlds.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum WorldsChoice {
    /// The held-out worlds: never used in training or validation (`compare`'s default).
    HeldOut,
    /// The experiment's `[validation]` worlds, on which best.json is chosen.
    Validation,
    /// A generation's training worlds (`--generation G`).
    Training,
    /// The design worlds, where hand-designed controllers and settings are tuned, never
    /// the held-out ones.
    Design,
}

/// What the command line adds to a [`WorldSet`]: resolving `--worlds` and `--generation`,
/// refusals worded with the flags, and `--trials`.
pub trait WorldSetArgs: Sized {
    /// The set `--worlds` and `--generation` name: `default` when neither is given, and the
    /// training worlds of `--generation` (else `default_generation`) for `training`. A
    /// generation given with another set is refused: it would be silently ignored.
    fn choose(
        worlds: Option<WorldsChoice>,
        generation: Option<u64>,
        default: WorldsChoice,
        default_generation: u64,
    ) -> anyhow::Result<Self>;

    /// Refuses the validation worlds of an experiment without validation: it has none.
    fn check_file(self, experiment: &Experiment, path: &Path) -> anyhow::Result<()>;

    /// `experiment` with `trials` worlds in this set (the validation table's `trials` for
    /// the validation worlds, `[evaluation] trials` for the others), validated again.
    fn with_trials(self, experiment: &Experiment, trials: u64) -> anyhow::Result<Experiment>;
}

impl WorldSetArgs for WorldSet {
    fn choose(
        worlds: Option<WorldsChoice>,
        generation: Option<u64>,
        default: WorldsChoice,
        default_generation: u64,
    ) -> anyhow::Result<WorldSet> {
        let choice = match (worlds, generation) {
            (
                Some(c @ (WorldsChoice::HeldOut | WorldsChoice::Validation | WorldsChoice::Design)),
                Some(g),
            ) => {
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
            WorldsChoice::Design => WorldSet::Design,
            WorldsChoice::Training => {
                WorldSet::of_generation(generation.unwrap_or(default_generation))
            }
        })
    }

    fn check_file(self, experiment: &Experiment, path: &Path) -> anyhow::Result<()> {
        if self.check(experiment).is_err() {
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

    fn with_trials(self, experiment: &Experiment, trials: u64) -> anyhow::Result<Experiment> {
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
    use berry_evolve::evo::worlds::HELD_OUT_GENERATION;
    use berry_evolve::seed::Generation;

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
