//! The resume's decision, pure: from the checkpoint, the experiment file in the run folder
//! and the request, what the run continues as ([`ResumePlan`]) or why it must not (a
//! [`RunError`] giving the whole command that works). It reads no file and writes none, so a
//! refused resume touches nothing and every refusal is tested without a folder.

use crate::experiment::diff::changed_keys;
use crate::experiment::{Experiment, ExperimentError};
use crate::run::error::RunError;
use crate::validate::InvalidValue;
use std::path::{Path, PathBuf};

/// What `resume` is asked to do beyond continuing.
#[derive(Debug, Clone, Copy, Default)]
pub struct ResumeRequest {
    /// Run until this many generations in total.
    pub generations: Option<u64>,
    /// Continue although experiment.toml differs from the checkpoint's experiment.
    pub allow_config_change: bool,
    /// Resume an older checkpoint although newer ones exist, moving those aside.
    pub discard_newer: bool,
    /// Accept `generations` below what the run plans.
    pub shorten: bool,
}

/// What a resume found before deciding: the checkpoint it continues from and the folder's
/// checkpoints.
pub struct Found<'a> {
    /// The target as typed (a run folder or a checkpoint file), for the commands a refusal
    /// gives.
    pub target: &'a Path,
    /// The run folder.
    pub dir: &'a Path,
    /// The checkpoint read.
    pub checkpoint: &'a Path,
    /// Its experiment (validated).
    pub experiment: &'a Experiment,
    /// Its last completed generation.
    pub last_generation: u64,
    /// Every checkpoint of the run folder, (generation, path), oldest first.
    pub checkpoints: &'a [(u64, PathBuf)],
    /// The run folder's experiment file (whether or not it exists), which errors name.
    pub experiment_path: &'a Path,
}

/// What a resume does, decided before anything is touched.
#[derive(Debug)]
pub struct ResumePlan {
    /// The experiment the run continues as (written to the folder's experiment.toml).
    pub experiment: Experiment,
    /// The file in the folder changed the experiment (`--allow-config-change`): recorded in
    /// config-changes.log.
    pub config_changed: bool,
    /// The checkpoints newer than the one resumed, to move aside (`--discard-newer`).
    pub discard: Vec<PathBuf>,
    /// `(requested, planned)` generations when `--shorten` shortens the run: recorded.
    pub shortened: Option<(u64, u64)>,
    /// Generations remain after the checkpoint's last one.
    pub extending: bool,
    /// The planned length differs from the checkpoint's: older checkpoints are rewritten
    /// with it, as a run planned this long from the start wrote them.
    pub replanned: bool,
}

/// The flags a resume needs, to name the whole command that works in a refusal.
#[derive(Debug, Clone, Copy)]
struct ResumeFlags {
    discard_newer: bool,
    allow_config_change: bool,
    shorten: bool,
}

impl ResumeFlags {
    /// `berry-evolve resume TARGET [--generations G]` with these flags.
    fn command(&self, target: &Path, generations: Option<u64>) -> String {
        let mut command = format!(
            "{} resume {}",
            crate::invocation::program(),
            target.display()
        );
        if let Some(g) = generations {
            command.push_str(&format!(" --generations {g}"));
        }
        for (on, flag) in [
            (self.discard_newer, " --discard-newer"),
            (self.shorten, " --shorten"),
            (self.allow_config_change, " --allow-config-change"),
        ] {
            if on {
                command.push_str(flag);
            }
        }
        command
    }
}

/// Refuses a run folder with a run's files but no checkpoint (`holds_run`, `checkpoints`
/// empty) when no checkpoint file was named: there is nothing to resume, only to start over
/// (with the folder's experiment.toml when `experiment_is_file`).
pub fn check_something_to_resume(
    dir: &Path,
    checkpoints: &[(u64, PathBuf)],
    holds_run: bool,
    experiment_is_file: bool,
) -> Result<(), RunError> {
    if checkpoints.is_empty() && holds_run {
        let experiment = crate::run::names::EXPERIMENT_FILE;
        return Err(RunError::NothingToResume {
            dir: dir.to_path_buf(),
            experiment: if experiment_is_file {
                dir.join(experiment).display().to_string()
            } else {
                "EXPERIMENT.toml".to_string()
            },
        });
    }
    Ok(())
}

