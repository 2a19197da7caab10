//! Plastic brains: MLP weights that change during a life by an evolved local rule
//! (`[brain] plasticity = "hebbian" | "neuromodulated"`).
//!
//! # The rule
//!
//! After the forward pass of a tick, every weight w of the network (from presynaptic value
//! `pre`, the input or hidden unit's activation, to postsynaptic `post`, the receiving unit's
//! output after its activation function, tanh for the output units) changes by the rule of
//! Soltoggio et al. (2008):
//!
//! ```text
//! Δw = η · (A·pre·post + B·pre + C·post + D) · g
//! w  = min(max(w + Δw, w_min), w_max)
//! ```
//!
//! with g = 1 for `"hebbian"` and g = tanh(m / 2) for `"neuromodulated"`, m being the tick's
//! modulatory signal (below). The coefficients (η, A, B, C, D) are genes: one set for the whole
//! network, one per weight layer or one per synapse (`granularity`). Biases never change.
//!
//! # Order of operations (what fixes the bits)
//!
//! The update runs once per tick, after the forward pass has written the outputs and before
//! the next tick reads the weights. Layers go in order (first hidden layer, …, output layer);
//! within a layer, synapses go input by input and, for each input, unit by unit (the order of
//! the network's input-major weight copy). Each synapse's change depends only on its own
//! weight, its pre and post values, its coefficients and m, so the order changes no bit; it is
//! fixed anyway. Each operation is a separate IEEE 754 multiply or add, never a fused
//! multiply-add (Rust does not contract `a * b + c`, and nothing here calls `mul_add`), in
//! exactly this order:
//!
//! ```text
//! s  = ((A·pre)·post + B·pre) + (C·post + D)
//! Δw = (η·g)·s
//! w  = clamp(w + Δw): w_min unless w + Δw > w_min, then w_max unless it is < w_max
//!      (so a NaN becomes w_min; one max and one min instruction each)
//! ```
//!
//! (This grouping lets a shared coefficient set compute C·post + D once per receiving unit
//! and η·g once per layer, which the per-synapse rule cannot; the values are the same.) On
//! x86-64 CPUs with AVX2 the update is compiled for AVX2 (4 synapses per instruction, still
//! without FMA), which gives the same bits as the portable build.
//!
//! m is summed from 0 in the order of `modulators`: `m += gene·signal` for a food detector
//! (`"food_a"` … `"food_d"`) or the shock sensor (`"shock"`), read from the observation the
//! brain was given (their indices found once, when the brain is built); for
//! `"metabolism_change"`, s_t = Σ_k g_k·x_k (the four metabolism inputs, left to right, with
//! four genes) and m = m + (s_t − s_{t−1}), 0 on the first tick of a life; for `"neurons"`,
//! each modulatory neuron k adds tanh(b_k + Σ_j w_kj·h_j) (h: the last hidden layer's
//! activations, or the inputs when there is none, summed left to right). tanh is the brains'
//! rational [`super::activation::tanh`], the same bits everywhere.
//!
//! # State and reset
//!
//! The live weights are the brain's state: [`crate::brain::Brain::reset`] (the start of a
//! life) restores the genome's weights (`initial_weights = "evolved"`) or draws a new set
//! (`"random"`, after Najarro & Risi 2020: uniform in [−1, 1], clamped to the bounds, biases
//! 0, the genome then holding only the rule's and the modulation's genes). Random weights come
//! from the life's own seed stream ([`crate::seed::Purpose::PlasticWeights`], keyed by the
//! life as the trial world is, see [`LifeKey`]), so a life gets the same weights on any
//! thread count. Nothing else resets the weights: a brain carried over several episodes keeps
//! what it learned.
//!
//! A plastic brain keeps state, so it is not [stateless](crate::brain::Brain::is_stateless):
//! evaluation runs it in lockstep with one copy per trial world
//! (`crate::evo::lockstep::WorldBrains`), never one brain for several worlds.

