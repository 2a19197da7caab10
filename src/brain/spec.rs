//! The `[brain]` TOML table ([`BrainSpec`]) and the [`Topology`] it defines once the number of
//! inputs and outputs is known: its validation, its parameter count and the documented order
//! of its parameters.
//!
//! ```toml
//! [brain]
//! kind = "mlp"          # "mlp" | "recurrent" | "ctrnn"
//! hidden = [16]         # mlp, recurrent
//! activation = "tanh"   # mlp, recurrent: "tanh" | "sigmoid" | "relu"
//! precision = "f64"     # mlp only: "f64" (default) | "f32" (opt-in, changes results)
//!
//! # or
//! [brain]
//! kind = "ctrnn"
//! neurons = 8
//! step = 0.2            # Euler step, time units
//! substeps = 5          # Euler steps per world tick
//! tau = [1.0, 10.0]     # time constant range, time units
//! gain = [1.0, 5.0]
//! ```
//!
//! Fields that do not apply to the chosen `kind` are rejected rather than ignored, so that a
//! user who writes `neurons = 32` on an MLP learns that it has no effect.

use super::activation::Activation;
use super::plasticity::{
    Granularity, InitialWeights, Modulator, PlasticSettings, Plasticity, SignalInputs,
    DEFAULT_MODULATORY_NEURONS, DEFAULT_WEIGHT_BOUNDS,
};
use crate::validate::{count_within, finite, positive, InvalidValue, Valid};
use schemars::JsonSchema;
use serde::{de::Error as _, Deserialize, Deserializer, Serialize};

/// Largest number of units in one hidden layer, and of neurons in a CTRNN.
pub const MAX_UNITS: usize = 4096;

/// Largest number of hidden layers of an MLP.
pub const MAX_HIDDEN_LAYERS: usize = 16;

/// Largest number of Euler steps per world tick of a CTRNN.
pub const MAX_SUBSTEPS: usize = 1000;

/// Largest parameter count of a topology (2^22, 32 MiB per genome): the genetic algorithm keeps
/// whole populations of genomes in memory.
pub const MAX_PARAMETERS: usize = 1 << 22;

/// Default hidden layer sizes of `mlp` and `recurrent` brains.
pub const DEFAULT_HIDDEN: [usize; 1] = [16];
/// Default number of CTRNN neurons.
pub const DEFAULT_NEURONS: usize = 8;
/// Default CTRNN Euler step, in CTRNN time units.
pub const DEFAULT_STEP: f64 = 0.2;
/// Default number of CTRNN Euler steps per world tick (with the default step: one time unit
/// per tick).
pub const DEFAULT_SUBSTEPS: usize = 5;
/// Default CTRNN time constant range [τ_min, τ_max], in CTRNN time units.
pub const DEFAULT_TAU: [f64; 2] = [1.0, 10.0];
/// Default CTRNN gain range [g_min, g_max].
pub const DEFAULT_GAIN: [f64; 2] = [1.0, 5.0];

/// Which kind of network a brain is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum BrainKind {
    /// Feed-forward multilayer perceptron (the default).
    #[default]
    Mlp,
    /// Elman network: one hidden layer whose previous activations are extra inputs.
    Recurrent,
    /// Continuous-time recurrent neural network (Beer 1995), Euler-integrated.
    Ctrnn,
}

impl BrainKind {
    /// The name used in TOML (`"mlp"`, `"recurrent"`, `"ctrnn"`).
    pub fn name(self) -> &'static str {
        match self {
            BrainKind::Mlp => "mlp",
            BrainKind::Recurrent => "recurrent",
            BrainKind::Ctrnn => "ctrnn",
        }
    }
}

/// The float type an MLP computes in (`brain.precision`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Precision {
    /// Double precision throughout (the default).
    #[default]
    F64,
    /// Single precision sums: parameters and inputs rounded to f32, every sum in f32 with
    /// fused multiply-adds (one rounding per term), the activation functions in f64 on the
    /// widened sum, rounded back (see
    /// [`crate::brain::mlp`]). Opt-in, for comparisons with float32 peers such as EvoJAX: it
    /// changes results.
    F32,
}

