//! The controller boundary: what a creature's sensors give its controller each tick (an
//! observation laid out by [`ObservationLayout`]) and what the controller gives back
//! ([`MotorCommand`]). The simulator knows nothing else about brains.

use serde::{Deserialize, Serialize};
use std::ops::Range;

/// What a controller asks of the body for one tick.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct MotorCommand {
    /// Left motor in rotations per tick (RPT); the simulator clamps it to ±`max_rpt`.
    pub left: f64,
    /// Right motor in RPT; clamped like `left`.
    pub right: f64,
    /// Eat output in [0, 1]; with `eating = "action"` the creature eats when it exceeds 0.5.
    /// Ignored with `eating = "contact"`.
    pub eat: f64,
}

/// Anything that turns an observation into a motor command: a scripted vehicle, or a brain.
pub trait Controller {
    /// Called once per tick with the creature's observation, laid out as its
    /// [`ObservationLayout`] says.
    fn act(&mut self, observation: &[f64]) -> MotorCommand;
}

impl<C: Controller + ?Sized> Controller for Box<C> {
    fn act(&mut self, observation: &[f64]) -> MotorCommand {
        (**self).act(observation)
    }
}

/// A group of sensor inputs that an experiment can switch on or off.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SensorGroup {
    /// The 8 receptors of the left smell sensor, then the 8 of the right one (§7.1), in [0, 1].
    Smell,
    /// Left and right whisker, 1 while touching (§7.3).
    Whiskers,
    /// Food detectors A, B, C, D, 1 while in contact with food holding that substance (§5.2).
    Food,
    /// The shock sensor, 1 this tick if shocked (§5.2).
    Shock,
    /// The metabolic vector m = ⟨fA, fB, fC, fD⟩ (§5.3), raw values.
    Metabolism,
    /// A constant 1, so that networks without biases can still shift their units.
    Bias,
}

impl SensorGroup {
    /// Every group, in the order they appear in an observation.
    pub const ORDER: [SensorGroup; 6] = [
        SensorGroup::Smell,
        SensorGroup::Whiskers,
        SensorGroup::Food,
        SensorGroup::Shock,
        SensorGroup::Metabolism,
        SensorGroup::Bias,
    ];

    /// Names of the group's inputs, in order.
    pub fn input_names(self) -> Vec<String> {
        match self {
            SensorGroup::Smell => ["left", "right"]
                .iter()
                .flat_map(|side| (1..=8).map(move |k| format!("smell_{side}_{k}")))
                .collect(),
            SensorGroup::Whiskers => vec!["whisker_left".into(), "whisker_right".into()],
            SensorGroup::Food => ["a", "b", "c", "d"]
                .iter()
                .map(|t| format!("food_{t}"))
                .collect(),
            SensorGroup::Shock => vec!["shock".into()],
            SensorGroup::Metabolism => ["a", "b", "c", "d"]
                .iter()
                .map(|t| format!("metabolism_{t}"))
                .collect(),
            SensorGroup::Bias => vec!["bias".into()],
        }
    }

    /// How many inputs the group contributes.
    pub fn width(self) -> usize {
        match self {
            SensorGroup::Smell => 16,
            SensorGroup::Whiskers => 2,
            SensorGroup::Food => 4,
            SensorGroup::Shock => 1,
            SensorGroup::Metabolism => 4,
            SensorGroup::Bias => 1,
        }
    }
}

/// Which sensor groups a creature's controller receives (`[creature.inputs]`).
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct InputsSpec {
    /// Both smell sensors, 16 inputs (default: on).
    pub smell: bool,
    /// Both whiskers, 2 inputs (default: on).
    pub whiskers: bool,
    /// The four food detectors (default: on).
    pub food: bool,
    /// The shock sensor (default: on).
    pub shock: bool,
    /// The metabolic vector (default: off).
    pub metabolism: bool,
    /// A constant 1 input (default: on).
    pub bias: bool,
}

impl Default for InputsSpec {
    fn default() -> Self {
        InputsSpec {
            smell: true,
            whiskers: true,
            food: true,
            shock: true,
            metabolism: false,
            bias: true,
        }
    }
}

impl InputsSpec {
    /// Is `group` switched on?
    pub fn includes(&self, group: SensorGroup) -> bool {
        match group {
            SensorGroup::Smell => self.smell,
            SensorGroup::Whiskers => self.whiskers,
            SensorGroup::Food => self.food,
            SensorGroup::Shock => self.shock,
            SensorGroup::Metabolism => self.metabolism,
            SensorGroup::Bias => self.bias,
        }
    }
}

/// Where each input sits in an observation vector: the groups switched on, in
/// [`SensorGroup::ORDER`], each a contiguous range.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct ObservationLayout {
    groups: Vec<(SensorGroup, Range<usize>)>,
    names: Vec<String>,
}

impl ObservationLayout {
    /// The layout for the groups `inputs` switches on.
    pub fn new(inputs: &InputsSpec) -> Self {
        let mut groups = Vec::new();
        let mut names = Vec::new();
        for group in SensorGroup::ORDER {
            if inputs.includes(group) {
                let start = names.len();
                names.extend(group.input_names());
                groups.push((group, start..names.len()));
            }
        }
        ObservationLayout { groups, names }
    }

    /// Number of inputs.
    pub fn len(&self) -> usize {
        self.names.len()
    }

    /// True when no group is switched on.
    pub fn is_empty(&self) -> bool {
        self.names.is_empty()
    }

    /// Names of the inputs, in order (`smell_left_1`, …, `bias`).
    pub fn names(&self) -> &[String] {
        &self.names
    }

    /// The groups switched on and their ranges in the observation.
    pub fn groups(&self) -> &[(SensorGroup, Range<usize>)] {
        &self.groups
    }

    /// The range of `group`, if it is switched on.
    pub fn range(&self, group: SensorGroup) -> Option<Range<usize>> {
        self.groups
            .iter()
            .find(|(g, _)| *g == group)
            .map(|(_, r)| r.clone())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_layout_is_documented_order() {
        let layout = ObservationLayout::new(&InputsSpec::default());
        assert_eq!(layout.len(), 16 + 2 + 4 + 1 + 1);
        assert_eq!(layout.names()[0], "smell_left_1");
        assert_eq!(layout.names()[8], "smell_right_1");
        assert_eq!(layout.names()[16], "whisker_left");
        assert_eq!(layout.names()[18], "food_a");
        assert_eq!(layout.names()[22], "shock");
        assert_eq!(layout.names()[23], "bias");
        assert_eq!(layout.range(SensorGroup::Food), Some(18..22));
        assert_eq!(layout.range(SensorGroup::Metabolism), None);
    }

    #[test]
    fn switching_groups_moves_ranges() {
        let inputs = InputsSpec {
            smell: false,
            metabolism: true,
            ..InputsSpec::default()
        };
        let layout = ObservationLayout::new(&inputs);
        assert_eq!(layout.range(SensorGroup::Whiskers), Some(0..2));
        assert_eq!(layout.range(SensorGroup::Metabolism), Some(7..11));
        assert_eq!(layout.names().last().map(String::as_str), Some("bias"));
    }
}