use super::activation::tanh;
use crate::seed::{stream, uniform, Generation, IndividualId, Purpose, Rng, Seed, TrialIndex};
use crate::sim::controller::{ObservationLayout, SensorGroup};
use crate::validate::{count_within, finite, InvalidValue, Valid};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use std::ops::Range;

/// Default `brain.weight_bounds`: plastic weights stay in [−4, 4].
pub const DEFAULT_WEIGHT_BOUNDS: [f64; 2] = [-4.0, 4.0];

/// Default number of modulatory neurons when `modulators` names `"neurons"`.
pub const DEFAULT_MODULATORY_NEURONS: usize = 1;

/// Largest number of modulatory neurons.
pub const MAX_MODULATORY_NEURONS: usize = 64;

/// Random initial weights are drawn uniformly from [−RANDOM_WEIGHT_RANGE, RANDOM_WEIGHT_RANGE]
/// (then clamped to the bounds).
pub const RANDOM_WEIGHT_RANGE: f64 = 1.0;

/// Whether and how an MLP's weights change during a life (`brain.plasticity`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Plasticity {
    /// Fixed weights (the default).
    #[default]
    None,
    /// Δw = η · (A·pre·post + B·pre + C·post + D) after every tick.
    Hebbian,
    /// The Hebbian change gated by tanh(m/2), m the tick's modulatory signal (`modulators`).
    Neuromodulated,
}

impl Plasticity {
    /// The name used in TOML.
    pub fn name(self) -> &'static str {
        match self {
            Plasticity::None => "none",
            Plasticity::Hebbian => "hebbian",
            Plasticity::Neuromodulated => "neuromodulated",
        }
    }
}

/// How many sets of rule coefficients (η, A, B, C, D) a plastic brain evolves
/// (`brain.granularity`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Granularity {
    /// One set for the whole network (5 genes; the default).
    #[default]
    Network,
    /// One set per weight layer (5 genes per hidden layer and for the output layer).
    Layer,
    /// One set per synapse (5 genes per weight).
    Synapse,
}

impl Granularity {
    /// The name used in TOML.
    pub fn name(self) -> &'static str {
        match self {
            Granularity::Network => "network",
            Granularity::Layer => "layer",
            Granularity::Synapse => "synapse",
        }
    }
}

/// Where a plastic brain's weights start each life (`brain.initial_weights`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum InitialWeights {
    /// The genome's weights (the default).
    #[default]
    Evolved,
    /// Drawn anew for each life from the life's seed stream (uniform in [−1, 1], biases 0);
    /// the genome holds only the rule's and the modulation's genes.
    Random,
}

impl InitialWeights {
    /// The name used in TOML.
    pub fn name(self) -> &'static str {
        match self {
            InitialWeights::Evolved => "evolved",
            InitialWeights::Random => "random",
        }
    }
}

/// A signal summed into the modulatory signal m (`brain.modulators`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Modulator {
    /// The food detector of type A (needs `creature.inputs.food`); one gene.
    FoodA,
    /// The food detector of type B; one gene.
    FoodB,
    /// The food detector of type C; one gene.
    FoodC,
    /// The food detector of type D; one gene.
    FoodD,
    /// The shock sensor (needs `creature.inputs.shock`); one gene.
    Shock,
    /// The change since the last tick of the metabolic vector's weighted sum (needs
    /// `creature.inputs.metabolism`); four genes, one per component.
    MetabolismChange,
    /// Evolved modulatory neurons fed by the last hidden layer (`modulatory_neurons` of them).
    Neurons,
}

impl Modulator {
    /// The name used in TOML.
    pub fn name(self) -> &'static str {
        match self {
            Modulator::FoodA => "food_a",
            Modulator::FoodB => "food_b",
            Modulator::FoodC => "food_c",
            Modulator::FoodD => "food_d",
            Modulator::Shock => "shock",
            Modulator::MetabolismChange => "metabolism_change",
            Modulator::Neurons => "neurons",
        }
    }
}