impl Precision {
    /// The name used in TOML (`"f64"`, `"f32"`).
    pub fn name(self) -> &'static str {
        match self {
            Precision::F64 => "f64",
            Precision::F32 => "f32",
        }
    }
}

/// The `[brain]` table: which network turns a creature's observation into motor outputs.
///
/// Every field but `kind` is optional; a missing field takes the default of the chosen kind
/// (listed on each field). A field that does not apply to the chosen kind is an error.
/// The default table is an MLP with one hidden layer of 16 tanh units.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct BrainSpec {
    /// The network kind: `"mlp"`, `"recurrent"` or `"ctrnn"` (default: `"mlp"`).
    #[serde(default)]
    pub kind: BrainKind,
    /// mlp, recurrent: the number of units of each hidden layer, input side first
    /// (default: `[16]`). An mlp may have none (`[]`: inputs wired straight to the outputs)
    /// and at most 16; a recurrent network has exactly one. Each layer has 1 to 4096 units.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub hidden: Option<Vec<usize>>,
    /// mlp, recurrent: the activation function of hidden units, `"tanh"`, `"sigmoid"` or
    /// `"relu"` (default: `"tanh"`). Output units always use tanh, so outputs are in [-1, 1].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub activation: Option<Activation>,
    /// mlp: the float type of the forward pass, `"f64"` (default) or `"f32"` (sums in single
    /// precision with fused multiply-adds, as float32 frameworks compute; it changes results,
    /// so it is opt-in). Recurrent
    /// and ctrnn brains always compute in f64 and refuse `"f32"`. Left out of files when unset,
    /// so files written before the key existed still read the same.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub precision: Option<Precision>,
    /// ctrnn: the number of neurons N, fully connected, 1 to 4096 and at least the number of
    /// motor outputs (default: 8). Motors are read from neurons 0, 1 (and 2 for eating).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub neurons: Option<usize>,
    /// ctrnn: the Euler integration step dt, in CTRNN time units, > 0 and at most `tau[0]`
    /// so that dt/τ ≤ 1 for every neuron (default: 0.2).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub step: Option<f64>,
    /// ctrnn: the number of Euler steps per world tick, 1 to 1000; one tick lasts
    /// `step * substeps` time units (default: 5).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub substeps: Option<usize>,
    /// ctrnn: the range [τ_min, τ_max] of the neurons' time constants, in CTRNN time units,
    /// 0 < τ_min ≤ τ_max; genes map into it on a log scale (default: `[1.0, 10.0]`).
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "range"
    )]
    pub tau: Option<[f64; 2]>,
    /// ctrnn: the range [g_min, g_max] of the neurons' gains, 0 ≤ g_min ≤ g_max; genes map into
    /// it linearly (default: `[1.0, 5.0]`).
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "range"
    )]
    pub gain: Option<[f64; 2]>,
    /// mlp: whether the weights change during a life, `"none"` (default), `"hebbian"` or
    /// `"neuromodulated"`. After every tick each weight w changes by
    /// Δw = η·(A·pre·post + B·pre + C·post + D), times tanh(m/2) when neuromodulated (m: the
    /// tick's modulatory signal, see `modulators`), then is clamped to `weight_bounds`; the
    /// coefficients are evolved genes (see `granularity`), biases stay fixed, and the weights
    /// start each life afresh (`initial_weights`). Recurrent and ctrnn brains are not
    /// supported yet, nor `precision = "f32"`. Plastic brains run in lockstep with one brain
    /// per trial world (docs/learning.md, "Plastic brains").
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub plasticity: Option<Plasticity>,
    /// mlp with plasticity: how many sets of rule coefficients (η, A, B, C, D) evolve:
    /// `"network"` (one set, the default), `"layer"` (one per weight layer) or `"synapse"`
    /// (one per weight: 5 genes per weight).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub granularity: Option<Granularity>,
    /// mlp with plasticity: the range [w_min, w_max] every plastic weight is clamped to after
    /// each change, w_min < w_max (default: `[-4.0, 4.0]`).
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "range"
    )]
    pub weight_bounds: Option<[f64; 2]>,
    /// mlp with plasticity: where the weights start each life: `"evolved"` (the genome's
    /// weights, the default) or `"random"` (drawn anew for each life, uniform in [-1, 1] and
    /// clamped to `weight_bounds`, biases 0, from the life's own seed stream; the genome then
    /// holds only the rule's and the modulation's genes).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub initial_weights: Option<InitialWeights>,
    /// mlp with `plasticity = "neuromodulated"`: the signals summed, each with an evolved
    /// weight, into the modulatory signal m: `"food_a"` … `"food_d"` (the food detectors;
    /// need `creature.inputs.food`), `"shock"` (the shock sensor; needs
    /// `creature.inputs.shock`), `"metabolism_change"` (the change since the last tick of the
    /// metabolic vector's weighted sum, four genes; needs `creature.inputs.metabolism`) and
    /// `"neurons"` (evolved modulatory neurons on the last hidden layer, each adding its tanh
    /// activation). At least one for a neuromodulated rule, none twice (default: `[]`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub modulators: Option<Vec<Modulator>>,
    /// mlp with `modulators` naming `"neurons"`: how many modulatory neurons, 1 to 64
    /// (default: 1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub modulatory_neurons: Option<usize>,
}

