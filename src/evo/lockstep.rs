//! Lockstep evaluation: one brain per genome drives its creature in several trial
//! worlds at once, tick by tick, so that the brain computes a batch of observations per call
//! ([`BrainController::act_batch`]) and is built once per job instead of once per trial.
//!
//! Creature i of world w depends only on world w: each world goes through the phases of
//! [`World::step`] in their only valid order ([`World::begin_tick`], then per creature
//! [`World::observe`] and [`World::apply`], then [`World::end_tick`]); the lockstep only
//! interleaves worlds between those phases. Each world senses with [`World::observe_into`],
//! which writes the observation straight into its place in the batch (the same bits as
//! `observe`, without a copy). A stateless brain's batch gives every observation
//! the bits it gives alone, so each world's trial is the same bits as
//! [`crate::evo::trial::run_trial`]'s, whatever the chunk size or the other worlds.
//!
//! A plastic brain's weights change within a life, so one brain cannot serve several worlds:
//! it runs in lockstep with one copy per world ([`WorldBrains`], [`Lanes::PerWorld`]), each
//! started for its own life as the single-trial path starts it, and gets the same bits too.

use crate::brain::genome::Genome;
use crate::brain::plasticity::LifeKey;
use crate::brain::spec::Topology;
use crate::brain::{Brain, BrainController};
use crate::evo::episodes::{EpisodeChoices, Life, LifeOrigin};
use crate::evo::fitness::{LifePlan, LifeScore};
use crate::evo::life::{
    build_trial_world, controllers, finite_command, outcomes, record_tick, start_scores,
    valid_specs, EvaluationError, TrialOutcome,
};
use crate::evo::trial::LifeEpisodes;
use crate::evo::trial_plan::TrialPlan;
use crate::seed::{Generation, IndividualId, TrialIndex};
use crate::sim::controller::{Controller, MotorCommand};
use crate::sim::world::World;
use std::ops::Range;

/// Most trials (worlds) one lockstep job runs: enough for a batched brain kernel to pay off
/// (n ≥ 8), few enough that a generation still splits into many jobs. A constant, so that
/// the jobs never depend on the number of threads (the results depend on neither).
pub const CHUNK_TRIALS: u64 = 16;

/// Most trials one lockstep job of plastic brains runs ([`Lanes::PerWorld`]): each world has
/// its own brain, whose weights and rule coefficients the tick rewrites, so more worlds only
/// crowd the cache (bench, experiments/bench/foraging-plastic.toml: 16 worlds a job ran about
/// 25% slower than one world at a time, 4 as fast).
pub const CHUNK_TRIALS_PER_WORLD: u64 = 4;

/// The trial ranges of one group's jobs: `0..trials` cut into chunks of [`CHUNK_TRIALS`],
/// in order.
pub fn chunks(trials: u64) -> Vec<Range<u64>> {
    chunks_of(CHUNK_TRIALS, trials)
}

/// The trial ranges of one group's jobs for brains that run in lockstep as `lanes` says:
/// [`chunks`], in chunks of [`CHUNK_TRIALS_PER_WORLD`] for plastic brains.
pub fn chunks_for(lanes: Lanes, trials: u64) -> Vec<Range<u64>> {
    match lanes {
        Lanes::Shared => chunks(trials),
        Lanes::PerWorld => chunks_of(CHUNK_TRIALS_PER_WORLD, trials),
    }
}

fn chunks_of(size: u64, trials: u64) -> Vec<Range<u64>> {
    (0..trials.div_ceil(size))
        .map(|c| c * size..((c + 1) * size).min(trials))
        .collect()
}

/// Do brains of `topology` keep no state from tick to tick, so that one serves every world
/// of a lockstep job ([`Lanes::Shared`])?
pub fn stateless(topology: &Topology) -> bool {
    lanes(topology) == Some(Lanes::Shared)
}

/// How brains of a topology drive the worlds of a lockstep job.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Lanes {
    /// One brain for every world, fed a batch of observations per tick (a stateless MLP).
    Shared,
    /// One copy of the brain per world (a plastic MLP: its weights are its life's).
    PerWorld,
}

