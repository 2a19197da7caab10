//! A creature (§5): its pose, its metabolic state m and what it sensed and did in its last
//! tick. The world owns its creatures; the senses, the eye and fitness read them.

use crate::sim::controller::MotorCommand;
use crate::sim::motion::Pose;
use crate::sim::smell::Smell;

/// One creature: its pose, its metabolism and what it sensed and did in its last tick.
#[derive(Debug, Clone, PartialEq)]
pub struct Creature {
    /// Where the body is and which way it faces.
    pub pose: Pose,
    /// The metabolic state m = ⟨fA, fB, fC, fD⟩ (§5.3).
    pub metabolism: [f64; 4],
    /// Total substance received by eating over its life, per type (before any decay).
    pub eaten: [f64; 4],
    /// Shock state at the end of its last tick: its body touched an aversive object after
    /// moving, or (with `wall_shock`) a wall stopped its move. The shock sensor reads this at
    /// the start of the next tick.
    pub shocked: bool,
    /// Number of ticks that ended with `shocked` set.
    pub shock_ticks: u64,
    /// Living creatures sense, move, eat, block others and are felt and smelled by them.
    pub alive: bool,
    /// Distance travelled over its life in LU.
    pub travelled: f64,
    /// Number of ticks it has lived through.
    pub age: u64,
    /// Left and right whisker at the start of its last tick (§7.3).
    pub whiskers: [bool; 2],
    /// Left and right smell sensors at the start of its last tick, 8 receptors each (§7.1).
    /// All zeros when smell was not computed (see [`World::set_full_sensing`](crate::sim::world::World::set_full_sensing)). Without sensor
    /// noise: noise goes only into the observation.
    pub smell: [[f64; 8]; 2],
    /// Food detectors A–D at the start of its last tick (§5.2).
    pub food_detectors: [bool; 4],
    /// The motor command of its last tick, after clamping to ±`max_rpt`.
    pub command: MotorCommand,
    /// Its last move was cut short by an obstacle.
    pub blocked: bool,
    /// The smell its body gives off to the other creatures (`[creature] odour`, or its own
    /// of `odours`, §5.1).
    pub body_smell: Smell,
}

impl Creature {
    pub(crate) fn new(pose: Pose, metabolism: [f64; 4], body_smell: Smell) -> Creature {
        Creature {
            body_smell,
            pose,
            metabolism,
            eaten: [0.0; 4],
            shocked: false,
            shock_ticks: 0,
            alive: true,
            travelled: 0.0,
            age: 0,
            whiskers: [false; 2],
            smell: [[0.0; 8]; 2],
            food_detectors: [false; 4],
            command: MotorCommand::default(),
            blocked: false,
        }
    }
}