/// Reads a `[min, max]` range. serde's own `[f64; 2]` lets the `toml` crate pass a longer
/// array (it reads two elements and ignores the rest), which would silently drop values.
fn range<'de, D: Deserializer<'de>>(deserializer: D) -> Result<Option<[f64; 2]>, D::Error> {
    let values = Vec::<f64>::deserialize(deserializer)?;
    match values[..] {
        [min, max] => Ok(Some([min, max])),
        _ => Err(D::Error::invalid_length(
            values.len(),
            &"an array of 2 numbers [min, max]",
        )),
    }
}

/// A CTRNN's settings with defaults filled in.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct CtrnnSettings {
    pub neurons: usize,
    pub step: f64,
    pub substeps: usize,
    pub tau: [f64; 2],
    pub gain: [f64; 2],
}

/// A spec with the kind's defaults filled in and inapplicable fields dropped.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Architecture {
    Mlp {
        hidden: Vec<usize>,
        activation: Activation,
        precision: Precision,
    },
    Recurrent {
        hidden: usize,
        activation: Activation,
    },
    Ctrnn(CtrnnSettings),
}

impl BrainSpec {
    /// Checks every value, with keys starting `brain.`: sizes within their limits, CTRNN
    /// ranges finite and ordered, and no field that the chosen `kind` does not use.
    pub fn validate(&self) -> Valid {
        let kind = self.kind;
        let uses_layers = matches!(kind, BrainKind::Mlp | BrainKind::Recurrent);
        let not_applicable = |field: &str, applies_to: &str| {
            InvalidValue::new(
                format!("brain.{field}"),
                format!(
                    "applies only to {applies_to}, but this brain is kind = \"{}\"; \
                     remove it (it would have no effect)",
                    kind.name()
                ),
            )
        };
        if !uses_layers {
            if self.hidden.is_some() {
                return Err(not_applicable(
                    "hidden",
                    "kind = \"mlp\" or \"recurrent\" (a ctrnn's size is `neurons`)",
                ));
            }
            if self.activation.is_some() {
                return Err(not_applicable(
                    "activation",
                    "kind = \"mlp\" or \"recurrent\" (ctrnn neurons use the logistic function)",
                ));
            }
        }
        if kind != BrainKind::Mlp && self.precision == Some(Precision::F32) {
            return Err(InvalidValue::new(
                "brain.precision",
                format!(
                    "\"f32\" applies only to kind = \"mlp\", but this brain is kind = \"{}\", \
                     which always computes in f64; remove it or set \"f64\"",
                    kind.name()
                ),
            ));
        }
        if kind != BrainKind::Ctrnn {
            let ctrnn_fields = [
                ("neurons", self.neurons.is_some()),
                ("step", self.step.is_some()),
                ("substeps", self.substeps.is_some()),
                ("tau", self.tau.is_some()),
                ("gain", self.gain.is_some()),
            ];
            if let Some((field, _)) = ctrnn_fields.iter().find(|(_, given)| *given) {
                return Err(not_applicable(field, "kind = \"ctrnn\""));
            }
        }
        self.validate_plasticity()?;

        match self.architecture() {
            Architecture::Mlp { hidden, .. } => validate_layers(&hidden, MAX_HIDDEN_LAYERS),
            Architecture::Recurrent { .. } => {
                let layers = self.hidden.as_deref().unwrap_or(&DEFAULT_HIDDEN);
                if layers.len() != 1 {
                    return Err(InvalidValue::new(
                        "brain.hidden",
                        format!(
                            "a recurrent (Elman) network has exactly one hidden layer, got {}",
                            layers.len()
                        ),
                    ));
                }
                validate_layers(layers, 1)
            }
            Architecture::Ctrnn(c) => {
                count_within(
                    "brain.neurons",
                    c.neurons as u64,
                    1,
                    MAX_UNITS as u64,
                    "per-tick cost grows with the square",
                )?;
                positive("brain.step", c.step)?;
                count_within(
                    "brain.substeps",
                    c.substeps as u64,
                    1,
                    MAX_SUBSTEPS as u64,
                    "per-tick cost",
                )?;
                positive("brain.tau[0]", c.tau[0])?;
                positive("brain.tau[1]", c.tau[1])?;
                if c.tau[1] < c.tau[0] {
                    return Err(InvalidValue::new(
                        "brain.tau",
                        format!(
                            "must be [min, max] with min <= max, got [{}, {}]",
                            c.tau[0], c.tau[1]
                        ),
                    ));
                }
                if c.step > c.tau[0] {
                    return Err(InvalidValue::new(
                        "brain.step",
                        format!(
                            "must not exceed the smallest time constant tau[0] = {}, got {} \
                             (Euler integration needs step/tau <= 1 to stay stable)",
                            c.tau[0], c.step
                        ),
                    ));
                }
                for (i, g) in c.gain.iter().enumerate() {
                    let key = format!("brain.gain[{i}]");
                    finite(&key, *g)?;
                    if *g < 0.0 {
                        return Err(InvalidValue::new(key, format!("must be >= 0, got {g}")));
                    }
                }
                if c.gain[1] < c.gain[0] {
                    return Err(InvalidValue::new(
                        "brain.gain",
                        format!(
                            "must be [min, max] with min <= max, got [{}, {}]",
                            c.gain[0], c.gain[1]
                        ),
                    ));
                }
                Ok(())
            }
        }
    }