/// How brains of `topology` run in lockstep (None: a recurrent brain, Elman or CTRNN, which
/// evolution runs one trial at a time). Asks an all-zero brain, so that which kinds qualify
/// is decided in one place ([`Brain::is_stateless`], [`Brain::plastic_weights`]).
pub fn lanes(topology: &Topology) -> Option<Lanes> {
    let brain = Brain::new(topology, &vec![0.0; topology.parameter_count()]).ok()?;
    if brain.is_stateless() {
        Some(Lanes::Shared)
    } else if brain.plastic_weights().is_some() {
        Some(Lanes::PerWorld)
    } else {
        None
    }
}

/// What lockstep needs of a controller: the commands of several observations at once, each
/// the one it would give that observation alone (no state from call to call).
pub trait BatchController {
    /// Fills `commands[k]` with the command for observation k of `observations`
    /// (`commands.len()` observations back to back).
    fn act_batch(&mut self, observations: &[f64], commands: &mut [MotorCommand]);

    /// [`BatchController::act_batch`] where observation k comes from world `worlds[k]` of
    /// the tick's worlds: a controller with one brain per world picks it by that index.
    #[inline]
    fn act_in(&mut self, worlds: &[usize], observations: &[f64], commands: &mut [MotorCommand]) {
        let _ = worlds;
        self.act_batch(observations, commands);
    }

    /// The next ticks' worlds are the lives `lives` (world w is life `lives[w]`): a
    /// controller with one brain per life follows its lives when some of them have ended.
    fn worlds_are(&mut self, lives: &[usize]) {
        let _ = lives;
    }

    /// True when every command is finite whatever the observations, so that the lockstep
    /// need not check each one (per creature and tick) for a non-finite value. False
    /// unless the controller knows.
    fn commands_always_finite(&self) -> bool {
        false
    }
}

impl BatchController for BrainController {
    #[inline]
    fn act_batch(&mut self, observations: &[f64], commands: &mut [MotorCommand]) {
        BrainController::act_batch(self, observations, commands);
    }

    #[inline]
    fn commands_always_finite(&self) -> bool {
        BrainController::commands_always_finite(self)
    }
}

/// One creature's brains in a lockstep job of plastic brains: one per life (world), each
/// started for that life as [`crate::evo::trial::run_trial`] starts it.
#[derive(Debug, Clone)]
pub struct WorldBrains {
    brains: Vec<BrainController>,
    /// World w of the current batch is life `lives[w]` (empty: world w is life w).
    lives: Vec<usize>,
}

impl WorldBrains {
    /// The brains of lives 0, 1, ... in order.
    pub fn new(brains: Vec<BrainController>) -> WorldBrains {
        WorldBrains {
            brains,
            lives: Vec::new(),
        }
    }
}

impl BatchController for WorldBrains {
    fn act_batch(&mut self, observations: &[f64], commands: &mut [MotorCommand]) {
        let width = observations.len() / commands.len().max(1);
        for (w, (observation, command)) in observations
            .chunks_exact(width)
            .zip(commands.iter_mut())
            .enumerate()
        {
            let life = self.lives.get(w).copied().unwrap_or(w);
            *command = self.brains[life].act(observation);
        }
    }

    #[inline]
    fn act_in(&mut self, worlds: &[usize], observations: &[f64], commands: &mut [MotorCommand]) {
        let width = observations.len() / commands.len().max(1);
        for ((&w, observation), command) in worlds
            .iter()
            .zip(observations.chunks_exact(width))
            .zip(commands.iter_mut())
        {
            let life = self.lives.get(w).copied().unwrap_or(w);
            *command = self.brains[life].act(observation);
        }
    }

    fn worlds_are(&mut self, lives: &[usize]) {
        self.lives.clear();
        self.lives.extend_from_slice(lives);
    }
}

/// The buffers of one lockstep job, sized for its worlds once so that a tick allocates
/// nothing.
#[derive(Debug, Clone)]
pub struct Lockstep {
    creatures: usize,
    width: usize,
    /// Creature i's observations in every world where it is alive, back to back: room for
    /// one per world, each written there by [`World::observe_into`] (no copy).
    observations: Vec<f64>,
    /// Their commands, in the same order: the first `live.len()` of one per world, each
    /// written by the batch before it is read.
    commands: Vec<MotorCommand>,
    /// The worlds those observations came from, in the same order.
    live: Vec<usize>,
}