/// Where the signals that modulators read sit in the observation (the first index of each
/// sensor group), found once from the [`ObservationLayout`]; `None` for a group the creature
/// does not receive.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct SignalInputs {
    /// The four food detectors (A, B, C, D).
    pub food: Option<usize>,
    /// The shock sensor.
    pub shock: Option<usize>,
    /// The four metabolism inputs.
    pub metabolism: Option<usize>,
}

impl SignalInputs {
    /// The signals `layout` carries.
    pub fn from_layout(layout: &ObservationLayout) -> SignalInputs {
        let start = |group| layout.range(group).map(|r: Range<usize>| r.start);
        SignalInputs {
            food: start(SensorGroup::Food),
            shock: start(SensorGroup::Shock),
            metabolism: start(SensorGroup::Metabolism),
        }
    }

    /// The observation index of a food or shock modulator's signal, or of the first
    /// metabolism input; `None` when the creature lacks it (and for `"neurons"`, which reads
    /// no input).
    pub fn index(&self, modulator: Modulator) -> Option<usize> {
        match modulator {
            Modulator::FoodA => self.food,
            Modulator::FoodB => self.food.map(|i| i + 1),
            Modulator::FoodC => self.food.map(|i| i + 2),
            Modulator::FoodD => self.food.map(|i| i + 3),
            Modulator::Shock => self.shock,
            Modulator::MetabolismChange => self.metabolism,
            Modulator::Neurons => None,
        }
    }

    /// Every modulator in `modulators` has its signal, or the error names `brain.modulators`
    /// and the `[creature.inputs]` switch to turn on.
    pub fn check(&self, modulators: &[Modulator]) -> Valid {
        for &m in modulators {
            let switch = match m {
                Modulator::Neurons => continue,
                Modulator::Shock => "shock",
                Modulator::MetabolismChange => "metabolism",
                _ => "food",
            };
            if self.index(m).is_none() {
                return Err(InvalidValue::new(
                    "brain.modulators",
                    format!(
                        "\"{}\" reads a sensor this creature does not have: switch on \
                         `creature.inputs.{switch} = true`, or remove \"{}\"",
                        m.name(),
                        m.name()
                    ),
                ));
            }
        }
        Ok(())
    }
}

/// The plasticity settings of a `[brain]` table with their defaults filled in (for a brain
/// whose `plasticity` is not `"none"`).
#[derive(Debug, Clone, PartialEq)]
pub struct PlasticSettings {
    /// `"hebbian"` or `"neuromodulated"`.
    pub rule: Plasticity,
    /// How many coefficient sets.
    pub granularity: Granularity,
    /// [w_min, w_max].
    pub bounds: [f64; 2],
    /// Evolved or random initial weights.
    pub initial: InitialWeights,
    /// The modulatory signals, in the order m sums them.
    pub modulators: Vec<Modulator>,
    /// Modulatory neurons (0 unless `"neurons"` is a modulator).
    pub neurons: usize,
}

impl PlasticSettings {
    /// Checks the settings (keys `brain.*`): bounds finite with min < max, modulators only for
    /// the neuromodulated rule, at least one for it, none twice, and a modulatory neuron count
    /// only with `"neurons"`.
    pub(crate) fn validate(&self, neurons_given: bool) -> Valid {
        let [lo, hi] = self.bounds;
        finite("brain.weight_bounds[0]", lo)?;
        finite("brain.weight_bounds[1]", hi)?;
        if lo >= hi {
            return Err(InvalidValue::new(
                "brain.weight_bounds",
                format!("must be [min, max] with min < max, got [{lo}, {hi}]"),
            ));
        }
        match self.rule {
            Plasticity::Hebbian if !self.modulators.is_empty() => {
                return Err(InvalidValue::new(
                    "brain.modulators",
                    "only a neuromodulated rule reads modulators: set \
                     `brain.plasticity = \"neuromodulated\"` or remove `brain.modulators`",
                ));
            }
            Plasticity::Neuromodulated if self.modulators.is_empty() => {
                return Err(InvalidValue::new(
                    "brain.modulators",
                    "a neuromodulated rule needs at least one modulator, e.g. \
                     `modulators = [\"food_a\"]` (\"food_a\"..\"food_d\", \"shock\", \
                     \"metabolism_change\", \"neurons\")",
                ));
            }
            _ => {}
        }
        for (k, m) in self.modulators.iter().enumerate() {
            if self.modulators[..k].contains(m) {
                return Err(InvalidValue::new(
                    "brain.modulators",
                    format!("names \"{}\" twice", m.name()),
                ));
            }
        }
        let has_neurons = self.modulators.contains(&Modulator::Neurons);
        if neurons_given && !has_neurons {
            return Err(InvalidValue::new(
                "brain.modulatory_neurons",
                "applies only when `brain.modulators` names \"neurons\"; add it or remove this key",
            ));
        }
        if has_neurons {
            count_within(
                "brain.modulatory_neurons",
                self.neurons as u64,
                1,
                MAX_MODULATORY_NEURONS as u64,
                "modulatory neurons",
            )?;
        }
        Ok(())
    }

