//! The names of a run folder's files: the one place that spells them, so that the folder's
//! code, the errors that name them and the commands that read a run agree.

/// The effective experiment of the run, as this program writes it.
pub const EXPERIMENT_FILE: &str = "experiment.toml";
/// The fitness curve.
pub const FITNESS_FILE: &str = "fitness.csv";
/// The best genome so far.
pub const BEST_FILE: &str = "best.json";
/// Each generation's best genome, one genome file per line.
pub const CHAMPIONS_FILE: &str = "champions.jsonl";
/// The checkpoint folder.
pub const CHECKPOINT_DIR: &str = "checkpoints";
/// Where `resume --discard-newer` moves the checkpoints newer than the one resumed.
pub const DISCARDED_DIR: &str = "discarded-checkpoints";
/// The log of explicit changes to a run (config changes, shortening, discarded checkpoints).
pub const CHANGES_FILE: &str = "config-changes.log";
/// A copy of the experiment's baseline genome (`[output] baseline`), kept for the held-out
/// check of a later `resume`, which cannot resolve the key from the run folder.
pub const BASELINE_FILE: &str = "baseline.json";