impl Lockstep {
    /// Buffers for up to `worlds` worlds of `creatures` creatures whose observations have
    /// `width` values.
    pub fn new(worlds: usize, creatures: usize, width: usize) -> Lockstep {
        Lockstep {
            creatures,
            width,
            observations: vec![0.0; worlds * width],
            commands: vec![MotorCommand::default(); worlds],
            live: Vec::with_capacity(worlds),
        }
    }

    /// One tick of every world `w` with `running[w]`: creature i of each is driven by
    /// `controllers[i]`, one batch per creature index. A non-finite command sets
    /// `invalid[w * creatures + i]` and the creature gets [`MotorCommand::default`] for that
    /// tick, as [`crate::evo::trial::run_trial`] does.
    ///
    /// # Panics
    /// When the slices do not match the sizes given to [`Lockstep::new`] (a programming
    /// error).
    // Never inlined: called once per tick, it costs nothing to keep as its own frame, which
    // profiles of the tick (callgrind's `--toggle-collect`) find by name.
    #[inline(never)]
    pub fn tick<B: BatchController>(
        &mut self,
        worlds: &mut [World],
        running: &[bool],
        controllers: &mut [B],
        invalid: &mut [bool],
    ) {
        let k = self.creatures;
        assert_eq!(controllers.len(), k, "one controller per creature");
        assert_eq!(running.len(), worlds.len(), "one running flag per world");
        assert_eq!(invalid.len(), worlds.len() * k, "one flag per creature");
        let width = self.width;
        assert!(
            self.live.capacity() >= worlds.len()
                && self.commands.len() >= worlds.len()
                && self.observations.len() >= worlds.len() * width,
            "lockstep buffers too small"
        );
        for (world, _) in worlds.iter_mut().zip(running).filter(|(_, &r)| r) {
            world.begin_tick();
        }
        for (i, controller) in controllers.iter_mut().enumerate() {
            self.live.clear();
            for (w, world) in worlds.iter_mut().enumerate() {
                if !running[w] {
                    continue;
                }
                let at = self.live.len() * width;
                if world.observe_into(i, &mut self.observations[at..at + width]) {
                    self.live.push(w);
                }
            }
            let n = self.live.len();
            if n == 0 {
                continue;
            }
            let commands = &mut self.commands[..n];
            controller.act_in(&self.live, &self.observations[..n * width], commands);
            if controller.commands_always_finite() {
                // Known finite (a brain's commands): nothing to check per world.
                for (&w, &command) in self.live.iter().zip(commands.iter()) {
                    debug_assert!(finite_command(command).is_some(), "{command:?}");
                    worlds[w].apply(i, command);
                }
                continue;
            }
            for (&w, &command) in self.live.iter().zip(commands.iter()) {
                let command = finite_command(command).unwrap_or_else(|| {
                    invalid[w * k + i] = true;
                    MotorCommand::default()
                });
                worlds[w].apply(i, command);
            }
        }
        for (world, _) in worlds.iter_mut().zip(running).filter(|(_, &r)| r) {
            world.end_tick();
        }
    }
}

/// Lives trials `trials` (a chunk, see [`chunks`]) of group `group` in lockstep; returns,
/// per trial in order, one outcome per genome: the same bits as
/// [`crate::evo::trial::run_trial`] for each trial.
///
/// # Panics
/// When the brains cannot run in lockstep ([`lanes`] is None: a recurrent brain) (a
/// programming error: check first).
pub fn run_trials(
    plan: &TrialPlan,
    topology: &Topology,
    genomes: &[Genome],
    generation: Generation,
    group: u64,
    trials: Range<u64>,
) -> Result<Vec<Vec<TrialOutcome>>, EvaluationError> {
    let origin = LifeOrigin::trial(plan, generation, group, TrialIndex(0));
    run_trials_in(
        plan, topology, genomes, generation, group, trials, None, origin,
    )
}