    /// The plasticity keys: only on an f64 MLP, the settings' own keys only with a rule, and
    /// the settings valid (see [`PlasticSettings::validate`]).
    fn validate_plasticity(&self) -> Valid {
        let rule = self.plasticity.unwrap_or_default();
        if rule != Plasticity::None && self.kind != BrainKind::Mlp {
            return Err(InvalidValue::new(
                "brain.plasticity",
                format!(
                    "plastic weights are supported for kind = \"mlp\" only (recurrent and \
                     ctrnn brains are not supported yet), but this brain is kind = \"{}\"; \
                     remove it or use kind = \"mlp\"",
                    self.kind.name()
                ),
            ));
        }
        if rule != Plasticity::None && self.precision == Some(Precision::F32) {
            return Err(InvalidValue::new(
                "brain.plasticity",
                format!(
                    "\"{}\" needs precision = \"f64\" (the rule is computed in f64); remove \
                     `brain.precision = \"f32\"`",
                    rule.name()
                ),
            ));
        }
        let keys = [
            ("granularity", self.granularity.is_some()),
            ("weight_bounds", self.weight_bounds.is_some()),
            ("initial_weights", self.initial_weights.is_some()),
            ("modulators", self.modulators.is_some()),
            ("modulatory_neurons", self.modulatory_neurons.is_some()),
        ];
        match self.plastic_settings() {
            None => match keys.iter().find(|(_, given)| *given) {
                Some((key, _)) => Err(InvalidValue::new(
                    format!("brain.{key}"),
                    "applies only to a plastic brain: set `brain.plasticity = \"hebbian\"` \
                     or \"neuromodulated\", or remove it (it would have no effect)",
                )),
                None => Ok(()),
            },
            Some(settings) => settings.validate(self.modulatory_neurons.is_some()),
        }
    }

