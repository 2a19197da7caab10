//! The one trial path: build a trial's world, live it tick by tick, score every life. Scoring
//! (the evaluation jobs of [`crate::evo::evaluate`] and [`crate::evo::door`], one trial at a
//! time or in worlds built beforehand), replay (`berry-evolve replay`) and traces
//! (`evo::trace`'s recorder is a [`TickObserver`]) all live a trial through this file, so a
//! traced life is the scored life by construction. Only the lockstep path
//! ([`crate::evo::lockstep`], tested bit-identical to this one) steps its worlds itself, built
//! from the same parts ([`crate::evo::life`]: the world, the checked controllers, the score
//! bookkeeping).
//!
//! A trial reads the experiment only through its [`TrialPlan`] (the world, the creature, the
//! ticks, the streams, the scoring), resolved once by whoever starts the trials, so nothing on
//! this path can depend on the search's, the validation's or the output's settings.
//!
//! A caller watches the trial through a [`TickObserver`]: [`TickObserver::start`] sees the
//! world as built (tick 0), [`TickObserver::tick`] the world after every tick (the last one
//! included: the tick in which the trial ended), [`TickObserver::finish`] the outcomes.
//! Observers only read the world, so they cannot change a result. [`NoObserver`]'s hooks are
//! empty and inlined: the loop evaluation runs is the same machine code as before observers
//! existed (the benchmark figures do not move; see `docs/performance.md`).

use crate::brain::genome::Genome;
use crate::brain::spec::Topology;
use crate::brain::{Brain, BrainController};
use crate::evo::episodes::{EpisodeChoices, Life, LifeOrigin};
use crate::evo::life::{
    checked_controllers, outcomes, record_tick, start_scores, trial_world, CheckedController,
    EvaluationError, TrialOutcome,
};
use crate::evo::trial_plan::TrialPlan;
use crate::seed::{Generation, TrialIndex};
use crate::sim::controller::Controller;
use crate::sim::world::World;

/// Which trial a life is: the generation and group its world's stream comes from, and the
/// trial index.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TrialId {
    /// Whose trial worlds (the generation).
    pub generation: Generation,
    /// The group of genomes sharing the world (0 with common random numbers unless the
    /// caller says otherwise; it also numbers the individuals in errors).
    pub group: u64,
    /// The trial index.
    pub trial: TrialIndex,
}

/// Sees a trial tick by tick; every hook only reads the world.
pub trait TickObserver {
    /// Does it read the world's events ([`World::events`])? The trial then switches the
    /// world's event log on before the first tick; off (the default), the world makes none.
    #[inline(always)]
    fn listens(&self) -> bool {
        false
    }

    /// The world as built, before its first tick.
    #[inline(always)]
    fn start(&mut self, _trial: TrialId, _world: &World) {}

    /// The world after tick `tick` (ticks done: 1 after the first), every tick of the trial,
    /// the one in which it ended included.
    fn tick(&mut self, world: &World, tick: u64);

    /// The trial is over: `outcomes` holds one outcome per creature, in index order.
    #[inline(always)]
    fn finish(&mut self, _world: &World, _outcomes: &[TrialOutcome]) {}

    /// In a life of several episodes, which episode the next [`TickObserver::start`] begins
    /// (not called for a life of one).
    #[inline(always)]
    fn episode(&mut self, _mark: EpisodeMark) {}

    /// Does it read the creatures' brains ([`TickObserver::brain`])? Off (the default), the
    /// trial never calls that hook.
    #[inline(always)]
    fn watches_brains(&self) -> bool {
        false
    }

    /// Creature `creature`'s brain after tick `tick` (0: at the start of the episode, after
    /// [`TickObserver::start`]), when [`TickObserver::watches_brains`]; only reads it.
    #[inline(always)]
    fn brain(&mut self, _tick: u64, _creature: usize, _brain: &Brain) {}
}

/// Which episode of a life a trial is (see [`crate::evo::episodes`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct EpisodeMark {
    /// The episode, 0-based.
    pub index: u64,
    /// Episodes in the life.
    pub episodes: u64,
    /// The switch kinds' payoffs are exchanged in this episode.
    pub exchanged: bool,
    /// A switch comes before this episode (never before the first).
    pub switched: bool,
}

/// A controller whose brain an observer may read ([`TickObserver::brain`]): a
/// [`BrainController`]'s; none for the scripted controllers of tests.
pub trait BrainOf {
    /// The brain behind the controller, if it has one.
    fn brain_of(&self) -> Option<&Brain> {
        None
    }
}

