//! A lockstep tick allocates nothing: a counting global allocator watches
//! `Lockstep::tick` drive a chunk of foraging worlds with MLP brains (one shared brain per
//! creature, or a plastic brain per world and creature) while creatures die and worlds stop,
//! so that the batches shrink from tick to tick. The job's buffers are sized once, when it
//! starts.

use berry_evolve::brain::genome::Genome;
use berry_evolve::brain::{Brain, BrainController};
use berry_evolve::evo::lockstep::{BatchController, Lockstep, WorldBrains, CHUNK_TRIALS};
use berry_evolve::evo::search::ga::first_population;
use berry_evolve::experiment::Experiment;
use berry_evolve::seed::{stream, Generation, IndividualId, Purpose, TrialIndex};
use berry_evolve::sim::world::World;
use std::path::Path;

use crate::alloc_common::allocations;

fn load(file: &str) -> Experiment {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    Experiment::load(&root.join(file)).unwrap()
}

fn controller(experiment: &Experiment, genome: &Genome) -> BrainController {
    BrainController::new(
        Brain::new(&experiment.topology(), &genome.parameters).unwrap(),
        experiment.creature.max_rpt,
        experiment.creature.eats_by_action(),
    )
}

/// Drives `CHUNK_TRIALS` worlds of `experiment`, one creature per controller, for 600 ticks
/// (after one uncounted tick), killing creatures and stopping worlds on the way, and checks
/// that no tick allocated and that somebody moved.
fn ticks_do_not_allocate<B: BatchController>(experiment: &Experiment, controllers: &mut [B]) {
    let creatures = controllers.len();
    let n = CHUNK_TRIALS as usize;
    let mut worlds: Vec<World> = (0..n as u64)
        .map(|w| {
            let rng = stream(
                experiment.seed(),
                Purpose::Baseline,
                Generation(0),
                IndividualId(w),
                TrialIndex(0),
            );
            World::new(&experiment.world, &experiment.creature, creatures, rng).unwrap()
        })
        .collect();
    let width = worlds[0].layout().len();
    let mut lockstep = Lockstep::new(n, creatures, width);
    let mut running = vec![true; n];
    let mut invalid = vec![false; n * creatures];
    // One tick outside the count: the brains' batch buffers grow to the largest batch then.
    lockstep.tick(&mut worlds, &running, controllers, &mut invalid);
    let before = allocations();
    for tick in 0..600 {
        lockstep.tick(&mut worlds, &running, controllers, &mut invalid);
        // Deaths and stopped worlds shrink the batches.
        if tick % 50 == 0 {
            let k = tick / 50;
            worlds[k % n].kill(k % creatures);
            running[(3 * k + 1) % n] = false;
        }
    }
    let allocated = allocations() - before;
    assert_eq!(allocated, 0, "{allocated} heap allocations in 600 ticks");
    assert!(
        worlds
            .iter()
            .flat_map(World::creatures)
            .any(|c| c.travelled > 10.0),
        "nobody moved"
    );
}

#[test]
fn lockstep_tick_does_not_allocate() {
    let experiment = load("experiments/foraging.toml");
    let genomes = first_population(&experiment, &experiment.topology());
    let mut controllers: Vec<BrainController> = genomes[..3]
        .iter()
        .map(|g| controller(&experiment, g))
        .collect();
    ticks_do_not_allocate(&experiment, &mut controllers);
}

/// The same with plastic brains, one per world (`WorldBrains`): their weight updates and the
/// per-world dispatch allocate nothing either.
#[test]
fn plastic_lockstep_tick_does_not_allocate() {
    let experiment = load("experiments/bench/foraging-plastic.toml");
    let genomes = first_population(&experiment, &experiment.topology());
    let mut controllers: Vec<WorldBrains> = genomes[..3]
        .iter()
        .map(|g| {
            let brains = (0..CHUNK_TRIALS)
                .map(|_| controller(&experiment, g))
                .collect();
            WorldBrains::new(brains)
        })
        .collect();
    ticks_do_not_allocate(&experiment, &mut controllers);
}