    /// The plasticity settings with defaults filled in, or `None` for fixed weights.
    pub fn plastic_settings(&self) -> Option<PlasticSettings> {
        let rule = self.plasticity.unwrap_or_default();
        if rule == Plasticity::None {
            return None;
        }
        let modulators = self.modulators.clone().unwrap_or_default();
        let neurons = if modulators.contains(&Modulator::Neurons) {
            self.modulatory_neurons
                .unwrap_or(DEFAULT_MODULATORY_NEURONS)
        } else {
            0
        };
        Some(PlasticSettings {
            rule,
            granularity: self.granularity.unwrap_or_default(),
            bounds: self.weight_bounds.unwrap_or(DEFAULT_WEIGHT_BOUNDS),
            initial: self.initial_weights.unwrap_or_default(),
            modulators,
            neurons,
        })
    }

    /// The spec with its kind's defaults filled in; fields that do not apply are dropped
    /// (they are reported by [`BrainSpec::validate`]).
    pub(crate) fn architecture(&self) -> Architecture {
        let activation = self.activation.unwrap_or_default();
        let hidden = self.hidden.as_deref().unwrap_or(&DEFAULT_HIDDEN);
        match self.kind {
            BrainKind::Mlp => Architecture::Mlp {
                hidden: hidden.to_vec(),
                activation,
                precision: self.precision.unwrap_or_default(),
            },
            BrainKind::Recurrent => Architecture::Recurrent {
                hidden: hidden.first().copied().unwrap_or(0),
                activation,
            },
            BrainKind::Ctrnn => Architecture::Ctrnn(CtrnnSettings {
                neurons: self.neurons.unwrap_or(DEFAULT_NEURONS),
                step: self.step.unwrap_or(DEFAULT_STEP),
                substeps: self.substeps.unwrap_or(DEFAULT_SUBSTEPS),
                tau: self.tau.unwrap_or(DEFAULT_TAU),
                gain: self.gain.unwrap_or(DEFAULT_GAIN),
            }),
        }
    }
}

fn validate_layers(layers: &[usize], max_layers: usize) -> Valid {
    count_within(
        "brain.hidden",
        layers.len() as u64,
        0,
        max_layers as u64,
        "hidden layers",
    )?;
    for (i, units) in layers.iter().enumerate() {
        count_within(
            &format!("brain.hidden[{i}]"),
            *units as u64,
            1,
            MAX_UNITS as u64,
            "units per layer",
        )?;
    }
    Ok(())
}

