//! Batched MLP forward passes through the public API: `Brain::activate_batch` gives every
//! observation the bits of a single pass, for every activation and many batch sizes
//! (`BrainController::act_batch`, which must also allocate nothing once warmed up, is checked
//! in tests/alloc/brain_batches.rs); and `precision = "f32"`: batch bits, closeness to f64,
//! fused multiply-add sums, the TOML key, its refusal outside MLPs, and genome files carrying it.

use berry_evolve::brain::{Brain, BrainSpec, Precision, Topology};

use crate::brain_common::batch::{brain, values};

fn bits(v: &[f64]) -> Vec<u64> {
    v.iter().map(|f| f.to_bits()).collect()
}

#[test]
fn brain_batches_match_single_passes_bit_for_bit() {
    let shapes = [
        ("hidden = [16]", 24, 2),
        ("hidden = [16]", 24, 3),
        ("hidden = [100]", 98, 2),
        ("hidden = [7, 3]", 5, 3),
        ("hidden = []", 1, 2),
    ];
    for (k, (hidden, inputs, outputs)) in shapes.into_iter().enumerate() {
        for activation in ["tanh", "sigmoid", "relu"] {
            let text = format!("kind = \"mlp\"\n{hidden}\nactivation = \"{activation}\"");
            let mut batch = brain(&text, inputs, outputs, 100 + k as u64);
            let mut single = batch.clone();
            for n in (0..=9).chain([16, 33, 32, 5]) {
                let x = values(1000 + n as u64, n * inputs, 4.0);
                let mut y = vec![f64::NAN; n * outputs];
                batch.activate_batch(&x, &mut y);
                let mut expected = vec![0.0; n * outputs];
                for (xs, ys) in x
                    .chunks_exact(inputs)
                    .zip(expected.chunks_exact_mut(outputs))
                {
                    single.activate(xs, ys);
                }
                assert_eq!(bits(&y), bits(&expected), "{text} n={n}");
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------
// precision = "f32"

#[test]
fn f32_batches_match_single_passes_bit_for_bit_and_stay_near_f64() {
    for (hidden, inputs, outputs) in [("hidden = [16]", 24, 3), ("hidden = [100]", 98, 2)] {
        for activation in ["tanh", "sigmoid", "relu"] {
            let text = format!("{hidden}\nactivation = \"{activation}\"");
            let narrow_text = format!("{text}\nprecision = \"f32\"");
            let mut narrow = brain(&narrow_text, inputs, outputs, 11);
            let mut single = narrow.clone();
            let mut wide = brain(&text, inputs, outputs, 11);
            for n in [1, 3, 8, 13, 32] {
                let x = values(2000 + n as u64, n * inputs, 1.0);
                let mut y = vec![f64::NAN; n * outputs];
                narrow.activate_batch(&x, &mut y);
                let mut expected = vec![0.0; n * outputs];
                let mut reference = vec![0.0; n * outputs];
                wide.activate_batch(&x, &mut reference);
                for (xs, ys) in x
                    .chunks_exact(inputs)
                    .zip(expected.chunks_exact_mut(outputs))
                {
                    single.activate(xs, ys);
                }
                assert_eq!(bits(&y), bits(&expected), "{narrow_text} n={n}");
                // Weights in ±2 make saturated units; unsaturated sums differ by ~1e-6.
                for (a, b) in y.iter().zip(&reference) {
                    assert!((a - b).abs() <= 1e-4, "{narrow_text} n={n}: {a} vs {b}");
                }
            }
        }
    }
}

/// Through the public API, an f32 sum is a fused multiply-add: with w = x = 1 + 2⁻¹² and bias
/// −1 the exact sum 2⁻¹¹ + 2⁻²⁴ survives (a separate f32 multiply would round w·x to
/// 1 + 2⁻¹¹, leaving 2⁻¹¹), in single passes and batches alike.
#[test]
fn f32_sums_are_fused_through_the_public_api() {
    let spec: BrainSpec = toml::from_str("hidden = []\nprecision = \"f32\"").expect("spec");
    let topology = Topology::new(spec, 1, 2).expect("topology");
    let w = 1.0 + 2f64.powi(-12);
    let mut brain = Brain::new(&topology, &[w, w, -1.0, -1.0]).expect("brain");
    let fused = 2f64.powi(-11) + 2f64.powi(-24);
    let expected = f64::from(berry_evolve::brain::activation::tanh(fused) as f32);
    let unfused = f64::from(berry_evolve::brain::activation::tanh(2f64.powi(-11)) as f32);
    assert_ne!(expected, unfused);
    let mut y = [f64::NAN; 2];
    brain.activate(&[w], &mut y);
    assert_eq!(bits(&y), bits(&[expected; 2]));
    let mut batch = [f64::NAN; 10];
    brain.activate_batch(&[w; 5], &mut batch);
    assert_eq!(bits(&batch), bits(&[expected; 10]));
}

#[test]
fn precision_round_trips_through_toml_and_defaults_to_f64_unwritten() {
    let narrow: BrainSpec = toml::from_str("kind = \"mlp\"\nprecision = \"f32\"").expect("f32");
    assert_eq!(narrow.precision, Some(Precision::F32));
    let text = toml::to_string(&narrow).expect("serialises");
    assert!(text.contains("precision = \"f32\""), "{text}");
    let back: BrainSpec = toml::from_str(&text).expect("reads back");
    assert_eq!(back, narrow);
    let explicit: BrainSpec = toml::from_str("precision = \"f64\"").expect("f64");
    assert_eq!(explicit.precision, Some(Precision::F64));
    // A spec without the key (every file written before it existed) reads as before and
    // writes no key, so its bytes and config hashes do not change.
    let old: BrainSpec = toml::from_str("kind = \"mlp\"\nhidden = [16]").expect("old spec");
    assert_eq!(old.precision, None);
    assert!(!toml::to_string(&old)
        .expect("serialises")
        .contains("precision"));
    let json = serde_json::to_string(&old).expect("json");
    assert!(!json.contains("precision"), "{json}");
    assert!(toml::from_str::<BrainSpec>("precision = \"f16\"").is_err());
    // The brain built from it computes in f32; the default in f64 with unchanged bits.
    let narrow_brain = brain("precision = \"f32\"", 24, 2, 3);
    let Brain::Mlp(mlp) = &narrow_brain else {
        panic!("not an mlp")
    };
    assert_eq!(mlp.precision(), Precision::F32);
    let (mut a, mut b) = (brain("", 24, 2, 3), brain("precision = \"f64\"", 24, 2, 3));
    let x = values(4, 24, 1.0);
    let (mut ya, mut yb) = ([0.0; 2], [0.0; 2]);
    a.activate(&x, &mut ya);
    b.activate(&x, &mut yb);
    assert_eq!(bits(&ya), bits(&yb));
}

#[test]
fn f32_is_refused_on_recurrent_and_ctrnn_brains() {
    for kind in ["recurrent", "ctrnn"] {
        let spec: BrainSpec =
            toml::from_str(&format!("kind = \"{kind}\"\nprecision = \"f32\"")).expect("parses");
        let message = spec.validate().expect_err("refused").to_string();
        assert!(message.contains("brain.precision"), "{message}");
        assert!(message.contains("mlp"), "{message}");
        assert!(Topology::new(spec, 4, 2).is_err());
        // "f64" is what they compute anyway: accepted.
        let spec: BrainSpec =
            toml::from_str(&format!("kind = \"{kind}\"\nprecision = \"f64\"")).expect("parses");
        spec.validate().expect("f64 accepted");
    }
}

#[test]
fn precision_travels_with_genome_files() {
    use berry_evolve::record::genome_file::{GenomeFile, Origin, GENOME_FORMAT};
    use std::path::Path;
    let spec: BrainSpec = toml::from_str("hidden = [3]\nprecision = \"f32\"").expect("spec");
    let topology = Topology::new(spec.clone(), 2, 2).expect("topology");
    let file = GenomeFile {
        format: GENOME_FORMAT,
        brain: spec,
        inputs: vec!["a".into(), "b".into()],
        outputs: vec!["left".into(), "right".into()],
        parameters: values(5, topology.parameter_count(), 1.0),
        step_size: None,
        origin: Origin::default(),
    };
    let json = file.to_json();
    assert!(String::from_utf8_lossy(&json).contains("\"precision\": \"f32\""));
    let back = GenomeFile::from_slice(&json, Path::new("g.json")).expect("reads back");
    assert_eq!(back, file);
    assert_eq!(back.brain.precision, Some(Precision::F32));
    // A recurrent genome claiming f32 is refused when read.
    let mut recurrent = file.clone();
    recurrent.brain = toml::from_str("kind = \"recurrent\"\nhidden = [3]").expect("spec");
    recurrent.brain.precision = Some(Precision::F32);
    let error = GenomeFile::from_slice(&recurrent.to_json(), Path::new("r.json"))
        .expect_err("refused")
        .to_string();
    assert!(error.contains("brain.precision"), "{error}");
}
