//! The first choices of an episode, as the switch measures (`adapted_choice`,
//! `good_bite_share`) follow them: which food objects belong to the two switch kinds, which
//! of them pays in this episode's world, and the creature's bites of them in order.

use crate::evo::trial_plan::TrialPlan;
use crate::sim::metabolism::weighted;
use crate::sim::world::World;

/// What the switch measures watch in one episode's world: the food objects of the two switch
/// kinds, in [`World::food`] order, and whether each is of the kind that pays there.
#[derive(Debug, Clone, PartialEq)]
pub struct ChoicePlan {
    objects: Vec<(usize, bool)>,
}

impl ChoicePlan {
    /// The plan in `world` for the experiment's switch kinds (None without a switch). The
    /// paying kind is read off the world's objects as built (their substance, weighted by
    /// `[fitness] weights`), so it holds whatever the episode's payoffs are; a kind with no
    /// object in the world is never the paying one. Made before the first tick.
    pub fn new(plan: &TrialPlan, world: &World) -> Option<ChoicePlan> {
        let switch = plan.switch?;
        let index = |name: &String| world.kinds().iter().position(|k| k == name);
        let kinds = [index(&switch.kinds[0])?, index(&switch.kinds[1])?];
        let value = |kind: usize| {
            world
                .food()
                .iter()
                .find(|f| f.kind == kind)
                .map_or(f64::NEG_INFINITY, |f| {
                    weighted(&plan.fitness.weights, &f.amount)
                })
        };
        let paying = if value(kinds[0]) >= value(kinds[1]) {
            kinds[0]
        } else {
            kinds[1]
        };
        let objects = world
            .food()
            .iter()
            .enumerate()
            .filter(|(_, f)| kinds.contains(&f.kind))
            .map(|(k, f)| (k, f.kind == paying))
            .collect();
        Some(ChoicePlan { objects })
    }
}

/// One episode's bites of the two switch kinds: a bite is the first taking from an object
/// (each object counts once per episode).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct EpisodeChoices {
    /// Whether its first bite was of the paying kind (None: it bit neither kind).
    pub first: Option<bool>,
    /// Bites, the first included.
    pub bites: u64,
    /// Bites of the paying kind, the first included.
    pub good: u64,
}

/// Follows one creature's bites of the switch kinds tick by tick.
#[derive(Debug, Clone, PartialEq)]
pub struct ChoiceTrack {
    seen: Vec<bool>,
    choices: EpisodeChoices,
}

impl ChoiceTrack {
    /// Nothing bitten yet.
    pub fn new(plan: &ChoicePlan) -> ChoiceTrack {
        ChoiceTrack {
            seen: vec![false; plan.objects.len()],
            choices: EpisodeChoices::default(),
        }
    }

    /// Notes the objects first bitten in the tick that just ended (`bitten` from
    /// [`World::bitten`]); several in one tick count in the world's order.
    #[inline]
    pub fn record(&mut self, plan: &ChoicePlan, bitten: &[bool]) {
        for (seen, &(k, pays)) in self.seen.iter_mut().zip(&plan.objects) {
            if !*seen && bitten.get(k) == Some(&true) {
                *seen = true;
                self.choices.bites += 1;
                self.choices.good += u64::from(pays);
                self.choices.first.get_or_insert(pays);
            }
        }
    }

    /// The episode's choices so far.
    pub fn choices(&self) -> EpisodeChoices {
        self.choices
    }
}