impl BrainOf for BrainController {
    fn brain_of(&self) -> Option<&Brain> {
        Some(self.brain())
    }
}

/// Shows each creature's brain after tick `tick` to `observer` (only called when it
/// watches brains).
fn show_brains<C: BrainOf, O: TickObserver>(
    observer: &mut O,
    controllers: &[CheckedController<C>],
    tick: u64,
) {
    for (i, c) in controllers.iter().enumerate() {
        if let Some(brain) = c.inner.brain_of() {
            observer.brain(tick, i, brain);
        }
    }
}

/// The observer that watches nothing (evaluation's): every hook is empty and inlined away.
#[derive(Debug, Clone, Copy, Default)]
pub struct NoObserver;

impl TickObserver for NoObserver {
    #[inline(always)]
    fn tick(&mut self, _world: &World, _tick: u64) {}
}

impl<O: TickObserver + ?Sized> TickObserver for &mut O {
    #[inline(always)]
    fn listens(&self) -> bool {
        (**self).listens()
    }

    #[inline(always)]
    fn start(&mut self, trial: TrialId, world: &World) {
        (**self).start(trial, world);
    }

    #[inline(always)]
    fn tick(&mut self, world: &World, tick: u64) {
        (**self).tick(world, tick);
    }

    #[inline(always)]
    fn finish(&mut self, world: &World, outcomes: &[TrialOutcome]) {
        (**self).finish(world, outcomes);
    }

    #[inline(always)]
    fn episode(&mut self, mark: EpisodeMark) {
        (**self).episode(mark);
    }

    #[inline(always)]
    fn watches_brains(&self) -> bool {
        (**self).watches_brains()
    }

    #[inline(always)]
    fn brain(&mut self, tick: u64, creature: usize, brain: &Brain) {
        (**self).brain(tick, creature, brain);
    }
}

/// Lives trial `trial` of generation `generation` for group `group` (`genomes`, one creature
/// each, sharing one world) and returns one outcome per genome, showing every tick to
/// `observer`. A pure function of its arguments: the world comes from the trial's own seed
/// stream ([`crate::evo::life::trial_stream`]), brains are built anew for this trial.
pub fn run_trial<O: TickObserver>(
    plan: &TrialPlan,
    topology: &Topology,
    genomes: &[Genome],
    generation: Generation,
    group: u64,
    trial: TrialIndex,
    mut observer: O,
) -> Result<Vec<TrialOutcome>, EvaluationError> {
    // The brains first, then the world, so that a bad genome is reported before a world
    // that cannot be built, as everywhere.
    let mut controllers = checked_controllers(plan, topology, genomes, group, (generation, trial))?;
    let id = TrialId {
        generation,
        group,
        trial,
    };
    if plan.episodes_per_life > 1 {
        let origin = LifeOrigin::trial(plan, generation, group, trial);
        return Ok(live_life(plan, None, origin, id, &mut controllers, observer)?.0);
    }
    let mut world = trial_world(plan, genomes.len(), generation, group, trial)?;
    // Before `start_scores`, which also switches the log on for a plan that reads events.
    world.set_event_log(observer.listens());
    observer.start(id, &world);
    Ok(live(plan, world, &mut controllers, observer))
}

/// Lives one trial in a `world` built beforehand for `genomes.len()` creatures (e.g. a
/// validation world of [`crate::evo::worlds::validation_worlds`], which no generation's
/// stream builds), showing every tick to `observer`: the life evaluation in those worlds
/// scores. `id` only names the trial to the observer (and numbers individuals in errors);
/// `origin` is where `world` came from, whence the later episodes of a life of several.
pub fn run_trial_in_world<O: TickObserver>(
    plan: &TrialPlan,
    topology: &Topology,
    genomes: &[Genome],
    id: TrialId,
    origin: LifeOrigin,
    world: World,
    observer: O,
) -> Result<Vec<TrialOutcome>, EvaluationError> {
    let mut controllers = checked_controllers(
        plan,
        topology,
        genomes,
        id.group,
        (origin.generation, origin.trial),
    )?;
    Ok(live_life(plan, Some(world), origin, id, &mut controllers, observer)?.0)
}

/// Lives the life at `origin` for `genomes` (one creature each), `first` its first world when
/// built beforehand, showing each episode to `observer`: each creature's life outcome and
/// its episodes (what `compare --json` reports per episode).
pub fn run_life<O: TickObserver>(
    plan: &TrialPlan,
    topology: &Topology,
    genomes: &[Genome],
    id: TrialId,
    origin: LifeOrigin,
    first: Option<World>,
    observer: O,
) -> Result<(Vec<TrialOutcome>, LifeEpisodes), EvaluationError> {
    let mut controllers = checked_controllers(
        plan,
        topology,
        genomes,
        id.group,
        (origin.generation, origin.trial),
    )?;
    live_life(plan, first, origin, id, &mut controllers, observer)
}

