//! The fitness terms beyond the metabolic gain, declared once: each one's key, unit, report
//! section, what it counts and its words. Validation, the reference page, `inspect` and the
//! scoring (`evo::fitness`) all read this table, so a term cannot mean one thing in the
//! score and another on the page.
//!
//! Adding a term (docs/fitness.md): a field in [`FitnessSpec`] (its doc comment, and the
//! formula in the struct's doc) and one entry here. A term that counts something no term
//! counts yet also adds a [`Quantity`], which the compiler then asks `evo::fitness` to
//! accumulate. `experiment::reference`'s tests refuse a `*_bonus` or `*_penalty` field without an entry.

use super::tables::FitnessSpec;
use super::GoalAt;
use crate::validate::{finite, non_negative, Valid};

/// What a term multiplies its weight by, accumulated over a life by `evo::fitness`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Quantity {
    /// Ticks at whose end the creature was alive (and its brain's output finite).
    TicksAlive,
    /// Ticks alive at whose end its centre was inside `[fitness] area`.
    TicksInArea,
    /// `max(0, 1 − d / goal_range)`, d the distance to the goal (at the end, or closest).
    GoalNearness,
    /// Distinct food objects it took substance from.
    DistinctFood,
    /// LU its centre moved forward along its heading at each tick's start.
    ForwardDistance,
    /// Ticks alive with a threat near and its centre inside a safe area.
    ShelteredThreatTicks,
    /// 1 when it is dead at the end of the trial, else 0.
    Died,
    /// 1 when the episode's first bite of the two `[evaluation.switch]` kinds was of the
    /// kind that pays in it, else 0 (a life of K episodes sums K of them).
    CorrectFirstChoice,
}

/// What a life must follow, beyond its end, for a quantity to be counted: the plan
/// (`evo::fitness::LifePlan`) switches on the matching tracker when a term counting it is on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Follows {
    /// Nothing: the end of the life (or the ticks, always counted) is enough.
    End,
    /// The pose every tick.
    Pose,
    /// The food objects it bites.
    Bites,
    /// Threats near and safe areas every tick.
    Threats,
    /// Its bites of the `[evaluation.switch]` kinds, in order (needs the switch).
    Choices,
}

impl Quantity {
    /// What a life must follow to count it.
    pub const fn follows(self) -> Follows {
        match self {
            Quantity::TicksAlive | Quantity::Died => Follows::End,
            // The area and the goal come with their own tables (`area`, `goal`), which the
            // plan resolves against the world.
            Quantity::TicksInArea | Quantity::GoalNearness => Follows::End,
            Quantity::DistinctFood => Follows::Bites,
            Quantity::ForwardDistance => Follows::Pose,
            Quantity::ShelteredThreatTicks => Follows::Threats,
            Quantity::CorrectFirstChoice => Follows::Choices,
        }
    }
}

/// Whether a term adds to the score or takes from it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Sign {
    /// `score + weight × quantity` (a bonus; a negative weight is allowed).
    Add,
    /// `score − weight × quantity` (a penalty; the weight may not be negative).
    Subtract,
}

/// One fitness term.
#[derive(Debug, Clone, Copy)]
pub struct Term {
    /// Its key in `[fitness]`.
    pub key: &'static str,
    /// Its key as the derived schema and the reference page name it.
    pub schema_key: &'static str,
    /// The unit of its weight ("per tick"), or "".
    pub unit: &'static str,
    /// The BERRY III report section (or SPEC-NOTES decision) it serves.
    pub section: &'static str,
    /// A constraint beyond its range, for the reference page, or "".
    pub note: &'static str,
    /// Adds or subtracts.
    pub sign: Sign,
    /// What it counts.
    pub counts: Quantity,
    /// Does it pay for where the creature goes or how far it drives (so that even an empty
    /// world can tell lives apart)?
    pub pays_for_motion: bool,
    /// Its weight in a `[fitness]` table.
    pub weight: fn(&FitnessSpec) -> f64,
    /// What follows its weight in `inspect`'s words ("× tick alive", "if killed").
    pub words: fn(&FitnessSpec) -> String,
}

/// `[fitness]`'s report section for terms the report leaves open.
const EVAL: &str = "§5.3 (fitness left open; SPEC-NOTES)";