    /// The number of rule coefficient genes for weight layers of `sizes` ((units, inputs)
    /// per layer).
    pub(crate) fn rule_genes(&self, sizes: &[(usize, usize)]) -> usize {
        match self.granularity {
            Granularity::Network => 5,
            Granularity::Layer => 5 * sizes.len(),
            Granularity::Synapse => 5 * sizes.iter().map(|&(u, i)| u * i).sum::<usize>(),
        }
    }

    /// The number of modulation genes, with `source` values feeding the modulatory neurons.
    fn modulation_genes(&self, source: usize) -> usize {
        self.modulators
            .iter()
            .map(|m| match m {
                Modulator::MetabolismChange => 4,
                Modulator::Neurons => self.neurons * (source + 1),
                _ => 1,
            })
            .sum()
    }

    /// Genes the plasticity adds to (or, with random initial weights, puts instead of) the
    /// network's weights and biases. `sizes` are the weight layers' (units, inputs), `source`
    /// the width of the last hidden layer (or the inputs).
    pub(crate) fn gene_count(&self, sizes: &[(usize, usize)], source: usize) -> usize {
        self.rule_genes(sizes) + self.modulation_genes(source)
    }

    /// The plasticity genes' names, in genome order (see [`crate::brain::Topology`]).
    pub(crate) fn gene_names(
        &self,
        sizes: &[(usize, usize)],
        layer_names: &[String],
        source: usize,
        names: &mut Vec<String>,
    ) {
        const COEFFICIENTS: [&str; 5] = ["eta", "a", "b", "c", "d"];
        match self.granularity {
            Granularity::Network => {
                names.extend(COEFFICIENTS.iter().map(|c| format!("rule_{c}")));
            }
            Granularity::Layer => {
                for layer in layer_names {
                    names.extend(COEFFICIENTS.iter().map(|c| format!("rule_{c}_{layer}")));
                }
            }
            Granularity::Synapse => {
                for (layer, &(units, inputs)) in layer_names.iter().zip(sizes) {
                    for c in COEFFICIENTS {
                        for j in 0..units {
                            names
                                .extend((0..inputs).map(|i| format!("rule_{c}_{layer}[{j}][{i}]")));
                        }
                    }
                }
            }
        }
        for m in &self.modulators {
            match m {
                Modulator::MetabolismChange => {
                    names.extend((0..4).map(|k| format!("mod_metabolism[{k}]")));
                }
                Modulator::Neurons => {
                    for k in 0..self.neurons {
                        names.extend((0..source).map(|j| format!("w_mod[{k}][{j}]")));
                    }
                    names.extend((0..self.neurons).map(|k| format!("b_mod[{k}]")));
                }
                other => names.push(format!("mod_{}", other.name())),
            }
        }
    }
}