/// [`run_trials`], cloning the trials' worlds from `shared` (evaluation's shared worlds: the
/// same worlds, built once for every group) when given, else building them. Trial t's life
/// is at `origin.with_trial(t)` (its later episodes' worlds come from there).
#[allow(clippy::too_many_arguments)] // the trial coordinates, each needed
pub(crate) fn run_trials_in(
    plan: &TrialPlan,
    topology: &Topology,
    genomes: &[Genome],
    generation: Generation,
    group: u64,
    trials: Range<u64>,
    shared: Option<&[World]>,
    origin: LifeOrigin,
) -> Result<Vec<Vec<TrialOutcome>>, EvaluationError> {
    let mut controllers = controllers(plan, topology, genomes, group)?;
    let job = Chunk {
        plan,
        creatures: genomes.len(),
        generation,
        group,
        trials,
        shared,
        origin,
    };
    if lanes(topology) == Some(Lanes::PerWorld) {
        let mut brains = job.world_brains(controllers);
        return job.live(&mut brains);
    }
    job.live(&mut controllers)
}

/// One lockstep job's trials: what [`run_trials_in`] lives once its controllers are built.
struct Chunk<'a> {
    plan: &'a TrialPlan<'a>,
    creatures: usize,
    generation: Generation,
    group: u64,
    trials: Range<u64>,
    shared: Option<&'a [World]>,
    origin: LifeOrigin,
}

impl Chunk<'_> {
    /// Each creature's controller copied once per trial of the chunk, each copy started for
    /// the life of its trial as [`crate::evo::trial::run_trial`] starts its brains (the same
    /// [`LifeKey`], so a plastic brain's random initial weights are the same draws).
    fn world_brains(&self, controllers: Vec<BrainController>) -> Vec<WorldBrains> {
        let first = self.group * self.creatures as u64;
        controllers
            .into_iter()
            .enumerate()
            .map(|(k, controller)| {
                let brains = self
                    .trials
                    .clone()
                    .map(|t| {
                        let mut brain = controller.clone();
                        brain.brain_mut().start_life(LifeKey {
                            seed: self.plan.seed,
                            generation: self.origin.generation,
                            individual: IndividualId(first + k as u64),
                            trial: TrialIndex(t),
                        });
                        brain
                    })
                    .collect();
                WorldBrains::new(brains)
            })
            .collect()
    }

    /// Lives the chunk's trials with `controllers` (one per creature).
    fn live<B: BatchController>(
        &self,
        controllers: &mut [B],
    ) -> Result<Vec<Vec<TrialOutcome>>, EvaluationError> {
        let (plan, trials) = (self.plan, self.trials.clone());
        if plan.episodes_per_life > 1 {
            let lives: Vec<Life<'_>> = trials
                .clone()
                .map(|t| Life::new(plan, self.origin.with_trial(TrialIndex(t))))
                .collect();
            let firsts: Vec<Option<World>> = match self.shared {
                Some(worlds) => worlds[trials.start as usize..trials.end as usize]
                    .iter()
                    .map(|w| Some(w.clone()))
                    .collect(),
                None => vec![None; lives.len()],
            };
            return live_lives(plan, &lives, firsts, controllers);
        }
        let worlds = match self.shared {
            Some(worlds) => worlds[trials.start as usize..trials.end as usize].to_vec(),
            None => {
                let specs = valid_specs(plan, self.generation, TrialIndex(trials.start))?;
                trials
                    .map(|t| {
                        let trial = TrialIndex(t);
                        let (generation, group) = (self.generation, self.group);
                        build_trial_world(specs, plan, self.creatures, generation, group, trial)
                    })
                    .collect::<Result<Vec<_>, _>>()?
            }
        };
        Ok(live_trials(plan, worlds, controllers))
    }
}

