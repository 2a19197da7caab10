//! The scaling series' worlds: a world tiled k × k times at the same density of walls and
//! food, so that `bench --scaling` can show how the cost of a creature-tick grows with the
//! size of the world (docs/performance.md).

use crate::sim::spec::WorldSpec;
use thiserror::Error;

/// Why a world cannot be tiled.
#[derive(Debug, Error, PartialEq, Eq)]
pub enum TilingError {
    /// Gadgets, areas and landmarks have no tiled meaning (whose door, which nest?).
    #[error(
        "the scaling series tiles walls and food only; the base world has gadgets, areas or \
         landmarks (give `--scaling-world` a world of walls and food)"
    )]
    NotWallsAndFood,
    /// The corner pieces copy an interior wall's look.
    #[error(
        "the scaling series needs a base world with at least one interior wall, whose look the \
         corner pieces copy; add a `[[world.walls]]` entry"
    )]
    NoInteriorWall,
}

/// The scaling series' world `k`: `base` (a w × h arena) tiled k × k times into a kw × kh
/// arena at the same density of walls and food. Tile (i, j) holds a copy of every
/// `[[world.walls]]` entry and explicit object of `base`, shifted by (iw, jh); placement
/// rules place k² times as many objects over their region tiled the same way (a rule without
/// a region covers the whole larger arena). The arena's 4 boundary walls are shared, so
/// every tile but the first also gets 4 short free-standing wall pieces (two L-shaped pairs
/// in opposite corners) to replace the boundary walls it lacks: the tiled world has
/// exactly k² times `base`'s walls when `base` has boundary walls and 8 interior walls,
/// as the benchmark world does (12 → 1,200 walls for k = 10). `k = 1` is `base` itself.
pub fn tiled_world(base: &WorldSpec, k: u32) -> Result<WorldSpec, TilingError> {
    if k <= 1 {
        return Ok(base.clone());
    }
    if !(base.doors.is_empty()
        && base.teleporters.is_empty()
        && base.predators.is_empty()
        && base.air_predators.is_empty()
        && base.wanderers.count == 0
        && base.areas.is_empty()
        && base.landmarks.is_empty())
    {
        return Err(TilingError::NotWallsAndFood);
    }
    let [w, h] = base.arena;
    let mut spec = base.clone();
    spec.arena = [w * f64::from(k), h * f64::from(k)];
    spec.walls.clear();
    spec.objects.clear();
    // Corner pieces as fractions of the tile: (from, to).
    const PIECES: [([f64; 2], [f64; 2]); 4] = [
        ([0.05, 0.05], [0.2, 0.05]),
        ([0.05, 0.1], [0.05, 0.25]),
        ([0.8, 0.95], [0.95, 0.95]),
        ([0.95, 0.8], [0.95, 0.9]),
    ];
    for j in 0..k {
        for i in 0..k {
            let (dx, dy) = (w * f64::from(i), h * f64::from(j));
            let shift = |p: [f64; 2]| [p[0] + dx, p[1] + dy];
            for wall in &base.walls {
                let mut wall = wall.clone();
                wall.from = shift(wall.from);
                wall.to = shift(wall.to);
                spec.walls.push(wall);
            }
            if i + j > 0 && base.boundary_walls {
                for (from, to) in PIECES {
                    let mut wall = base
                        .walls
                        .first()
                        .cloned()
                        .ok_or(TilingError::NoInteriorWall)?;
                    wall.from = shift([from[0] * w, from[1] * h]);
                    wall.to = shift([to[0] * w, to[1] * h]);
                    wall.opaque = true;
                    spec.walls.push(wall);
                }
            }
            for object in &base.objects {
                let mut object = object.clone();
                object.position = shift(object.position);
                spec.objects.push(object);
            }
        }
    }
    spec.place.clear();
    for rule in &base.place {
        match rule.region {
            None => {
                let mut rule = rule.clone();
                rule.count *= u64::from(k) * u64::from(k);
                spec.place.push(rule);
            }
            Some([x0, y0, x1, y1]) => {
                for j in 0..k {
                    for i in 0..k {
                        let (dx, dy) = (w * f64::from(i), h * f64::from(j));
                        let mut rule = rule.clone();
                        rule.region = Some([x0 + dx, y0 + dy, x1 + dx, y1 + dy]);
                        spec.place.push(rule);
                    }
                }
            }
        }
    }
    if let Some([x0, y0, x1, y1]) = base.start.region {
        // One creature per world: it starts in the first tile's start region.
        spec.start.region = Some([x0, y0, x1, y1]);
    }
    Ok(spec)
}

/// Number of food and aversive objects a world spec will hold (explicit plus placed).
pub fn object_count(spec: &WorldSpec) -> u64 {
    spec.objects.len() as u64 + spec.place.iter().map(|p| p.count).sum::<u64>()
}

/// Number of walls of a world spec, boundary walls included.
pub fn wall_count(spec: &WorldSpec) -> usize {
    spec.walls.len() + if spec.boundary_walls { 4 } else { 0 }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::experiment::Experiment;
    use crate::seed::{stream, Generation, IndividualId, Purpose, TrialIndex};
    use crate::sim::world::World;
    use std::path::Path;

    fn bench_world() -> Experiment {
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        Experiment::load(&root.join("experiments/bench/foraging-world.toml")).unwrap()
    }

    #[test]
    fn tiling_keeps_the_density_of_walls_and_food() {
        let experiment = bench_world();
        let base = &experiment.world;
        assert_eq!(tiled_world(base, 1).unwrap(), *base);
        for k in [2u32, 5, 10] {
            let spec = tiled_world(base, k).unwrap();
            let k2 = u64::from(k * k);
            assert_eq!(spec.arena, [300.0 * f64::from(k), 300.0 * f64::from(k)]);
            assert_eq!(wall_count(&spec) as u64, 12 * k2, "k = {k}");
            assert_eq!(object_count(&spec), 40 * k2, "k = {k}");
            for wall in &spec.walls {
                for p in [wall.from, wall.to] {
                    assert!(p[0] >= 0.0 && p[0] <= spec.arena[0], "{p:?}");
                    assert!(p[1] >= 0.0 && p[1] <= spec.arena[1], "{p:?}");
                }
            }
        }
        // The largest world of the series can be built and run.
        let spec = tiled_world(base, 10).unwrap();
        let rng = stream(
            experiment.seed(),
            Purpose::Baseline,
            Generation(0),
            IndividualId(0),
            TrialIndex(0),
        );
        let world = World::new(&spec, &experiment.creature, 1, rng).unwrap();
        assert_eq!(world.creatures().len(), 1);
    }

    #[test]
    fn worlds_with_gadgets_are_refused() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        let experiment = Experiment::load(&root.join("experiments/predator-arena.toml")).unwrap();
        assert_eq!(
            tiled_world(&experiment.world, 2),
            Err(TilingError::NotWallsAndFood)
        );
    }
}
