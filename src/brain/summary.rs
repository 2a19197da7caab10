//! A brain's shape in plain words and numbers ([`BrainSummary`]): what `inspect` prints, e.g.
//! "MLP 24 → 16 → 2, tanh hidden units, tanh outputs, f64 sums, 466 parameters", instead of
//! the `[brain]` table with its unset options.

use super::spec::{Architecture, Topology};
use serde::Serialize;
use std::fmt;

/// The shape of a topology with every default filled in; the fields that do not apply to
/// its kind are `None` (left out of JSON).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BrainSummary {
    /// `"mlp"`, `"recurrent"` or `"ctrnn"`.
    pub kind: &'static str,
    /// Inputs (the observation's length).
    pub inputs: usize,
    /// mlp, recurrent: units of each hidden layer, input side first.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub hidden: Option<Vec<usize>>,
    /// Outputs (motor commands, each in [-1, 1]).
    pub outputs: usize,
    /// mlp, recurrent: the hidden units' activation function.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub activation: Option<&'static str>,
    /// mlp: the float type of its sums, `"f64"` or `"f32"`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub precision: Option<&'static str>,
    /// ctrnn: fully connected neurons.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub neurons: Option<usize>,
    /// ctrnn: the Euler step, in CTRNN time units.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub step: Option<f64>,
    /// ctrnn: Euler steps per world tick.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub substeps: Option<usize>,
    /// ctrnn: the time constants' range [min, max], in CTRNN time units.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tau: Option<[f64; 2]>,
    /// ctrnn: the gains' range [min, max].
    #[serde(skip_serializing_if = "Option::is_none")]
    pub gain: Option<[f64; 2]>,
    /// mlp with `plasticity`: the rule and the genome's share of it in words, e.g.
    /// "neuromodulated plasticity per synapse, weights within [-4, 4] starting from the
    /// genome's, modulated by food_a, shock: 2080 rule genes, 2 modulation genes".
    #[serde(skip_serializing_if = "Option::is_none")]
    pub plasticity: Option<String>,
    /// Parameters a genome carries.
    pub parameters: usize,
}

impl Topology {
    /// This topology's shape (see [`BrainSummary`]).
    pub fn summary(&self) -> BrainSummary {
        let mut s = BrainSummary {
            kind: self.spec.kind.name(),
            inputs: self.inputs,
            hidden: None,
            outputs: self.outputs,
            activation: None,
            precision: None,
            neurons: None,
            step: None,
            substeps: None,
            tau: None,
            gain: None,
            plasticity: None,
            parameters: self.parameter_count(),
        };
        if let Some(p) = self.spec.plastic_settings() {
            let (sizes, source) = self.weight_layers();
            let rule = p.rule_genes(&sizes);
            let modulation = p.gene_count(&sizes, source) - rule;
            let start = match p.initial {
                super::plasticity::InitialWeights::Evolved => "starting from the genome's",
                super::plasticity::InitialWeights::Random => {
                    "drawn anew each life (not in the genome)"
                }
            };
            let modulators: Vec<&str> = p.modulators.iter().map(|m| m.name()).collect();
            let modulated = if modulators.is_empty() {
                String::new()
            } else {
                format!(", modulated by {}", modulators.join(", "))
            };
            s.plasticity = Some(format!(
                "{} plasticity per {}, weights within [{}, {}] {start}{modulated}: {rule} rule \
                 genes, {modulation} modulation genes",
                p.rule.name(),
                p.granularity.name(),
                p.bounds[0],
                p.bounds[1],
            ));
        }
        match self.spec.architecture() {
            Architecture::Mlp {
                hidden,
                activation,
                precision,
            } => {
                s.hidden = Some(hidden);
                s.activation = Some(activation.name());
                s.precision = Some(precision.name());
            }
            Architecture::Recurrent { hidden, activation } => {
                s.hidden = Some(vec![hidden]);
                s.activation = Some(activation.name());
            }
            Architecture::Ctrnn(c) => {
                s.neurons = Some(c.neurons);
                s.step = Some(c.step);
                s.substeps = Some(c.substeps);
                s.tau = Some(c.tau);
                s.gain = Some(c.gain);
            }
        }
        s
    }
}

