//! Scripted controllers for tests and demos (no brain): constant motor signals, or a
//! Braitenberg vehicle steering towards a smell; and the `[demo]` table that picks one.

use crate::sim::controller::{Controller, MotorCommand, ObservationLayout, SensorGroup};
use crate::validate::{count_within, finite, InvalidValue, Valid};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// Most creatures a demo may run.
pub const MAX_DEMO_CREATURES: u64 = 1_000;

/// The `[demo]` table: how the `simulate` command fills a world without evolved brains.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct DemoSpec {
    /// Number of creatures, each driven by its own copy of `controller` (default: 1).
    pub creatures: usize,
    /// The scripted controller (`[demo.controller]`; default: a constant gentle right turn).
    pub controller: ScriptedSpec,
}

impl Default for DemoSpec {
    fn default() -> Self {
        DemoSpec {
            creatures: 1,
            controller: ScriptedSpec::default(),
        }
    }
}

impl DemoSpec {
    /// Checks every value; keys start with `demo.`.
    pub fn validate(&self) -> Valid {
        count_within(
            "demo.creatures",
            self.creatures as u64,
            1,
            MAX_DEMO_CREATURES,
            "a demo is for watching",
        )?;
        self.controller.validate("demo.controller")
    }
}

/// A scripted controller, chosen with `kind`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum ScriptedSpec {
    /// Fixed motor signals every tick.
    Constant {
        /// Left motor in RPT.
        left: f64,
        /// Right motor in RPT.
        right: f64,
    },
    /// Braitenberg's vehicle 2b (crossed excitatory connections): each motor is driven by
    /// the receptor on the other side, so the side nearer the smell turns the vehicle towards
    /// it. left = base + gain · right receptor, right = base + gain · left receptor.
    Braitenberg {
        /// Which receptor (1–8) of each smell sensor drives the motors.
        receptor: usize,
        /// RPT per unit of receptor activation.
        gain: f64,
        /// RPT of each motor with no smell.
        base: f64,
    },
}

impl Default for ScriptedSpec {
    /// A gentle right turn: the left wheel a little faster than the right.
    fn default() -> Self {
        ScriptedSpec::Constant {
            left: 0.1,
            right: 0.05,
        }
    }
}

impl ScriptedSpec {
    /// Checks every value; keys start with `key_prefix`.
    pub fn validate(&self, key_prefix: &str) -> Valid {
        match self {
            ScriptedSpec::Constant { left, right } => {
                finite(&format!("{key_prefix}.left"), *left)?;
                finite(&format!("{key_prefix}.right"), *right)
            }
            ScriptedSpec::Braitenberg {
                receptor,
                gain,
                base,
            } => {
                count_within(
                    &format!("{key_prefix}.receptor"),
                    *receptor as u64,
                    1,
                    8,
                    "a smell sensor has 8 receptors",
                )?;
                finite(&format!("{key_prefix}.gain"), *gain)?;
                finite(&format!("{key_prefix}.base"), *base)
            }
        }
    }

    /// The controller for creatures whose observations follow `layout`. A Braitenberg
    /// vehicle needs the smell inputs.
    pub fn build(&self, layout: &ObservationLayout) -> Result<Scripted, InvalidValue> {
        self.validate("demo.controller")?;
        match *self {
            ScriptedSpec::Constant { left, right } => Ok(Scripted::Constant(MotorCommand {
                left,
                right,
                eat: 1.0,
            })),
            ScriptedSpec::Braitenberg {
                receptor,
                gain,
                base,
            } => {
                let smell = layout.range(SensorGroup::Smell).ok_or_else(|| {
                    InvalidValue::new(
                        "demo.controller.kind",
                        "a braitenberg vehicle needs smell input; set creature.inputs.smell = true",
                    )
                })?;
                Ok(Scripted::Braitenberg {
                    left_receptor: smell.start + receptor - 1,
                    right_receptor: smell.start + 8 + receptor - 1,
                    gain,
                    base,
                })
            }
        }
    }
}

/// A scripted controller. Both kinds always ask to eat (`eat = 1`), so they also feed under
/// `eating = "action"`.
#[derive(Debug, Clone, PartialEq)]
pub enum Scripted {
    /// The same command every tick.
    Constant(MotorCommand),
    /// Vehicle 2b; the receptors are indices into the observation.
    Braitenberg {
        /// Index of the chosen receptor of the left smell sensor.
        left_receptor: usize,
        /// Index of the chosen receptor of the right smell sensor.
        right_receptor: usize,
        /// RPT per unit of activation.
        gain: f64,
        /// RPT with no smell.
        base: f64,
    },
}

impl Controller for Scripted {
    fn act(&mut self, observation: &[f64]) -> MotorCommand {
        match *self {
            Scripted::Constant(command) => command,
            Scripted::Braitenberg {
                left_receptor,
                right_receptor,
                gain,
                base,
            } => {
                // Crossed wiring: a stronger smell on the right speeds up the left wheel, and
                // φ = (d_L − d_R)/w > 0 turns clockwise on screen, i.e. to the right (§8.1).
                MotorCommand {
                    left: base + gain * observation[right_receptor],
                    right: base + gain * observation[left_receptor],
                    eat: 1.0,
                }
            }
        }
    }
}
