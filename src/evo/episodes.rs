//! Lives of several episodes (`[evaluation] episodes_per_life`) and switches
//! (`[evaluation.switch]`): where each episode's world comes from, which episodes have the
//! two switch kinds' payoffs exchanged, how the episodes' outcomes make the life's, and the
//! per-episode bookkeeping of the switch measures (`adapted_choice`, `good_bite_share`).
//!
//! A life's worlds are a family of seed streams below the stream of its first world (its
//! [`LifeOrigin`]): episode 1 is that world itself, so a life of one episode is the trial
//! of before, bit for bit; episode e > 1 is built from [`sub_stream`] with e as an extra
//! coordinate. Every trial path (one world at a time in [`crate::evo::trial`], lockstep in
//! [`crate::evo::lockstep`]) builds them here, so they agree to the bit.

use crate::evo::fitness::MEASURE_COUNT;
use crate::evo::life::{world_error, EvaluationError, TrialOutcome};
use crate::evo::trial_plan::TrialPlan;
use crate::experiment::{Measure, SwitchStart};
use crate::seed::{below, sub_stream, Generation, IndividualId, Purpose, Rng, TrialIndex};
use crate::sim::spec::{KindSpec, WorldSpec};
use crate::sim::world::{ValidSpecs, World};
use std::borrow::Cow;

pub use crate::evo::choices::{ChoicePlan, ChoiceTrack, EpisodeChoices};

/// Where a life's first world comes from: the coordinates of its seed stream. The later
/// episodes' worlds and the life's switch draws are streams below it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct LifeOrigin {
    /// The first world's purpose ([`Purpose::TrialWorld`], [`Purpose::ValidationWorld`]).
    pub purpose: Purpose,
    /// Its generation coordinate.
    pub generation: Generation,
    /// Its individual coordinate (0 with common random numbers).
    pub individual: IndividualId,
    /// Its trial coordinate.
    pub trial: TrialIndex,
}

impl LifeOrigin {
    /// The life in trial `trial` of generation `generation` for group `group`: the origin
    /// of [`crate::evo::life::trial_stream`]'s world.
    pub fn trial(
        plan: &TrialPlan,
        generation: Generation,
        group: u64,
        trial: TrialIndex,
    ) -> LifeOrigin {
        let who = if plan.common_random_numbers { 0 } else { group };
        LifeOrigin {
            purpose: Purpose::TrialWorld,
            generation,
            individual: IndividualId(who),
            trial,
        }
    }

    /// The life in validation world `trial` (see
    /// [`crate::evo::worlds::validation_worlds`]).
    pub fn validation(trial: TrialIndex) -> LifeOrigin {
        LifeOrigin {
            purpose: Purpose::ValidationWorld,
            generation: Generation(0),
            individual: IndividualId(0),
            trial,
        }
    }

    /// The same family of worlds, trial `trial` (pre-built world lists give the origin of
    /// their first world).
    pub fn with_trial(self, trial: TrialIndex) -> LifeOrigin {
        LifeOrigin { trial, ..self }
    }

    /// The stream of episode `episode`'s world (0-based; episode 0 is the life's first
    /// world, the stream a life of one episode has always had).
    pub fn episode_stream(&self, plan: &TrialPlan, episode: u64) -> Rng {
        let extra: &[u64] = if episode == 0 { &[] } else { &[episode] };
        sub_stream(
            plan.seed,
            self.purpose,
            self.generation,
            self.individual,
            self.trial,
            extra,
        )
    }

    /// The stream of the life's switch draws.
    fn switch_stream(&self, plan: &TrialPlan) -> Rng {
        sub_stream(
            plan.seed,
            Purpose::Switch,
            self.generation,
            self.individual,
            self.trial,
            &[self.purpose as u64],
        )
    }
}

/// Which episodes of a life have the switch kinds' payoffs exchanged, drawn per life.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Schedule {
    /// Per episode (0-based): the payoffs are exchanged (relative to `[world.kinds]`).
    pub exchanged: Vec<bool>,
    /// Per episode: it starts a phase (episode 0, and each episode a switch comes before).
    pub phase_start: Vec<bool>,
}