/// Every term, in the order the score adds them up (the order is part of the bits).
pub const TERMS: [Term; 8] = [
    Term {
        key: "alive_bonus",
        schema_key: "FitnessSpec.alive_bonus",
        unit: "per tick",
        section: EVAL,
        note: "",
        sign: Sign::Add,
        counts: Quantity::TicksAlive,
        pays_for_motion: false,
        weight: |f| f.alive_bonus,
        words: |_| "× tick alive".into(),
    },
    Term {
        key: "area_bonus",
        schema_key: "FitnessSpec.area_bonus",
        unit: "per tick",
        section: "§4.6",
        note: "needs `area`",
        sign: Sign::Add,
        counts: Quantity::TicksInArea,
        pays_for_motion: true,
        weight: |f| f.area_bonus,
        words: |f| format!("× tick in area `{}`", f.area.as_deref().unwrap_or("?")),
    },
    Term {
        key: "goal_bonus",
        schema_key: "FitnessSpec.goal_bonus",
        unit: "",
        section: EVAL,
        note: "needs `goal` or `goal_point`",
        sign: Sign::Add,
        counts: Quantity::GoalNearness,
        pays_for_motion: true,
        weight: |f| f.goal_bonus,
        words: goal_words,
    },
    Term {
        key: "distinct_food_bonus",
        schema_key: "FitnessSpec.distinct_food_bonus",
        unit: "",
        section: EVAL,
        note: "",
        sign: Sign::Add,
        counts: Quantity::DistinctFood,
        pays_for_motion: false,
        weight: |f| f.distinct_food_bonus,
        words: |_| "× distinct food object eaten".into(),
    },
    Term {
        key: "forward_bonus",
        schema_key: "FitnessSpec.forward_bonus",
        unit: "per LU",
        section: EVAL,
        note: "",
        sign: Sign::Add,
        counts: Quantity::ForwardDistance,
        pays_for_motion: true,
        weight: |f| f.forward_bonus,
        words: |_| "× LU driven forward".into(),
    },
    Term {
        key: "shelter_bonus",
        schema_key: "FitnessSpec.shelter_bonus",
        unit: "per tick",
        section: "§4.7",
        note: "a threat is within [behaviour] threat_radius",
        sign: Sign::Add,
        counts: Quantity::ShelteredThreatTicks,
        pays_for_motion: false,
        weight: |f| f.shelter_bonus,
        words: |_| "× tick in a safe area with a predator near".into(),
    },
    Term {
        key: "death_penalty",
        schema_key: "FitnessSpec.death_penalty",
        unit: "",
        section: "§4.7, §5.3",
        note: "",
        sign: Sign::Subtract,
        counts: Quantity::Died,
        pays_for_motion: false,
        weight: |f| f.death_penalty,
        words: |_| "if killed".into(),
    },
    Term {
        key: "choice_bonus",
        schema_key: "FitnessSpec.choice_bonus",
        unit: "per episode",
        section: "§5 (learning; issue 31)",
        note: "needs [evaluation.switch]",
        sign: Sign::Add,
        counts: Quantity::CorrectFirstChoice,
        pays_for_motion: false,
        weight: |f| f.choice_bonus,
        words: |_| "× episode whose first choice paid".into(),
    },
];

/// How many terms there are.
pub const TERM_COUNT: usize = TERMS.len();

/// The goal term's words: where the goal is and when the distance is taken.
fn goal_words(f: &FitnessSpec) -> String {
    let goal = match (&f.goal, f.goal_point) {
        (Some(area), _) => format!("area `{area}`"),
        (None, Some([x, y])) => format!("[{x}, {y}]"),
        (None, None) => String::new(),
    };
    let when = match f.goal_at {
        GoalAt::End => "at the end",
        GoalAt::Closest => "at its closest",
    };
    format!("× nearness to {goal} {when}")
}

impl FitnessSpec {
    /// Checks each term's weight: finite, and not negative for a penalty.
    pub fn validate_terms(&self) -> Valid {
        for term in &TERMS {
            let key = format!("fitness.{}", term.key);
            let weight = (term.weight)(self);
            match term.sign {
                Sign::Add => finite(&key, weight)?,
                Sign::Subtract => non_negative(&key, weight)?,
            }
        }
        Ok(())
    }

    /// Does some term that is on pay for where the creature goes or how far it drives?
    pub fn pays_for_motion(&self) -> bool {
        TERMS
            .iter()
            .any(|t| t.pays_for_motion && (t.weight)(self) != 0.0)
    }

    /// The first term that is on and follows `follows`, if any.
    pub fn term_following(&self, follows: Follows) -> Option<&'static Term> {
        TERMS
            .iter()
            .find(|t| t.counts.follows() == follows && (t.weight)(self) != 0.0)
    }

    /// Is every term off (weight 0)?
    pub fn terms_off(&self) -> bool {
        TERMS.iter().all(|t| (t.weight)(self) == 0.0)
    }
}

/// Each term's weight in `spec`, in [`TERMS`] order.
pub fn weights(spec: &FitnessSpec) -> [f64; TERM_COUNT] {
    std::array::from_fn(|i| (TERMS[i].weight)(spec))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn weights_follow_the_table_order() {
        let spec = FitnessSpec {
            alive_bonus: 1.0,
            forward_bonus: 5.0,
            death_penalty: 7.0,
            ..FitnessSpec::default()
        };
        assert_eq!(weights(&spec), [1.0, 0.0, 0.0, 0.0, 5.0, 0.0, 7.0, 0.0]);
    }
}