/// Does the file in the folder (`on_disk`) describe the checkpoint's experiment with only its
/// `[output]` table edited? `[output]` decides only where and how often results are saved, so
/// the edit is honoured (and the user told).
pub fn output_edited(checkpointed: &Experiment, on_disk: Option<&Experiment>) -> bool {
    on_disk.is_some_and(|d| {
        d.config_hash() == checkpointed.config_hash() && d.output != checkpointed.output
    })
}

/// The names of `paths`' files, for messages and the change log.
pub fn file_names(paths: &[PathBuf]) -> Vec<String> {
    paths
        .iter()
        .map(|p| {
            p.file_name()
                .unwrap_or_default()
                .to_string_lossy()
                .into_owned()
        })
        .collect()
}

impl ResumePlan {
    /// Decides the resume from what was `found`, the folder's experiment file (`on_disk`,
    /// absent when there is none) and the `request`. First the experiment the run continues
    /// as; then the refusals, each giving the whole command that works with every flag this
    /// resume needs: fewer generations than the checkpoint holds, a changed experiment
    /// without `--allow-config-change`, newer checkpoints without `--discard-newer`, fewer
    /// generations than planned without `--shorten`.
    pub fn decide(
        found: &Found<'_>,
        on_disk: Option<&Experiment>,
        request: ResumeRequest,
    ) -> Result<ResumePlan, RunError> {
        let checkpointed = found.experiment;
        let last_generation = found.last_generation;
        let discard: Vec<PathBuf> = found
            .checkpoints
            .iter()
            .filter(|(g, _)| *g > last_generation)
            .map(|(_, p)| p.clone())
            .collect();
        let mut needs = ResumeFlags {
            discard_newer: request.discard_newer || !discard.is_empty(),
            allow_config_change: request.allow_config_change,
            shorten: request.shorten,
        };
        let (mut experiment, config_changed) =
            continued_experiment(found, on_disk, request.generations)?;
        needs.allow_config_change |= config_changed.is_some();
        let mut shortened = None;
        if let Some(g) = request.generations {
            if g < last_generation + 1 {
                return Err(too_few_generations(found, &experiment, needs, g));
            }
            let planned = experiment.evolution.generations;
            if g < planned {
                needs.shorten = true;
                shortened = Some((g, planned));
            }
            experiment = experiment
                .with_overrides()
                .generations(g)
                .build()
                .map_err(invalid(found))?;
        }
        let command = needs.command(found.target, request.generations);
        if let Some(on_disk) = config_changed.filter(|_| !request.allow_config_change) {
            return Err(RunError::ConfigChanged {
                path: found.experiment_path.to_path_buf(),
                checkpoint: found.checkpoint.to_path_buf(),
                hashes: format!(
                    "{} vs {}",
                    &on_disk.config_hash()[..12],
                    &checkpointed.config_hash()[..12]
                ),
                changes: changed_keys(checkpointed, on_disk).join("; "),
                command,
            });
        }
        if !discard.is_empty() && !request.discard_newer {
            return Err(RunError::NewerCheckpoints {
                dir: found.dir.to_path_buf(),
                checkpoint: found.checkpoint.to_path_buf(),
                newer: file_names(&discard).join(", "),
                command,
            });
        }
        if let Some((requested, planned)) = shortened.filter(|_| !request.shorten) {
            return Err(RunError::FewerGenerations {
                requested,
                planned,
                command,
            });
        }
        Ok(ResumePlan {
            extending: experiment.evolution.generations > last_generation + 1,
            replanned: checkpointed.evolution.generations != experiment.evolution.generations,
            config_changed: config_changed.is_some(),
            experiment,
            discard,
            shortened,
        })
    }
}

/// The experiment a resume continues as before `--generations`: the checkpoint's, or the
/// file's when it differs (returned too: a config change), or the checkpoint's with the
/// file's length (an edited `generations` extends the run unless `--generations` is given)
/// and the file's `[output]`.
fn continued_experiment<'e>(
    found: &Found<'_>,
    on_disk: Option<&'e Experiment>,
    generations: Option<u64>,
) -> Result<(Experiment, Option<&'e Experiment>), RunError> {
    let checkpointed = found.experiment;
    let Some(on_disk) = on_disk else {
        return Ok((checkpointed.clone(), None));
    };
    if on_disk.config_hash() != checkpointed.config_hash() {
        return Ok((on_disk.clone(), Some(on_disk)));
    }
    let mut experiment = checkpointed.clone();
    if on_disk.evolution.generations != experiment.evolution.generations && generations.is_none() {
        // Only the length differs: the file was edited to extend the run.
        experiment = experiment
            .with_overrides()
            .generations(on_disk.evolution.generations)
            .build()
            .map_err(invalid(found))?;
    }
    if output_edited(checkpointed, Some(on_disk)) {
        experiment = experiment
            .with_overrides()
            .output(on_disk.output.clone())
            .build()
            .map_err(invalid(found))?;
    }
    Ok((experiment, None))
}

