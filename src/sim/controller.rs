//! The controller boundary: what a creature's sensors give its controller each tick (an
//! observation laid out by [`ObservationLayout`]) and what the controller gives back
//! ([`MotorCommand`]). The simulator knows nothing else about brains.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use std::ops::Range;
use std::sync::OnceLock;

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
    /// For each distal landmark (§4.5.3), its bearing relative to the heading as (sin, cos):
    /// straight ahead is (0, 1), to the creature's right (clockwise on screen, y down) is
    /// (1, 0), behind is (0, −1). Two inputs per landmark of `[[world.landmarks]]`.
    Landmarks,
    /// One input per area of `[[world.areas]]` (§4.6): 1 while the body centre is inside.
    Areas,
    /// The retina of the eye (§7.4): `width × height × 3` values in [0, 1], row-major
    /// (top row first, left column first), each pixel R, G, B.
    Eye,
    /// A constant 1, so that networks without biases can still shift their units.
    Bias,
}

impl SensorGroup {
    /// Every group, in the order they appear in an observation.
    ///
    /// The groups added after the report's own senses (landmarks, areas, eye) sit after the
    /// metabolism and before the bias; they are off by default, so genomes made for the
    /// original layout keep their meaning.
    pub const ORDER: [SensorGroup; 9] = [
        SensorGroup::Smell,
        SensorGroup::Whiskers,
        SensorGroup::Food,
        SensorGroup::Shock,
        SensorGroup::Metabolism,
        SensorGroup::Landmarks,
        SensorGroup::Areas,
        SensorGroup::Eye,
        SensorGroup::Bias,
    ];

    /// The group in plain words, for people (`inspect`): "smell sensors", "eye (retina)".
    pub fn label(self) -> &'static str {
        match self {
            SensorGroup::Smell => "smell sensors (8 receptors left, 8 right)",
            SensorGroup::Whiskers => "whiskers",
            SensorGroup::Food => "food detectors",
            SensorGroup::Shock => "shock sensor",
            SensorGroup::Metabolism => "metabolism",
            SensorGroup::Landmarks => "landmark bearings (sin, cos each)",
            SensorGroup::Areas => "areas",
            SensorGroup::Eye => "eye (retina, R G B per pixel)",
            SensorGroup::Bias => "bias (constant 1)",
        }
    }

    /// Names of the group's inputs, in order; `sizes` gives the widths that depend on the
    /// world and the creature. Landmarks and areas count from 1 in file order
    /// (`landmark_1_sin`, `landmark_1_cos`, `area_1`); eye pixels are `eye_<c>_<row>_<column>`
    /// with c one of r, g, b, rows and columns from 0.
    pub fn input_names(self, sizes: &GroupSizes) -> Vec<String> {
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
            SensorGroup::Landmarks => (1..=sizes.landmarks)
                .flat_map(|k| [format!("landmark_{k}_sin"), format!("landmark_{k}_cos")])
                .collect(),
            SensorGroup::Areas => (1..=sizes.areas).map(|k| format!("area_{k}")).collect(),
            SensorGroup::Eye => {
                let [w, h] = sizes.retina;
                (0..h)
                    .flat_map(|row| {
                        (0..w).flat_map(move |col| {
                            ["r", "g", "b"].map(|c| format!("eye_{c}_{row}_{col}"))
                        })
                    })
                    .collect()
            }
            SensorGroup::Bias => vec!["bias".into()],
        }
    }

    /// How many inputs the group contributes, given the world- and creature-dependent
    /// `sizes`.
    pub fn width(self, sizes: &GroupSizes) -> usize {
        match self {
            SensorGroup::Smell => 16,
            SensorGroup::Whiskers => 2,
            SensorGroup::Food => 4,
            SensorGroup::Shock => 1,
            SensorGroup::Metabolism => 4,
            SensorGroup::Landmarks => 2 * sizes.landmarks,
            SensorGroup::Areas => sizes.areas,
            SensorGroup::Eye => 3 * sizes.retina[0] * sizes.retina[1],
            SensorGroup::Bias => 1,
        }
    }
}

/// The sizes of the sensor groups whose width depends on the world or the creature.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct GroupSizes {
    /// Number of distal landmarks in the world.
    pub landmarks: usize,
    /// Number of areas in the world.
    pub areas: usize,
    /// Retina `[width, height]` in pixels.
    pub retina: [usize; 2],
}

/// Which sensor groups a creature's controller receives (`[creature.inputs]`).
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
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
    /// Bearings of the distal landmarks, 2 inputs each (default: off).
    #[serde(skip_serializing_if = "is_false")]
    pub landmarks: bool,
    /// Inside-area flags, 1 input per area (default: off).
    #[serde(skip_serializing_if = "is_false")]
    pub areas: bool,
    /// The eye's retina, `width × height × 3` inputs (default: off; `[creature.eye]` sets
    /// its size).
    #[serde(skip_serializing_if = "is_false")]
    pub eye: bool,
}

// Switches that are off are left out when an experiment is written back, so that experiment
// files written before these groups existed keep their config hash.
fn is_false(b: &bool) -> bool {
    !*b
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
            landmarks: false,
            areas: false,
            eye: false,
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
            SensorGroup::Landmarks => self.landmarks,
            SensorGroup::Areas => self.areas,
            SensorGroup::Eye => self.eye,
            SensorGroup::Bias => self.bias,
        }
    }
}