/// Which life a brain lives: the same coordinates as the life's trial world
/// ([`crate::evo::life::trial_stream`]), with the individual's own index, so that random
/// initial weights are drawn from [`Purpose::PlasticWeights`] streams that depend on the life
/// only, not on threads or on the order lives run in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct LifeKey {
    /// The run's master seed.
    pub seed: Seed,
    /// The generation (or 0 for worlds outside evolution).
    pub generation: Generation,
    /// The individual.
    pub individual: IndividualId,
    /// The trial.
    pub trial: TrialIndex,
}

impl LifeKey {
    /// The stream random initial weights are drawn from.
    fn stream(&self) -> Rng {
        stream(
            self.seed,
            Purpose::PlasticWeights,
            self.generation,
            self.individual,
            self.trial,
        )
    }
}

/// A term of the modulatory signal, in `modulators` order.
#[derive(Debug, Clone, PartialEq)]
enum Term {
    /// gene · observation[index].
    Signal { index: usize, gene: f64 },
    /// The change of Σ_k genes[k] · observation[start + k] since the last tick.
    Metabolism { start: usize, genes: [f64; 4] },
    /// Modulatory neurons: `weights` (neurons × source, row-major) then `biases` in the
    /// genome slice held by [`Plastic`].
    Neurons {
        neurons: usize,
        source: usize,
        weights: Range<usize>,
        biases: Range<usize>,
    },
}

/// One weight layer's coefficients: one set, or one per synapse (input-major, like the
/// weights, at `range` in each of the five coefficient arrays).
#[derive(Debug, Clone, PartialEq)]
enum Coefficients {
    Shared([f64; 5]),
    PerSynapse(Range<usize>),
}

/// A plastic MLP's rule, modulation, initial weights and per-life state (held by
/// [`super::mlp::Mlp`]).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Plastic {
    rule: Plasticity,
    bounds: [f64; 2],
    initial: InitialWeights,
    /// Per weight layer (hidden layers, then the output layer).
    layers: Vec<Coefficients>,
    /// Per-synapse η, A, B, C, D, each input-major over all layers (empty unless
    /// `granularity = "synapse"`).
    synapse: [Vec<f64>; 5],
    /// The modulation genes (copied from the genome).
    genes: Vec<f64>,
    terms: Vec<Term>,
    /// The input-major weights a life starts from (evolved: the genome's; random: the last
    /// draw).
    start: Vec<f64>,
    /// Which life, for random initial weights.
    life: LifeKey,
    /// s_{t−1} of `"metabolism_change"`, and whether there was a previous tick in this life.
    previous: f64,
    has_previous: bool,
    /// C·post + D of each receiving unit of a layer with shared coefficients (scratch, as
    /// wide as the widest layer, so that the tick allocates nothing).
    post_terms: Vec<f64>,
    /// The last tick's m (0 before the first): one store per tick, kept because a trace
    /// cannot recompute it after the tick (the metabolism term's s_{t−1} is overwritten).
    last_m: f64,
}

