//! The experiment files shipped in `experiments/`, built into the program (`include_str!`),
//! so that an installed binary works from any folder: `berry-evolve new NAME --from foraging`
//! starts a new experiment from one of them, and `bench` measures its default worlds without a
//! checkout of the repository.
//!
//! A template is the shipped file's text byte for byte, comments included; only its `name`
//! changes when it is written out ([`Template::with_name`]). The only other file a shipped
//! experiment names is its baseline genome (`[output] baseline = "../genomes/..."`, relative
//! to `experiments/`), which only the end-of-run held-out check reads: written elsewhere, the
//! template still runs as it stands, and the check leaves the missing baseline out with a note.

use super::{Experiment, ExperimentError};
use std::path::Path;
use thiserror::Error;

/// One built-in experiment file.
#[derive(Debug)]
pub struct Template {
    /// What `--from` calls it: the file name without `.toml` (`foraging`).
    pub name: &'static str,
    /// Where it lies in the repository (`experiments/foraging.toml`).
    pub file: &'static str,
    /// The file's text as shipped.
    pub text: &'static str,
}

/// Builds the table of shipped files under `experiments/<dir>` from their names.
macro_rules! shipped {
    ($dir:literal: $($name:literal),* $(,)?) => {
        &[$(Template {
            name: $name,
            file: concat!("experiments/", $dir, $name, ".toml"),
            text: include_str!(concat!("../../experiments/", $dir, $name, ".toml")),
        }),*]
    };
}

/// Every experiment of `experiments/*.toml`, in file-name order (a test checks that the list
/// equals the folder, so a new experiment cannot be forgotten here).
pub const TEMPLATES: &[Template] = shipped!("":
    "air-raid",
    "balanced-diet",
    "crowded-arena",
    "eye-arena",
    "foraging",
    "landmark-arena",
    "locked-room",
    "open-arena",
    "predator-arena",
    "shock-avoidance",
    "t-maze",
    "t-maze-switch",
    "walled-arena",
    "which-food",
);

/// `bench`'s default simulator worlds (`experiments/bench/`): the standard world, which is
/// also the base of the scaling series, and the one with the eye and every kind of actor.
pub const BENCH_WORLDS: &[Template] = shipped!("bench/":
    "foraging-world",
    "eye-predators-world",
);

/// Why a template could not be given a new name.
#[derive(Debug, Error)]
pub enum TemplateError {
    /// The file has no top-level `name = "..."` line to replace (a shipped file always has one;
    /// a test checks it).
    #[error("{file} has no top-level `name = \"...\"` line to replace")]
    NoNameLine {
        /// The template's file.
        file: &'static str,
    },
    /// The file with the new name is not a valid experiment (the name is not a plain folder
    /// name, for instance).
    #[error(transparent)]
    Invalid(#[from] ExperimentError),
}

/// The template called `name`; `foraging.toml` and `experiments/foraging.toml` name it too.
pub fn find(name: &str) -> Option<&'static Template> {
    let bare = name.strip_prefix("experiments/").unwrap_or(name);
    let bare = bare.strip_suffix(".toml").unwrap_or(bare);
    TEMPLATES.iter().find(|t| t.name == bare)
}

impl Template {
    /// The template as a validated experiment; errors name it `experiments/<name>.toml (built in)`.
    pub fn experiment(&self) -> Result<Experiment, ExperimentError> {
        Experiment::from_toml(self.text, &self.origin())
    }

    /// How errors and messages name the built-in copy.
    pub fn origin(&self) -> std::path::PathBuf {
        std::path::PathBuf::from(format!("{} (built in)", self.file))
    }

    /// What the experiment is for, in one line: the first sentence of the file's opening
    /// comment (its lines joined, up to the first full stop that ends a sentence).
    pub fn purpose(&self) -> String {
        let comment: Vec<&str> = self
            .text
            .lines()
            .map_while(|line| line.strip_prefix('#'))
            .map(str::trim)
            .take_while(|line| !line.is_empty())
            .collect();
        let text = comment.join(" ");
        // A full stop followed by a space or the end; "e.g." and "§4.5." need no special care
        // in the shipped files' first sentences.
        match text.find(". ") {
            Some(end) => text[..=end].trim_end().to_string(),
            None => text,
        }
    }