/// Every creature's episodes of one life, in order: each episode's outcome and its bites of
/// the switch kinds.
pub type LifeEpisodes = Vec<Vec<(TrialOutcome, Option<EpisodeChoices>)>>;

/// Lives the life at `origin` (`[evaluation] episodes_per_life` episodes; `first`, when
/// given, is its first world built beforehand) with `controllers`, built once for the whole
/// life: their state carries over from one episode to the next. Each episode is shown to
/// `observer` as a trial of its own (`start`, every tick, `finish` with the episode's
/// outcomes). Returns each creature's life outcome and its episodes. A life of one episode is
/// the trial [`live`] lives, bit for bit.
pub(crate) fn live_life<C: Controller + BrainOf, O: TickObserver>(
    plan: &TrialPlan,
    first: Option<World>,
    origin: LifeOrigin,
    id: TrialId,
    controllers: &mut [CheckedController<C>],
    mut observer: O,
) -> Result<(Vec<TrialOutcome>, LifeEpisodes), EvaluationError> {
    let life = Life::new(plan, origin);
    let n = controllers.len();
    if life.episodes() <= 1 {
        let mut world = match first {
            Some(world) => world,
            None => life.world(n, 0)?,
        };
        world.set_event_log(observer.listens());
        observer.start(id, &world);
        let (outcomes, choices) = live_episode(plan, world, controllers, observer);
        let episodes = outcomes
            .iter()
            .copied()
            .zip(choices)
            .map(|e| vec![e])
            .collect();
        return Ok((outcomes, episodes));
    }
    let mut episodes: LifeEpisodes = vec![Vec::new(); n];
    let mut first = first;
    for e in 0..life.episodes() {
        let mut world = life.world_or(&mut first, n, e)?;
        world.set_event_log(observer.listens());
        let schedule = life.schedule();
        observer.episode(EpisodeMark {
            index: e,
            episodes: life.episodes(),
            exchanged: life.exchanged(e),
            switched: e > 0 && schedule.phase_start[e as usize],
        });
        observer.start(id, &world);
        let (outcomes, choices) = live_episode(plan, world, controllers, &mut observer);
        // A non-finite output ends the life (its creature stood still since).
        let over = outcomes.iter().all(|o| o.non_finite);
        for ((lived, o), c) in episodes.iter_mut().zip(outcomes).zip(choices) {
            lived.push((o, c));
        }
        if over {
            break;
        }
    }
    let measures = &plan.behaviour.measures;
    let outcomes = episodes.iter().map(|e| life.outcome(measures, e)).collect();
    Ok((outcomes, episodes))
}

/// Steps `world` for at most `ticks` ticks with `controllers` (one per creature), showing
/// each tick to `observer`, and stops after the first tick in which no creature recorded a
/// score (nothing it could still record).
pub(crate) fn live<C: Controller + BrainOf, O: TickObserver>(
    plan: &TrialPlan,
    world: World,
    controllers: &mut [CheckedController<C>],
    observer: O,
) -> Vec<TrialOutcome> {
    live_episode(plan, world, controllers, observer).0
}

/// [`live`], also returning each creature's bites of the switch kinds.
fn live_episode<C: Controller + BrainOf, O: TickObserver>(
    plan: &TrialPlan,
    mut world: World,
    controllers: &mut [CheckedController<C>],
    mut observer: O,
) -> (Vec<TrialOutcome>, Vec<Option<EpisodeChoices>>) {
    let (life_plan, mut scores) = start_scores(plan, &mut world);
    let mut invalid = vec![false; controllers.len()];
    let brains = observer.watches_brains();
    if brains {
        show_brains(&mut observer, controllers, 0);
    }
    for _ in 0..plan.ticks {
        world.step(controllers);
        for (flag, controller) in invalid.iter_mut().zip(controllers.iter()) {
            *flag = controller.non_finite;
        }
        observer.tick(&world, world.tick());
        if brains {
            show_brains(&mut observer, controllers, world.tick());
        }
        if !record_tick(&world, &invalid, &mut scores, &life_plan) {
            break;
        }
    }
    let outcomes = outcomes(&world, &scores, &invalid, &life_plan);
    observer.finish(&world, &outcomes);
    (outcomes, scores.iter().map(|s| s.choices()).collect())
}
