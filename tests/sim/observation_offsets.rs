//! `Offsets::write` writes smell, whiskers, food detectors and shock as one block when
//! the controller receives all of them, else group by group: for every combination of input
//! groups, what it writes is the plain placement of each group at its layout range, and it
//! leaves the landmarks, areas and eye (written by the world) untouched.

use berry_evolve::sim::controller::{GroupSizes, InputsSpec, ObservationLayout, SensorGroup};
use berry_evolve::sim::sensors::{Offsets, Senses};

#[test]
fn write_places_every_group_at_its_layout_range() {
    let sizes = GroupSizes {
        landmarks: 2,
        areas: 3,
        retina: [4, 2],
    };
    let senses = Senses {
        whiskers: [true, false],
        smell: [
            [0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8],
            [0.9, 0.15, 0.25, 0.35, 0.45, 0.55, 0.65, 0.75],
        ],
        food: [false, true, true, false],
    };
    let metabolism = [1.5, -2.5, 3.25, 0.125];
    let mut blocks = 0;
    for mask in 0u32..512 {
        let on = |k: u32| mask & (1 << k) != 0;
        let inputs = InputsSpec {
            smell: on(0),
            whiskers: on(1),
            food: on(2),
            shock: on(3),
            metabolism: on(4),
            bias: on(5),
            landmarks: on(6),
            areas: on(7),
            eye: on(8),
        };
        let layout = ObservationLayout::new(&inputs, &sizes);
        blocks += usize::from(mask & 0b1111 == 0b1111);
        for shock in [false, true] {
            let mut got = vec![-7.0; layout.len()];
            Offsets::new(&layout).write(&mut got, &senses, shock, &metabolism);
            let mut want = vec![-7.0; layout.len()];
            let bit = |b: bool| if b { 1.0 } else { 0.0 };
            for group in SensorGroup::ORDER {
                let Some(r) = layout.range(group) else {
                    continue;
                };
                let values: Vec<f64> = match group {
                    SensorGroup::Smell => senses.smell.concat(),
                    SensorGroup::Whiskers => senses.whiskers.map(bit).to_vec(),
                    SensorGroup::Food => senses.food.map(bit).to_vec(),
                    SensorGroup::Shock => vec![bit(shock)],
                    SensorGroup::Metabolism => metabolism.to_vec(),
                    SensorGroup::Bias => vec![1.0],
                    _ => continue,
                };
                want[r].copy_from_slice(&values);
            }
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&got), bits(&want), "inputs {inputs:?}, shock {shock}");
        }
    }
    assert_eq!(blocks, 32);
}