/// The refusal of `--generations g` below the generations the checkpoint holds, offering an
/// older checkpoint that `g` fits when there is one.
fn too_few_generations(
    found: &Found<'_>,
    experiment: &Experiment,
    needs: ResumeFlags,
    g: u64,
) -> RunError {
    let older = found
        .checkpoints
        .iter()
        .rev()
        .find(|(og, _)| *og < g)
        .map_or(String::new(), |(_, p)| {
            let flags = ResumeFlags {
                discard_newer: true,
                shorten: needs.shorten || g < experiment.evolution.generations,
                ..needs
            };
            format!(
                ", or continue from an older checkpoint: {}",
                flags.command(p, Some(g))
            )
        });
    RunError::TooFewGenerations {
        requested: g,
        completed: found.last_generation + 1,
        checkpoint: found.checkpoint.to_path_buf(),
        older,
    }
}

/// An experiment the overrides made invalid, named by the folder's experiment file.
fn invalid<'a>(found: &'a Found<'_>) -> impl Fn(InvalidValue) -> ExperimentError + 'a {
    move |error| ExperimentError::Invalid {
        path: found.experiment_path.to_path_buf(),
        error,
    }
}

#[cfg(test)]
mod tests {
    use super::{check_something_to_resume, Found, ResumePlan, ResumeRequest};
    use crate::experiment::templates;
    use crate::experiment::Experiment;
    use crate::run::error::RunError;
    use std::path::{Path, PathBuf};

    /// The shipped foraging experiment planned for `generations`.
    fn foraging(generations: u64) -> Experiment {
        templates::find("foraging")
            .expect("foraging is shipped")
            .experiment()
            .expect("the template is valid")
            .with_overrides()
            .generations(generations)
            .build()
            .expect("valid")
    }

    fn checkpoints(generations: &[u64]) -> Vec<(u64, PathBuf)> {
        generations
            .iter()
            .map(|g| {
                (
                    *g,
                    PathBuf::from(format!("run/checkpoints/gen-{g:06}.json")),
                )
            })
            .collect()
    }