/// A brain's shape: the spec plus the number of inputs (the observation's length) and of
/// outputs (motor outputs, see [`crate::brain::output_count`]). It fixes how many parameters a
/// genome must carry and what each one means.
///
/// # Parameter layout
///
/// Matrices are row-major, one row per receiving unit, so that each unit's incoming weights are
/// contiguous. Names are those of [`Topology::parameter_names`].
///
/// - **mlp** with hidden sizes H_0, …, H_{L-1}, n inputs and m outputs: for each hidden layer
///   l in order, its weights `w_h{l}[j][i]` (into unit j from unit i of the layer before, or
///   input i for l = 0), then its biases `b_h{l}[j]`; then the output layer's `w_out[o][j]`
///   (from the last hidden layer, or from the inputs when there is none) and `b_out[o]`.
///   Count: Σ_l (H_{l-1} + 1) H_l + (H_{L-1} + 1) m, with H_{-1} = n.
/// - **recurrent** with H hidden units: for each hidden unit j, its input weights
///   `w_h[j][i]` (i < n) followed by its context weights `w_ctx[j][k]` (from hidden unit k's
///   previous activation, k < H); then `b_h[j]`; then `w_out[o][j]` and `b_out[o]`.
///   Count: H (n + H + 1) + m (H + 1).
/// - **ctrnn** with N neurons: the input weights `w_in[i][k]` (into neuron i from input k),
///   the connection weights `w[i][j]` (into neuron i from neuron j, self-connections
///   included), the biases `bias[i]` (θ), the time-constant genes `tau[i]` and the gain
///   genes `gain[i]` (mapped into their ranges, see [`crate::brain::ctrnn`]).
///   Count: N n + N² + 3 N.
/// - **plastic mlp** (`plasticity` not `"none"`, see [`crate::brain::plasticity`]): the mlp's
///   weights and biases as above (left out with `initial_weights = "random"`), then the rule's
///   coefficients: `rule_eta`, `rule_a`, `rule_b`, `rule_c`, `rule_d` (granularity
///   `"network"`); the same five suffixed `_h0`, …, `_out` for each weight layer in order
///   (`"layer"`); or, for each weight layer, five blocks `rule_eta_h0[j][i]`, `rule_a_h0[j][i]`,
///   … laid out like the layer's weights (`"synapse"`). Then one group per modulator in
///   `modulators` order: `mod_food_a` (one gene; likewise the other food types and
///   `mod_shock`), `mod_metabolism[k]` (four), or the modulatory neurons' weights
///   `w_mod[k][j]` (from the last hidden layer, or the inputs) followed by `b_mod[k]`.
#[derive(Debug, Clone, PartialEq)]
pub struct Topology {
    /// The `[brain]` table.
    pub spec: BrainSpec,
    /// Number of inputs, the observation's length.
    pub inputs: usize,
    /// Number of outputs, each in [-1, 1].
    pub outputs: usize,
    /// Where the signals a neuromodulated brain's `modulators` read sit in the observation
    /// ([`SignalInputs::from_layout`]; the default, none, suits every other brain).
    pub signals: SignalInputs,
}

impl Topology {
    /// A validated topology (see [`Topology::validate`]).
    pub fn new(spec: BrainSpec, inputs: usize, outputs: usize) -> Result<Topology, InvalidValue> {
        let topology = Topology {
            spec,
            inputs,
            outputs,
            signals: SignalInputs::default(),
        };
        topology.validate()?;
        Ok(topology)
    }

    /// The topology with the modulators' signals located in `signals` (see
    /// [`Topology::signals`]).
    pub fn with_signals(mut self, signals: SignalInputs) -> Topology {
        self.signals = signals;
        self
    }

    /// Validates the spec, then what depends on the inputs and outputs too: a CTRNN needs at
    /// least one neuron per output, every modulator has its signal, and no topology may
    /// exceed [`MAX_PARAMETERS`].
    pub fn validate(&self) -> Valid {
        self.spec.validate()?;
        self.check_signals()?;
        let architecture = self.spec.architecture();
        let key = match &architecture {
            Architecture::Ctrnn(c) => {
                if c.neurons < self.outputs {
                    return Err(InvalidValue::new(
                        "brain.neurons",
                        format!(
                            "must be at least the number of motor outputs ({}), which are read \
                             from the first neurons, got {}",
                            self.outputs, c.neurons
                        ),
                    ));
                }
                "brain.neurons"
            }
            _ => "brain.hidden",
        };
        let count = self.parameter_count();
        if count > MAX_PARAMETERS {
            return Err(InvalidValue::new(
                key,
                format!(
                    "gives {count} parameters with {} inputs and {} outputs, more than the \
                     limit of {MAX_PARAMETERS} (every genome of the population holds them all)",
                    self.inputs, self.outputs
                ),
            ));
        }
        Ok(())
    }

    /// Every modulator of a neuromodulated brain has its signal in the observation, or the
    /// error names `brain.modulators` and the sensor to switch on.
    pub fn check_signals(&self) -> Valid {
        match self.spec.plastic_settings() {
            Some(settings) => self.signals.check(&settings.modulators),
            None => Ok(()),
        }
    }

    /// An MLP's weight layers as (units, inputs), hidden layers then the output layer, and
    /// the width of the last hidden layer (or of the inputs): what plasticity genes count.
    pub(crate) fn weight_layers(&self) -> (Vec<(usize, usize)>, usize) {
        let mut sizes = Vec::new();
        let mut previous = self.inputs;
        if let Architecture::Mlp { hidden, .. } = self.spec.architecture() {
            for units in hidden {
                sizes.push((units, previous));
                previous = units;
            }
        }
        sizes.push((self.outputs, previous));
        (sizes, previous)
    }