    /// The file's text with its `name` replaced by `name` (quoted as TOML quotes it), every
    /// other byte as shipped, and checked: the result must be a valid experiment named `name`.
    /// `origin` names the file in errors (where it will be written).
    pub fn with_name(&self, name: &str, origin: &Path) -> Result<String, TemplateError> {
        let mut out = String::with_capacity(self.text.len() + name.len());
        let mut replaced = false;
        let mut top_level = true;
        for line in self.text.split_inclusive('\n') {
            let trimmed = line.trim_start();
            if trimmed.starts_with('[') {
                top_level = false;
            }
            if top_level && !replaced {
                if let Some(rest) = name_value(trimmed) {
                    out.push_str("name = ");
                    out.push_str(&toml::Value::String(name.to_string()).to_string());
                    out.push_str(rest);
                    replaced = true;
                    continue;
                }
            }
            out.push_str(line);
        }
        if !replaced {
            return Err(TemplateError::NoNameLine { file: self.file });
        }
        let experiment = Experiment::from_toml(&out, origin)?;
        debug_assert_eq!(experiment.name, name);
        Ok(out)
    }
}

/// For a line `name = "value"<rest>`, the `<rest>` after the closing quote (a comment and the
/// line end); None for any other line.
fn name_value(line: &str) -> Option<&str> {
    let value = line.strip_prefix("name")?.trim_start().strip_prefix('=')?;
    let value = value.trim_start().strip_prefix('"')?;
    let close = value.find('"')?;
    Some(&value[close + 1..])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_template_is_the_shipped_file_and_a_valid_experiment() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        for t in TEMPLATES.iter().chain(BENCH_WORLDS) {
            let on_disk = std::fs::read_to_string(root.join(t.file)).unwrap();
            assert_eq!(on_disk, t.text, "{}", t.file);
            let experiment = t.experiment().unwrap_or_else(|e| panic!("{e}"));
            assert!(!experiment.name.is_empty(), "{}", t.file);
            assert!(!t.purpose().is_empty(), "{} has no opening comment", t.file);
        }
    }

    #[test]
    fn the_templates_are_exactly_the_files_of_experiments() {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("experiments");
        let mut shipped: Vec<String> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().into_string().unwrap())
            .filter_map(|f| f.strip_suffix(".toml").map(str::to_string))
            .collect();
        shipped.sort();
        let built_in: Vec<&str> = TEMPLATES.iter().map(|t| t.name).collect();
        assert_eq!(built_in, shipped, "add the new experiment to TEMPLATES");
    }

    #[test]
    fn a_renamed_template_differs_only_in_its_name() {
        for t in TEMPLATES {
            let text = t.with_name("my-run", Path::new("my-run.toml")).unwrap();
            let renamed = Experiment::from_toml(&text, Path::new("my-run.toml")).unwrap();
            let mut expected = t.experiment().unwrap().into_config();
            expected.name = "my-run".to_string();
            assert_eq!(renamed.config(), &expected, "{}", t.file);
            // Every comment is kept: only the one line changed.
            let changed: Vec<(&str, &str)> = t
                .text
                .lines()
                .zip(text.lines())
                .filter(|(a, b)| a != b)
                .collect();
            assert_eq!(changed.len(), 1, "{}: {changed:?}", t.file);
            assert_eq!(changed[0].1, "name = \"my-run\"");
            assert_eq!(t.text.lines().count(), text.lines().count());
        }
    }

    #[test]
    fn a_name_that_is_not_a_folder_name_is_refused_naming_the_key() {
        let t = find("foraging").unwrap();
        let error = t.with_name("a/b", Path::new("x.toml")).unwrap_err();
        assert!(error.to_string().contains("name"), "{error}");
        // A quote cannot end the string early and smuggle in a key: refused as a name.
        let error = t
            .with_name("x\"\nseed = \"7", Path::new("x.toml"))
            .unwrap_err();
        assert!(error.to_string().contains("`name`"), "{error}");
    }

    #[test]
    fn templates_are_found_by_name_file_name_or_path() {
        for name in ["foraging", "foraging.toml", "experiments/foraging.toml"] {
            assert_eq!(find(name).map(|t| t.name), Some("foraging"), "{name}");
        }
        assert!(find("forage").is_none());
    }

    #[test]
    fn the_purpose_is_the_opening_comments_first_sentence() {
        let t = find("foraging").unwrap();
        assert_eq!(
            t.purpose(),
            "The default main job: creatures with whiskers, smell sensors, food detectors and \
             a metabolism forage for four food types in a walled arena with interior walls."
        );
    }
}