/// Where each input sits in an observation vector: the groups switched on, in
/// [`SensorGroup::ORDER`], each a contiguous range.
///
/// Every trial world builds its layout, and the names (90 strings for a 30-pixel retina) are
/// only wanted by traces, genome files and `inspect`: they are made on first use. Two
/// layouts are equal when they have the same groups, ranges and input names.
#[derive(Debug, Clone)]
pub struct ObservationLayout {
    groups: Vec<(SensorGroup, Range<usize>)>,
    sizes: GroupSizes,
    len: usize,
    names: OnceLock<Vec<String>>,
}

impl PartialEq for ObservationLayout {
    fn eq(&self, other: &Self) -> bool {
        self.groups == other.groups && self.names() == other.names()
    }
}

impl Eq for ObservationLayout {}

impl ObservationLayout {
    /// The layout for the groups `inputs` switches on, with the world- and
    /// creature-dependent widths `sizes`. A group switched on with width 0 (landmarks in a
    /// world without landmarks) is listed with an empty range.
    pub fn new(inputs: &InputsSpec, sizes: &GroupSizes) -> Self {
        let mut groups = Vec::new();
        let mut len = 0;
        for group in SensorGroup::ORDER {
            if inputs.includes(group) {
                let start = len;
                len += group.width(sizes);
                groups.push((group, start..len));
            }
        }
        ObservationLayout {
            groups,
            sizes: *sizes,
            len,
            names: OnceLock::new(),
        }
    }

    /// Number of inputs.
    pub fn len(&self) -> usize {
        self.len
    }

    /// True when no group is switched on.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Names of the inputs, in order (`smell_left_1`, …, `bias`).
    pub fn names(&self) -> &[String] {
        self.names.get_or_init(|| {
            let names: Vec<String> = self
                .groups
                .iter()
                .flat_map(|(group, _)| group.input_names(&self.sizes))
                .collect();
            debug_assert_eq!(
                names.len(),
                self.len,
                "SensorGroup::width and input_names agree"
            );
            names
        })
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

    /// The layout counts inputs with `width` and names them lazily with `input_names`: the
    /// two must agree for every group and size.
    #[test]
    fn widths_count_the_names() {
        for sizes in [
            GroupSizes::default(),
            GroupSizes {
                landmarks: 3,
                areas: 2,
                retina: [30, 1],
            },
            GroupSizes {
                landmarks: 1,
                areas: 5,
                retina: [7, 4],
            },
        ] {
            for group in SensorGroup::ORDER {
                assert_eq!(
                    group.width(&sizes),
                    group.input_names(&sizes).len(),
                    "{group:?}"
                );
            }
            let all = InputsSpec {
                metabolism: true,
                landmarks: true,
                areas: true,
                eye: true,
                ..InputsSpec::default()
            };
            let layout = ObservationLayout::new(&all, &sizes);
            assert_eq!(layout.len(), layout.names().len());
            assert_eq!(
                layout.groups().last().map(|(_, r)| r.end),
                Some(layout.len())
            );
        }
    }

    #[test]
    fn default_layout_is_documented_order() {
        let layout = ObservationLayout::new(&InputsSpec::default(), &GroupSizes::default());
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
        let layout = ObservationLayout::new(&inputs, &GroupSizes::default());
        assert_eq!(layout.range(SensorGroup::Whiskers), Some(0..2));
        assert_eq!(layout.range(SensorGroup::Metabolism), Some(7..11));
        assert_eq!(layout.names().last().map(String::as_str), Some("bias"));
    }

    #[test]
    fn new_groups_sit_between_metabolism_and_bias() {
        let inputs = InputsSpec {
            metabolism: true,
            landmarks: true,
            areas: true,
            eye: true,
            ..InputsSpec::default()
        };
        let sizes = GroupSizes {
            landmarks: 2,
            areas: 3,
            retina: [4, 2],
        };
        let layout = ObservationLayout::new(&inputs, &sizes);
        assert_eq!(layout.range(SensorGroup::Metabolism), Some(23..27));
        assert_eq!(layout.range(SensorGroup::Landmarks), Some(27..31));
        assert_eq!(layout.range(SensorGroup::Areas), Some(31..34));
        assert_eq!(layout.range(SensorGroup::Eye), Some(34..58));
        assert_eq!(layout.range(SensorGroup::Bias), Some(58..59));
        let names = layout.names();
        assert_eq!(names[27], "landmark_1_sin");
        assert_eq!(names[28], "landmark_1_cos");
        assert_eq!(names[30], "landmark_2_cos");
        assert_eq!(names[31], "area_1");
        assert_eq!(names[33], "area_3");
        assert_eq!(names[34], "eye_r_0_0");
        assert_eq!(names[35], "eye_g_0_0");
        assert_eq!(names[36], "eye_b_0_0");
        assert_eq!(names[37], "eye_r_0_1");
        // Row-major: row 1 starts after the 4 pixels of row 0.
        assert_eq!(names[34 + 12], "eye_r_1_0");
        assert_eq!(names[57], "eye_b_1_3");
    }

    #[test]
    fn new_groups_off_keep_the_default_layout() {
        let sizes = GroupSizes {
            landmarks: 2,
            areas: 3,
            retina: [16, 1],
        };
        assert_eq!(
            ObservationLayout::new(&InputsSpec::default(), &sizes),
            ObservationLayout::new(&InputsSpec::default(), &GroupSizes::default())
        );
    }
}
