//! Extending a finished run: what its last generation did only because it was the last is
//! set aside, so that the extended run continues exactly as a run planned longer from the
//! start (same `fitness.csv`, `best.json`, `champions.jsonl` and checkpoints).
//!
//! Two things depend on where a run ends. A run validates its last generation even when
//! `[validation] every` does not schedule it, so that `best.json` has seen the end of
//! evolution; a longer run does not validate that generation. And a run writes a checkpoint of
//! its last generation (and of the generation a stop signal ends) off the `checkpoint_every`
//! schedule; a longer (or unstopped) run does not have that file. The first is undone from
//! what the final checkpoint records ([`EndOfRunValidation`]); the second by removing such a
//! checkpoint once the next checkpoint is written ([`superseded_checkpoint`]).

use crate::evo::validation::{validation_columns, ValidatedChampion};
use crate::experiment::Experiment;
use serde::{Deserialize, Serialize};

/// What a run's end-of-run validation changed: recorded in the final checkpoint when the last
/// generation was validated only because it was the last (not on `[validation] every`'s
/// schedule).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct EndOfRunValidation {
    /// Did that validation replace the champion on validation (`best.json`)?
    pub replaced_champion: bool,
    /// The champion it replaced (absent when it replaced none or kept the champion).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub previous: Option<ValidatedChampion>,
}

/// The state a run's end leaves that an extension rewinds.
pub struct Rewound {
    /// The champion on validation as a run planned longer has it after that generation.
    pub validated_best: Option<ValidatedChampion>,
    /// The last generation's extra `fitness.csv` columns without the end-of-run validation.
    pub last_extra: Vec<Option<f64>>,
}

/// Sets aside the end-of-run validation `end` of a finished run of `experiment` (the
/// experiment the checkpoint was written with) whose champion on validation is now `current`
/// and whose last generation's extra columns are `last_extra`.
pub fn rewind(
    experiment: &Experiment,
    end: &EndOfRunValidation,
    current: Option<ValidatedChampion>,
    last_extra: &[Option<f64>],
) -> Rewound {
    let validated_best = if end.replaced_champion {
        end.previous.clone()
    } else {
        current
    };
    // The measure columns stay; the validation columns become those of an unvalidated row;
    // the columns after them (an archive's metrics) stay.
    let measures = 2 * experiment.behaviour.measures.len();
    let validation = validation_columns(experiment, None);
    let after = last_extra.iter().skip(measures + validation.len()).copied();
    let mut extra: Vec<Option<f64>> = last_extra.iter().take(measures).copied().collect();
    extra.extend(validation);
    extra.extend(after);
    Rewound {
        validated_best,
        last_extra: extra,
    }
}

/// Is the checkpoint of generation `older`, found when the checkpoint of `generation` is
/// written, one that a run never stopped and planned this long would not have? Such a
/// checkpoint (a shorter run's last, or one written at a stop signal) is off the schedule of
/// `every` and newer than the last scheduled generation before `generation`; it was needed
/// only to continue from, and the new checkpoint replaces it. Older checkpoints, on the
/// schedule or not (e.g. before `checkpoint_every` was edited), are left to `keep_checkpoints`.
pub fn superseded_checkpoint(every: u64, generation: u64, older: u64) -> bool {
    let every = every.max(1);
    // The last scheduled generation before `generation` ((g + 1) % every == 0), if any.
    let last_scheduled = (generation / every)
        .checked_mul(every)
        .and_then(|g| g.checked_sub(1));
    older < generation && (older + 1) % every != 0 && last_scheduled.is_none_or(|s| older > s)
}

#[cfg(test)]
mod tests {
    use super::superseded_checkpoint;

    #[test]
    fn only_the_interim_checkpoints_since_the_last_scheduled_one_are_superseded() {
        // checkpoint_every 5: generations 4, 9, 14 are scheduled.
        assert!(
            superseded_checkpoint(5, 14, 11),
            "a stop at 11 is replaced by 14"
        );
        assert!(
            superseded_checkpoint(5, 4, 2),
            "a 3-generation run's last, by 4"
        );
        assert!(!superseded_checkpoint(5, 14, 9), "scheduled");
        assert!(
            !superseded_checkpoint(5, 14, 7),
            "before the last scheduled one"
        );
        assert!(!superseded_checkpoint(5, 14, 14), "itself");
        assert!(
            superseded_checkpoint(5, 12, 10),
            "a stop at 10, then another at 12"
        );
        assert!(
            !superseded_checkpoint(1, 3, 2),
            "every generation is scheduled"
        );
    }
}