/// Lives `lives` (of several episodes each) in lockstep, episode by episode: episode e of
/// every life still going (a non-finite output ends a life) in one [`live_trials`], `firsts`
/// the lives' first worlds when built beforehand. The brains are stateless or one per life
/// ([`WorldBrains`]), so living the episodes of other lives in between changes nothing: each
/// life gets the bits of [`crate::evo::trial::run_trial`]'s.
pub(crate) fn live_lives<B: BatchController>(
    plan: &TrialPlan,
    lives: &[Life<'_>],
    mut firsts: Vec<Option<World>>,
    controllers: &mut [B],
) -> Result<Vec<Vec<TrialOutcome>>, EvaluationError> {
    let k = controllers.len();
    let mut episodes: Vec<LifeEpisodes> = vec![vec![Vec::new(); k]; lives.len()];
    let mut going = vec![true; lives.len()];
    let count = lives.iter().map(Life::episodes).max().unwrap_or(0);
    for e in 0..count {
        let now: Vec<usize> = (0..lives.len())
            .filter(|&w| going[w] && e < lives[w].episodes())
            .collect();
        let worlds = now
            .iter()
            .map(|&w| lives[w].world_or(&mut firsts[w], k, e))
            .collect::<Result<Vec<_>, _>>()?;
        for controller in controllers.iter_mut() {
            controller.worlds_are(&now);
        }
        let (outcomes, choices) = live_trials_scored(plan, worlds, controllers);
        for ((&w, outcomes), choices) in now.iter().zip(outcomes).zip(choices) {
            going[w] = !outcomes.iter().all(|o| o.non_finite);
            for ((lived, o), c) in episodes[w].iter_mut().zip(outcomes).zip(choices) {
                lived.push((o, c));
            }
        }
    }
    let measures = &plan.behaviour.measures;
    Ok(lives
        .iter()
        .zip(&episodes)
        .map(|(life, creatures)| {
            creatures
                .iter()
                .map(|e| life.outcome(measures, e))
                .collect()
        })
        .collect())
}

/// Steps `worlds` in lockstep for at most `ticks` ticks with `controllers` (one per
/// creature); each world stops after the first tick in which none of its creatures recorded
/// a score, as [`crate::evo::trial::run_trial`]'s does.
pub(crate) fn live_trials<B: BatchController>(
    plan: &TrialPlan,
    worlds: Vec<World>,
    controllers: &mut [B],
) -> Vec<Vec<TrialOutcome>> {
    live_trials_scored(plan, worlds, controllers).0
}

/// Per world, each creature's bites of the switch kinds.
type WorldChoices = Vec<Vec<Option<EpisodeChoices>>>;

/// [`live_trials`], also returning each creature's bites of the switch kinds.
fn live_trials_scored<B: BatchController>(
    plan: &TrialPlan,
    mut worlds: Vec<World>,
    controllers: &mut [B],
) -> (Vec<Vec<TrialOutcome>>, WorldChoices) {
    let k = controllers.len();
    let n = worlds.len();
    let width = worlds.first().map_or(0, |w| w.layout().len());
    let mut lockstep = Lockstep::new(n, k, width);
    // One plan per world (the worlds of one experiment share their areas, but each world
    // tracks its own bites), and its creatures' scores side by side.
    let mut plans: Vec<LifePlan> = Vec::with_capacity(n);
    let mut scores: Vec<LifeScore> = Vec::with_capacity(n * k);
    for world in &mut worlds {
        let (life_plan, world_scores) = start_scores(plan, world);
        plans.push(life_plan);
        scores.extend(world_scores);
    }
    let mut invalid = vec![false; n * k];
    let mut running = vec![true; n];
    for _ in 0..plan.ticks {
        if !running.contains(&true) {
            break;
        }
        lockstep.tick(&mut worlds, &running, controllers, &mut invalid);
        for (w, world) in worlds.iter().enumerate() {
            if running[w] {
                let range = w * k..(w + 1) * k;
                running[w] = record_tick(
                    world,
                    &invalid[range.clone()],
                    &mut scores[range],
                    &plans[w],
                );
            }
        }
    }
    let lives = worlds
        .iter()
        .enumerate()
        .map(|(w, world)| {
            let range = w * k..(w + 1) * k;
            outcomes(world, &scores[range.clone()], &invalid[range], &plans[w])
        })
        .collect();
    let choices = scores
        .chunks(k.max(1))
        .map(|s| s.iter().map(LifeScore::choices).collect())
        .collect();
    (lives, choices)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::evo::life::{trial_world, CheckedController};
    use crate::evo::trial::{live, NoObserver};
    use crate::experiment::Experiment;
    use crate::sim::controller::Controller;
    use std::path::Path;

    /// A stateless controller that turns some observations into NaN commands: its command is
    /// a function of the observation's bits alone, NaN for about one observation in `every`.
    #[derive(Clone, Copy)]
    struct Flaky {
        every: u64,
    }

    impl crate::evo::trial::BrainOf for Flaky {}

    impl Controller for Flaky {
        fn act(&mut self, observation: &[f64]) -> MotorCommand {
            let sum: f64 = observation.iter().sum();
            if sum.to_bits() % self.every == 0 {
                return MotorCommand {
                    left: f64::NAN,
                    right: 0.1,
                    eat: 1.0,
                };
            }
            MotorCommand {
                left: 0.25 * libm::sin(sum),
                right: 0.25 * libm::cos(1.3 * sum),
                eat: 1.0,
            }
        }
    }

    impl BatchController for Flaky {
        fn act_batch(&mut self, observations: &[f64], commands: &mut [MotorCommand]) {
            let width = observations.len() / commands.len();
            for (command, observation) in commands.iter_mut().zip(observations.chunks(width)) {
                *command = self.act(observation);
            }
        }
    }

    fn tiny(ticks: u64) -> Experiment {
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        Experiment::load(&root.join("tests/fixtures/tiny.toml"))
            .unwrap()
            .with_overrides()
            .ticks(ticks)
            .build()
            .unwrap()
    }

    /// Non-finite commands mark exactly the lives `run_trial`'s check marks, stand the
    /// creature still the same way, and stop a world whose creatures are all invalid at the
    /// same tick.
    #[test]
    fn non_finite_commands_give_the_per_trial_outcomes() {
        let experiment = tiny(150);
        let plan = TrialPlan::new(&experiment);
        let mut some_invalid = 0;
        let mut all_invalid = 0;
        for (creatures, every) in [(1usize, 97u64), (3, 61), (4, 1009), (2, 3)] {
            let worlds: Vec<World> = (0..CHUNK_TRIALS + 3)
                .map(|t| trial_world(&plan, creatures, Generation(2), 1, TrialIndex(t)))
                .collect::<Result<_, _>>()
                .unwrap();
            let mut batch = vec![Flaky { every }; creatures];
            let lockstep = live_trials(&plan, worlds.clone(), &mut batch);
            for (world, together) in worlds.into_iter().zip(&lockstep) {
                let mut checked: Vec<CheckedController<Flaky>> = (0..creatures)
                    .map(|_| CheckedController {
                        inner: Flaky { every },
                        non_finite: false,
                    })
                    .collect();
                let alone = live(&plan, world, &mut checked, NoObserver);
                assert_eq!(alone.len(), together.len());
                for (a, b) in alone.iter().zip(together) {
                    assert_eq!(a.score.to_bits(), b.score.to_bits());
                    assert_eq!(
                        a.metabolism.map(f64::to_bits),
                        b.metabolism.map(f64::to_bits)
                    );
                    assert_eq!(a.shocked_ticks, b.shocked_ticks);
                    assert_eq!(a.non_finite, b.non_finite);
                }
                let invalid = together.iter().filter(|o| o.non_finite).count();
                some_invalid += usize::from(invalid > 0 && invalid < creatures);
                all_invalid += usize::from(invalid == creatures);
            }
        }
        // The cases above do exercise both a partly and a wholly invalid world.
        assert!(
            some_invalid > 0 && all_invalid > 0,
            "{some_invalid} {all_invalid}"
        );
    }

    /// `finite_command`'s one comparison is the three `is_finite` tests.
    #[test]
    fn finite_command_accepts_exactly_the_finite_commands() {
        let values = [
            0.0,
            -0.0,
            1.0,
            -3.5,
            f64::MAX,
            f64::MIN,
            f64::MIN_POSITIVE,
            5e-324,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
            -f64::NAN,
        ];
        for &left in &values {
            for &right in &values {
                for &eat in &values {
                    let command = MotorCommand { left, right, eat };
                    let finite = left.is_finite() && right.is_finite() && eat.is_finite();
                    let got = finite_command(command);
                    assert_eq!(got.is_some(), finite, "{command:?}");
                    if let Some(c) = got {
                        assert_eq!(
                            [c.left, c.right, c.eat].map(f64::to_bits),
                            [left, right, eat].map(f64::to_bits)
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn chunks_cover_the_trials_in_order() {
        assert!(chunks(0).is_empty());
        assert_eq!(chunks(5), vec![0..5]);
        assert_eq!(chunks(16), vec![0..16]);
        assert_eq!(chunks(33), vec![0..16, 16..32, 32..33]);
        assert_eq!(chunks_for(Lanes::Shared, 33), chunks(33));
        assert_eq!(chunks_for(Lanes::PerWorld, 9), vec![0..4, 4..8, 8..9]);
    }
}