impl Schedule {
    /// The schedule of the life at `origin`: `start = "random"` draws first (one draw, 50:50),
    /// then each `at` range one uniform draw in lo..=hi, in order. Without
    /// `[evaluation.switch]` nothing is exchanged and only episode 0 starts a phase.
    pub fn draw(plan: &TrialPlan, origin: LifeOrigin) -> Schedule {
        let k = plan.episodes_per_life.max(1) as usize;
        let mut exchanged = vec![false; k];
        let mut phase_start = vec![false; k];
        phase_start[0] = true;
        let Some(switch) = plan.switch else {
            return Schedule {
                exchanged,
                phase_start,
            };
        };
        let mut rng = switch_rng(plan, origin);
        let mut now = switch.start == SwitchStart::Random && below(&mut rng, 2) == 1;
        let mut at = Vec::with_capacity(switch.at.len());
        for &[lo, hi] in &switch.at {
            // Episode numbers in the file count from 1.
            at.push((lo + below(&mut rng, hi - lo + 1) - 1) as usize);
        }
        for (e, x) in exchanged.iter_mut().enumerate() {
            if at.contains(&e) {
                now = !now;
                phase_start[e] = true;
            }
            *x = now;
        }
        Schedule {
            exchanged,
            phase_start,
        }
    }

    /// The episodes (1-based) before which a switch comes.
    pub fn switches(&self) -> Vec<u64> {
        (1..self.phase_start.len())
            .filter(|&e| self.phase_start[e])
            .map(|e| e as u64 + 1)
            .collect()
    }
}

fn switch_rng(plan: &TrialPlan, origin: LifeOrigin) -> Rng {
    origin.switch_stream(plan)
}

/// `world` with the payoffs (substance, capacity, bite, regen, depletes) of food kinds `a`
/// and `b` exchanged; their look (radius, odour, intensity, range, colour, height, smell
/// that follows the amount) stays. Unchanged when either is not a food kind.
pub fn exchange_payoffs(world: &WorldSpec, a: &str, b: &str) -> WorldSpec {
    let mut out = world.clone();
    let (Some(KindSpec::Food(fa)), Some(KindSpec::Food(fb))) =
        (world.kinds.get(a), world.kinds.get(b))
    else {
        return out;
    };
    for (name, from) in [(a, fb), (b, fa)] {
        if let Some(KindSpec::Food(f)) = out.kinds.get_mut(name) {
            f.substance = from.substance;
            f.capacity = from.capacity;
            f.bite = from.bite;
            f.regen = from.regen;
            f.depletes = from.depletes;
        }
    }
    out
}

/// One life's worlds: its origin, its switch schedule and the world specification with the
/// payoffs exchanged (when there is a switch).
#[derive(Debug, Clone)]
pub struct Life<'a> {
    plan: TrialPlan<'a>,
    origin: LifeOrigin,
    schedule: Schedule,
    exchanged: Option<WorldSpec>,
}

impl<'a> Life<'a> {
    /// The life at `origin`.
    pub fn new(plan: &TrialPlan<'a>, origin: LifeOrigin) -> Life<'a> {
        let exchanged = plan
            .switch
            .map(|s| exchange_payoffs(plan.world, &s.kinds[0], &s.kinds[1]));
        Life {
            plan: *plan,
            origin,
            schedule: Schedule::draw(plan, origin),
            exchanged,
        }
    }

    /// Its switch schedule.
    pub fn schedule(&self) -> &Schedule {
        &self.schedule
    }

    /// Episodes in the life.
    pub fn episodes(&self) -> u64 {
        self.schedule.exchanged.len() as u64
    }

    /// Are the payoffs exchanged in episode `episode` (0-based)?
    pub fn exchanged(&self, episode: u64) -> bool {
        self.schedule.exchanged[episode as usize]
    }

    /// Episode `episode`'s world (0-based) for `creatures` creatures.
    pub fn world(&self, creatures: usize, episode: u64) -> Result<World, EvaluationError> {
        let spec: Cow<'_, WorldSpec> = match &self.exchanged {
            Some(spec) if self.exchanged(episode) => Cow::Borrowed(spec),
            _ => Cow::Borrowed(self.plan.world),
        };
        let trial = self.origin.trial;
        let generation = self.origin.generation;
        let specs = ValidSpecs::new(&spec, self.plan.creature)
            .map_err(|error| world_error(generation, trial, error))?;
        World::build(
            specs,
            creatures,
            self.origin.episode_stream(&self.plan, episode),
        )
        .map_err(|error| world_error(generation, trial, error))
    }