impl Plastic {
    /// The rule of `settings` with its genes `genes` (the plasticity part of the genome, in
    /// the order of [`PlasticSettings::gene_names`]), for weight layers `sizes` whose
    /// input-major weights are `transposed`; `signals` locates the modulators' inputs
    /// (checked by the topology). With random initial weights, `transposed` is overwritten by
    /// the first life's draw.
    pub(crate) fn new(
        settings: &PlasticSettings,
        sizes: &[(usize, usize)],
        source: usize,
        signals: &SignalInputs,
        genes: &[f64],
        transposed: &mut [f64],
    ) -> Plastic {
        let rule_end = settings.rule_genes(sizes);
        let mut offset = 0;
        let mut take = |n: usize| {
            let r = offset..offset + n;
            offset += n;
            r
        };
        let five = |g: &[f64]| [g[0], g[1], g[2], g[3], g[4]];
        let mut synapse: [Vec<f64>; 5] = Default::default();
        let layers = match settings.granularity {
            Granularity::Network => {
                let set = five(&genes[take(5)]);
                vec![Coefficients::Shared(set); sizes.len()]
            }
            Granularity::Layer => sizes
                .iter()
                .map(|_| Coefficients::Shared(five(&genes[take(5)])))
                .collect(),
            Granularity::Synapse => {
                let total: usize = sizes.iter().map(|&(u, i)| u * i).sum();
                for array in &mut synapse {
                    array.reserve_exact(total);
                }
                sizes
                    .iter()
                    .map(|&(units, inputs)| {
                        let start = synapse[0].len();
                        for array in &mut synapse {
                            // Genome: unit-major (j, i); here input-major (i, j) like the
                            // weights the forward pass reads.
                            let block = &genes[take(units * inputs)];
                            for i in 0..inputs {
                                array.extend((0..units).map(|j| block[j * inputs + i]));
                            }
                        }
                        Coefficients::PerSynapse(start..synapse[0].len())
                    })
                    .collect()
            }
        };
        let mut terms = Vec::with_capacity(settings.modulators.len());
        for &m in &settings.modulators {
            let term = match m {
                Modulator::MetabolismChange => {
                    let g = &genes[take(4)];
                    Term::Metabolism {
                        start: signals.metabolism.unwrap_or(0),
                        genes: [g[0], g[1], g[2], g[3]],
                    }
                }
                Modulator::Neurons => {
                    let weights = take(settings.neurons * source);
                    let biases = take(settings.neurons);
                    Term::Neurons {
                        neurons: settings.neurons,
                        source,
                        weights: weights.start - rule_end..weights.end - rule_end,
                        biases: biases.start - rule_end..biases.end - rule_end,
                    }
                }
                other => Term::Signal {
                    index: signals.index(other).unwrap_or(0),
                    gene: genes[take(1)][0],
                },
            };
            terms.push(term);
        }
        let mut plastic = Plastic {
            rule: settings.rule,
            bounds: settings.bounds,
            initial: settings.initial,
            layers,
            synapse,
            genes: genes[rule_end..].to_vec(),
            terms,
            start: transposed.to_vec(),
            life: LifeKey::default(),
            previous: 0.0,
            has_previous: false,
            post_terms: vec![0.0; sizes.iter().map(|&(units, _)| units).max().unwrap_or(0)],
            last_m: 0.0,
        };
        plastic.reset(transposed);
        plastic
    }

    /// Sets the life the next resets draw random initial weights for, and resets.
    pub(crate) fn start_life(&mut self, life: LifeKey, weights: &mut [f64]) {
        self.life = life;
        self.reset(weights);
    }

    /// The start of a life: the weights back to the genome's (or a new draw from the life's
    /// stream: the same life always draws the same), no previous metabolism.
    pub(crate) fn reset(&mut self, weights: &mut [f64]) {
        if self.initial == InitialWeights::Random {
            let mut rng = self.life.stream();
            let [lo, hi] = self.bounds;
            for w in &mut self.start {
                let x = uniform(&mut rng, -RANDOM_WEIGHT_RANGE, RANDOM_WEIGHT_RANGE);
                *w = x.max(lo).min(hi);
            }
        }
        weights.copy_from_slice(&self.start);
        self.previous = 0.0;
        self.has_previous = false;
        // Scratch only, cleared so that a reset brain equals a new one.
        self.post_terms.fill(0.0);
        self.last_m = 0.0;
    }

    /// The modulatory signal m of the last tick (0 before the first tick of a life), for a
    /// neuromodulated rule; None for a Hebbian one (g = 1). Its gate g is
    /// [`tanh`]`(m * 0.5)`, the same expression the update computes, so the same bits.
    pub(crate) fn last_modulation(&self) -> Option<f64> {
        (self.rule == Plasticity::Neuromodulated).then_some(self.last_m)
    }