impl fmt::Display for BrainSummary {
    /// One line: the kind, the layer sizes, the functions and the parameter count.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let hidden = self.hidden.as_deref().unwrap_or(&[]);
        let chain = |f: &mut fmt::Formatter<'_>| -> fmt::Result {
            write!(f, "{}", self.inputs)?;
            for h in hidden {
                write!(f, " → {h}")?;
            }
            write!(f, " → {}", self.outputs)
        };
        let units = |f: &mut fmt::Formatter<'_>| -> fmt::Result {
            match self.activation {
                Some(a) if !hidden.is_empty() => write!(f, ", {a} hidden units, tanh outputs"),
                _ => write!(f, ", tanh outputs"),
            }
        };
        match self.kind {
            "mlp" => {
                write!(f, "MLP ")?;
                chain(f)?;
                if hidden.is_empty() {
                    write!(f, " (no hidden layer)")?;
                }
                units(f)?;
                if let Some(p) = self.precision {
                    write!(f, ", {p} sums")?;
                }
            }
            "recurrent" => {
                write!(f, "Elman recurrent network ")?;
                chain(f)?;
                write!(
                    f,
                    " (the hidden layer also sees its own previous activations)"
                )?;
                units(f)?;
            }
            _ => {
                write!(
                    f,
                    "CTRNN of {} fully connected neurons, {} inputs, {} outputs read from \
                     the first neurons",
                    self.neurons.unwrap_or(0),
                    self.inputs,
                    self.outputs
                )?;
                if let (Some(step), Some(substeps)) = (self.step, self.substeps) {
                    write!(f, ", Euler step {step} × {substeps} per tick")?;
                }
                if let (Some([t0, t1]), Some([g0, g1])) = (self.tau, self.gain) {
                    write!(f, ", time constants {t0} to {t1}, gains {g0} to {g1}")?;
                }
            }
        }
        if let Some(p) = &self.plasticity {
            write!(f, ", {p}")?;
        }
        write!(f, ", {} parameters", self.parameters)
    }
}

#[cfg(test)]
mod tests {
    use crate::brain::spec::{BrainKind, BrainSpec, Topology};

    fn line(spec: BrainSpec, inputs: usize, outputs: usize) -> String {
        Topology::new(spec, inputs, outputs)
            .unwrap()
            .summary()
            .to_string()
    }

    #[test]
    fn brains_in_plain_words() {
        assert_eq!(
            line(BrainSpec::default(), 24, 2),
            "MLP 24 → 16 → 2, tanh hidden units, tanh outputs, f64 sums, 434 parameters"
        );
        let direct = BrainSpec {
            hidden: Some(vec![]),
            ..BrainSpec::default()
        };
        assert_eq!(
            line(direct, 24, 2),
            "MLP 24 → 2 (no hidden layer), tanh outputs, f64 sums, 50 parameters"
        );
        let elman = BrainSpec {
            kind: BrainKind::Recurrent,
            hidden: Some(vec![4]),
            ..BrainSpec::default()
        };
        assert_eq!(
            line(elman, 3, 2),
            "Elman recurrent network 3 → 4 → 2 (the hidden layer also sees its own previous \
             activations), tanh hidden units, tanh outputs, 42 parameters"
        );
        let ctrnn = BrainSpec {
            kind: BrainKind::Ctrnn,
            ..BrainSpec::default()
        };
        let plastic = BrainSpec {
            plasticity: Some(crate::brain::Plasticity::Hebbian),
            granularity: Some(crate::brain::plasticity::Granularity::Layer),
            ..BrainSpec::default()
        };
        assert_eq!(
            line(plastic, 24, 2),
            "MLP 24 → 16 → 2, tanh hidden units, tanh outputs, f64 sums, hebbian plasticity \
             per layer, weights within [-4, 4] starting from the genome's: 10 rule genes, 0 \
             modulation genes, 444 parameters"
        );
        assert_eq!(
            line(ctrnn, 24, 2),
            "CTRNN of 8 fully connected neurons, 24 inputs, 2 outputs read from the first \
             neurons, Euler step 0.2 × 5 per tick, time constants 1 to 10, gains 1 to 5, \
             280 parameters"
        );
    }
}