    /// Episode `episode`'s world, taking `first` (the life's first world, built beforehand
    /// from the same stream) for episode 0 when its payoffs are as written.
    pub fn world_or(
        &self,
        first: &mut Option<World>,
        creatures: usize,
        episode: u64,
    ) -> Result<World, EvaluationError> {
        match first.take() {
            Some(world) if episode == 0 && !self.exchanged(0) => Ok(world),
            _ => self.world(creatures, episode),
        }
    }

    /// One creature's life outcome from its episodes' (in order; fewer than K when a
    /// non-finite output ended the life): the score is the sum of the episode scores, the
    /// metabolism the last episode's, shocked ticks summed, `non_finite` when any episode's
    /// was; each measure the mean over the episodes lived, but `adapted_choice` and
    /// `good_bite_share`, which are taken over the life's phases; the ticks in each described
    /// area the mean over the episodes lived too.
    pub fn outcome(
        &self,
        measures: &[Measure],
        episodes: &[(TrialOutcome, Option<EpisodeChoices>)],
    ) -> TrialOutcome {
        let mut life = episodes[0].0;
        for (o, _) in &episodes[1..] {
            life.score += o.score;
            life.metabolism = o.metabolism;
            life.shocked_ticks += o.shocked_ticks;
            life.non_finite |= o.non_finite;
        }
        let n = episodes.len() as f64;
        let mut values = [0.0; MEASURE_COUNT];
        for &m in measures {
            let i = m.index();
            values[i] = match m {
                Measure::AdaptedChoice => self.adapted_choice(episodes),
                Measure::GoodBiteShare => self.good_bite_share(episodes),
                _ => episodes.iter().map(|(o, _)| o.measures[i]).sum::<f64>() / n,
            };
        }
        life.measures = values;
        for (k, t) in life.area_ticks.iter_mut().enumerate() {
            *t = episodes.iter().map(|(o, _)| o.area_ticks[k]).sum::<f64>() / n;
        }
        life
    }

    /// Per episode (0-based, all K): its first choice was correct (false when not lived).
    pub fn correct_choices(
        &self,
        episodes: &[(TrialOutcome, Option<EpisodeChoices>)],
    ) -> Vec<bool> {
        (0..self.schedule.exchanged.len())
            .map(|e| {
                episodes
                    .get(e)
                    .and_then(|(_, c)| c.as_ref())
                    .is_some_and(|c| c.first == Some(true))
            })
            .collect()
    }

    fn adapted_choice(&self, episodes: &[(TrialOutcome, Option<EpisodeChoices>)]) -> f64 {
        let correct = self.correct_choices(episodes);
        let counted: Vec<bool> = correct
            .iter()
            .zip(&self.schedule.phase_start)
            .filter(|(_, &start)| !start)
            .map(|(&c, _)| c)
            .collect();
        if counted.is_empty() {
            // Every episode starts a phase (one episode per life): the first choice itself.
            return f64::from(u8::from(correct[0]));
        }
        counted.iter().filter(|&&c| c).count() as f64 / counted.len() as f64
    }

    fn good_bite_share(&self, episodes: &[(TrialOutcome, Option<EpisodeChoices>)]) -> f64 {
        let (mut bites, mut good) = (0u64, 0u64);
        let mut phase_bitten = false;
        for (e, (_, choices)) in episodes.iter().enumerate() {
            if self.schedule.phase_start[e] {
                phase_bitten = false;
            }
            let Some(c) = choices else { continue };
            let Some(first) = c.first else { continue };
            bites += c.bites;
            good += c.good;
            if !phase_bitten {
                // The phase's first bite is not counted.
                bites -= 1;
                good -= u64::from(first);
                phase_bitten = true;
            }
        }
        if bites == 0 {
            0.0
        } else {
            good as f64 / bites as f64
        }
    }
}