    /// A checkpoint of generation `last` of `experiment` in folder `run` holding `listed`.
    fn found<'a>(
        experiment: &'a Experiment,
        last: u64,
        listed: &'a [(u64, PathBuf)],
        checkpoint: &'a Path,
    ) -> Found<'a> {
        Found {
            target: Path::new("run"),
            dir: Path::new("run"),
            checkpoint,
            experiment,
            last_generation: last,
            checkpoints: listed,
            experiment_path: Path::new("run/experiment.toml"),
        }
    }

    fn request(generations: Option<u64>) -> ResumeRequest {
        ResumeRequest {
            generations,
            ..ResumeRequest::default()
        }
    }

    #[test]
    fn a_folder_with_a_run_but_no_checkpoint_is_refused() {
        let refused = check_something_to_resume(Path::new("run"), &[], true, true);
        assert!(
            matches!(&refused, Err(RunError::NothingToResume { experiment, .. }) if experiment == "run/experiment.toml"),
            "{refused:?}"
        );
        let refused = check_something_to_resume(Path::new("run"), &[], true, false);
        assert!(
            matches!(&refused, Err(RunError::NothingToResume { experiment, .. }) if experiment == "EXPERIMENT.toml"),
            "{refused:?}"
        );
        assert!(
            check_something_to_resume(Path::new("run"), &checkpoints(&[4]), true, true).is_ok()
        );
        assert!(check_something_to_resume(Path::new("run"), &[], false, false).is_ok());
    }

    #[test]
    fn fewer_generations_than_the_checkpoint_holds_are_refused_offering_an_older_one() {
        let experiment = foraging(10);
        let listed = checkpoints(&[1, 4, 9]);
        let at = found(&experiment, 9, &listed, &listed[2].1);
        let refused = ResumePlan::decide(&at, Some(&experiment), request(Some(6)));
        match refused {
            Err(RunError::TooFewGenerations {
                requested,
                completed,
                older,
                ..
            }) => {
                assert_eq!((requested, completed), (6, 10));
                assert!(
                    older.ends_with(
                        "resume run/checkpoints/gen-000004.json --generations 6 --discard-newer --shorten"
                    ),
                    "{older}"
                );
            }
            other => panic!("expected TooFewGenerations, got {other:?}"),
        }
        // No older checkpoint fits: nothing offered.
        let listed = checkpoints(&[9]);
        let at = found(&experiment, 9, &listed, &listed[0].1);
        let refused = ResumePlan::decide(&at, None, request(Some(3)));
        assert!(
            matches!(&refused, Err(RunError::TooFewGenerations { older, .. }) if older.is_empty()),
            "{refused:?}"
        );
    }

    #[test]
    fn a_changed_experiment_is_refused_without_allow_config_change() {
        let experiment = foraging(10);
        let edited = experiment
            .with_overrides()
            .seed(experiment.seed + 1)
            .build()
            .expect("valid");
        let listed = checkpoints(&[4]);
        let at = found(&experiment, 4, &listed, &listed[0].1);
        let refused = ResumePlan::decide(&at, Some(&edited), request(None));
        match refused {
            Err(RunError::ConfigChanged {
                changes, command, ..
            }) => {
                assert!(changes.contains("seed"), "{changes}");
                assert!(
                    command.ends_with("resume run --allow-config-change"),
                    "{command}"
                );
            }
            other => panic!("expected ConfigChanged, got {other:?}"),
        }
        let allowed = ResumeRequest {
            allow_config_change: true,
            ..request(None)
        };
        let plan = ResumePlan::decide(&at, Some(&edited), allowed).expect("allowed");
        assert!(plan.config_changed);
        assert_eq!(plan.experiment.seed, edited.seed);
    }

    #[test]
    fn newer_checkpoints_are_refused_without_discard_newer() {
        let experiment = foraging(10);
        let listed = checkpoints(&[4, 9]);
        let at = found(&experiment, 4, &listed, &listed[0].1);
        let refused = ResumePlan::decide(&at, Some(&experiment), request(None));
        match refused {
            Err(RunError::NewerCheckpoints { newer, command, .. }) => {
                assert_eq!(newer, "gen-000009.json");
                assert!(command.ends_with("resume run --discard-newer"), "{command}");
            }
            other => panic!("expected NewerCheckpoints, got {other:?}"),
        }
        let discarding = ResumeRequest {
            discard_newer: true,
            ..request(None)
        };
        let plan = ResumePlan::decide(&at, Some(&experiment), discarding).expect("allowed");
        assert_eq!(plan.discard, vec![listed[1].1.clone()]);
        assert!(!plan.replanned && plan.extending);
    }

    #[test]
    fn fewer_generations_than_planned_are_refused_without_shorten() {
        let experiment = foraging(10);
        let listed = checkpoints(&[4]);
        let at = found(&experiment, 4, &listed, &listed[0].1);
        let refused = ResumePlan::decide(&at, Some(&experiment), request(Some(8)));
        match refused {
            Err(RunError::FewerGenerations {
                requested,
                planned,
                command,
            }) => {
                assert_eq!((requested, planned), (8, 10));
                assert!(
                    command.ends_with("resume run --generations 8 --shorten"),
                    "{command}"
                );
            }
            other => panic!("expected FewerGenerations, got {other:?}"),
        }
        let shortening = ResumeRequest {
            shorten: true,
            ..request(Some(8))
        };
        let plan = ResumePlan::decide(&at, None, shortening).expect("allowed");
        assert_eq!(plan.shortened, Some((8, 10)));
        assert_eq!(plan.experiment.evolution.generations, 8);
        assert!(plan.replanned);
    }

    #[test]
    fn an_edited_length_or_output_table_is_honoured_without_a_flag() {
        let experiment = foraging(4);
        let mut longer = foraging(6);
        longer = longer
            .with_overrides()
            .edit(|c| c.output.checkpoint_every += 1)
            .build()
            .expect("valid");
        let listed = checkpoints(&[3]);
        let at = found(&experiment, 3, &listed, &listed[0].1);
        assert!(super::output_edited(&experiment, Some(&longer)));
        let plan = ResumePlan::decide(&at, Some(&longer), request(None)).expect("no refusal");
        assert!(!plan.config_changed && plan.extending && plan.replanned);
        assert_eq!(plan.experiment.evolution.generations, 6);
        assert_eq!(plan.experiment.output, longer.output);
    }
}