    /// The tick's modulatory signal m from the observation `inputs` and `source` (the last
    /// hidden layer's activations, or the inputs).
    fn modulation(&mut self, inputs: &[f64], source: &[f64]) -> f64 {
        let mut m = 0.0;
        for term in &self.terms {
            match term {
                Term::Signal { index, gene } => m += gene * inputs[*index],
                Term::Metabolism { start, genes } => {
                    let x = &inputs[*start..*start + 4];
                    let s = genes[0] * x[0] + genes[1] * x[1] + genes[2] * x[2] + genes[3] * x[3];
                    if self.has_previous {
                        m += s - self.previous;
                    }
                    self.previous = s;
                    self.has_previous = true;
                }
                Term::Neurons {
                    neurons,
                    source: width,
                    weights,
                    biases,
                } => {
                    let w = &self.genes[weights.clone()];
                    let b = &self.genes[biases.clone()];
                    for k in 0..*neurons {
                        let mut s = b[k];
                        for (wkj, hj) in w[k * width..(k + 1) * width].iter().zip(source) {
                            s += wkj * hj;
                        }
                        m += tanh(s);
                    }
                }
            }
        }
        m
    }

    /// The update after a forward pass (see the module docs for the order): `layers` gives
    /// each weight layer's input-major weights range in `weights`, its input values and its
    /// output values (post-activation). Inlined into the caller, so that it is compiled with
    /// the caller's target features (see [`super::mlp`]).
    #[inline(always)]
    pub(crate) fn update<'a>(
        &mut self,
        weights: &mut [f64],
        layers: impl Iterator<Item = (Range<usize>, &'a [f64], &'a [f64])>,
        inputs: &[f64],
        source: &[f64],
    ) {
        let g = match self.rule {
            Plasticity::Neuromodulated => {
                self.last_m = self.modulation(inputs, source);
                tanh(self.last_m * 0.5)
            }
            _ => 1.0,
        };
        let [lo, hi] = self.bounds;
        for ((range, pre, post), coefficients) in layers.zip(&self.layers) {
            let w = &mut weights[range];
            let units = post.len();
            match coefficients {
                Coefficients::Shared([eta, a, b, c, d]) => {
                    let q = &mut self.post_terms[..units];
                    for (q, &y) in q.iter_mut().zip(post) {
                        *q = c * y + d;
                    }
                    let q: &[f64] = q;
                    let eg = eta * g;
                    for (row, &x) in w.chunks_exact_mut(units).zip(pre) {
                        let (ax, bx) = (a * x, b * x);
                        for ((wij, &y), &q) in row.iter_mut().zip(post).zip(q) {
                            let s = (ax * y + bx) + q;
                            *wij = clamp(*wij + eg * s, lo, hi);
                        }
                    }
                }
                Coefficients::PerSynapse(r) => {
                    let [eta, a, b, c, d] = &self.synapse;
                    let (eta, a, b, c, d) = (
                        &eta[r.clone()],
                        &a[r.clone()],
                        &b[r.clone()],
                        &c[r.clone()],
                        &d[r.clone()],
                    );
                    for (i, &x) in pre.iter().enumerate() {
                        let k = i * units..(i + 1) * units;
                        let row = &mut w[k.clone()];
                        let coefficients = eta[k.clone()]
                            .iter()
                            .zip(&a[k.clone()])
                            .zip(&b[k.clone()])
                            .zip(&c[k.clone()])
                            .zip(&d[k]);
                        for ((wij, &y), ((((eta, a), b), c), d)) in
                            row.iter_mut().zip(post).zip(coefficients)
                        {
                            let s = (a * x * y + b * x) + (c * y + d);
                            *wij = clamp(*wij + (eta * g) * s, lo, hi);
                        }
                    }
                }
            }
        }
    }
}

/// `x` clamped to [lo, hi] by two comparisons: lo unless x > lo (so NaN gives lo), then hi
/// unless the result is < hi. Written as selects that compile to one `maxpd` and one `minpd`
/// (whose x86 semantics, the second operand when either is NaN, are exactly these), where
/// `f64::max`/`min` add a NaN test and a blend each.
#[inline(always)]
fn clamp(x: f64, lo: f64, hi: f64) -> f64 {
    let x = if x > lo { x } else { lo };
    if x < hi {
        x
    } else {
        hi
    }
}