    /// The number of parameters a genome for this topology carries (formulas in the type's
    /// docs). Saturates at `usize::MAX` instead of overflowing; meaningful for a topology that
    /// passes [`Topology::validate`].
    pub fn parameter_count(&self) -> usize {
        let (n, m) = (self.inputs, self.outputs);
        // (inputs + 1) * units: a layer's weights and biases.
        let layer = |inputs: usize, units: usize| inputs.saturating_add(1).saturating_mul(units);
        match self.spec.architecture() {
            Architecture::Mlp { hidden, .. } => {
                let mut total = 0usize;
                let mut previous = n;
                for units in hidden {
                    total = total.saturating_add(layer(previous, units));
                    previous = units;
                }
                total = total.saturating_add(layer(previous, m));
                match self.spec.plastic_settings() {
                    None => total,
                    Some(settings) => {
                        let (sizes, source) = self.weight_layers();
                        let genes = settings.gene_count(&sizes, source);
                        match settings.initial {
                            InitialWeights::Evolved => total.saturating_add(genes),
                            InitialWeights::Random => genes,
                        }
                    }
                }
            }
            Architecture::Recurrent { hidden: h, .. } => {
                layer(n.saturating_add(h), h).saturating_add(layer(h, m))
            }
            Architecture::Ctrnn(c) => {
                let k = c.neurons;
                k.saturating_mul(n)
                    .saturating_add(k.saturating_mul(k))
                    .saturating_add(k.saturating_mul(3))
            }
        }
    }

    /// The name of every parameter, in genome order (see the type's docs), e.g. `w_h0[3][5]`,
    /// `b_out[1]`, `tau[2]`. Has [`Topology::parameter_count`] entries.
    pub fn parameter_names(&self) -> Vec<String> {
        let (n, m) = (self.inputs, self.outputs);
        let mut names = Vec::with_capacity(self.parameter_count().min(MAX_PARAMETERS));
        let matrix = |names: &mut Vec<String>, w: &str, rows: usize, cols: usize| {
            for r in 0..rows {
                for c in 0..cols {
                    names.push(format!("{w}[{r}][{c}]"));
                }
            }
        };
        let vector = |names: &mut Vec<String>, b: &str, len: usize| {
            names.extend((0..len).map(|i| format!("{b}[{i}]")));
        };
        match self.spec.architecture() {
            Architecture::Mlp { hidden, .. } => {
                let settings = self.spec.plastic_settings();
                let random = settings
                    .as_ref()
                    .is_some_and(|s| s.initial == InitialWeights::Random);
                let mut previous = n;
                let mut layer_names = Vec::with_capacity(hidden.len() + 1);
                for (l, units) in hidden.iter().enumerate() {
                    if !random {
                        matrix(&mut names, &format!("w_h{l}"), *units, previous);
                        vector(&mut names, &format!("b_h{l}"), *units);
                    }
                    layer_names.push(format!("h{l}"));
                    previous = *units;
                }
                if !random {
                    matrix(&mut names, "w_out", m, previous);
                    vector(&mut names, "b_out", m);
                }
                layer_names.push("out".to_string());
                if let Some(settings) = settings {
                    let (sizes, source) = self.weight_layers();
                    settings.gene_names(&sizes, &layer_names, source, &mut names);
                }
            }
            Architecture::Recurrent { hidden: h, .. } => {
                for j in 0..h {
                    names.extend((0..n).map(|i| format!("w_h[{j}][{i}]")));
                    names.extend((0..h).map(|k| format!("w_ctx[{j}][{k}]")));
                }
                vector(&mut names, "b_h", h);
                matrix(&mut names, "w_out", m, h);
                vector(&mut names, "b_out", m);
            }
            Architecture::Ctrnn(c) => {
                let k = c.neurons;
                matrix(&mut names, "w_in", k, n);
                matrix(&mut names, "w", k, k);
                vector(&mut names, "bias", k);
                vector(&mut names, "tau", k);
                vector(&mut names, "gain", k);
            }
        }
        names
    }
}
