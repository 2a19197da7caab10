//! The bytes MPI ranks exchange: little-endian 64-bit words, every `f64` sent as its raw bits
//! (`to_bits`), so a number arrives with exactly the bits it left with (text would round), and
//! strings as a length and UTF-8 bytes. A [`Reader`] checks every length it is told.

use crate::brain::genome::Genome;
use crate::evo::evaluate::JobLives;
use crate::evo::fitness::MEASURE_COUNT;
use crate::evo::life::TrialOutcome;
use crate::experiment::evolution::MAX_DESCRIBED_AREAS;
use thiserror::Error;

/// A message that does not hold what its tag says.
#[derive(Debug, Error)]
#[error("a message of {len} bytes is malformed: {what}")]
pub struct WireError {
    /// The message's length.
    pub len: usize,
    /// What was wrong.
    pub what: String,
}

/// Builds a message.
#[derive(Default)]
pub struct Writer(Vec<u8>);

impl Writer {
    /// An empty message.
    pub fn new() -> Self {
        Writer(Vec::new())
    }

    /// Appends a word.
    pub fn u64(&mut self, x: u64) -> &mut Self {
        self.0.extend_from_slice(&x.to_le_bytes());
        self
    }

    /// Appends a float's raw bits.
    pub fn f64(&mut self, x: f64) -> &mut Self {
        self.u64(x.to_bits())
    }

    /// Appends a string (its length, then its bytes).
    pub fn text(&mut self, s: &str) -> &mut Self {
        self.u64(s.len() as u64);
        self.0.extend_from_slice(s.as_bytes());
        self
    }

    /// Appends genomes: their count, then per genome its parameter count, the parameters
    /// and the self-adaptive step size (a 0/1 flag and the value).
    pub fn genomes(&mut self, genomes: &[Genome]) -> &mut Self {
        self.u64(genomes.len() as u64);
        for g in genomes {
            self.u64(g.parameters.len() as u64);
            for &p in &g.parameters {
                self.f64(p);
            }
            self.u64(u64::from(g.step_size.is_some()));
            self.f64(g.step_size.unwrap_or(0.0));
        }
        self
    }

    /// Appends jobs' results: per job, per trial, per genome one outcome (the shapes are
    /// known to both sides, see [`Reader::lives`]).
    pub fn lives(&mut self, per_job: &[JobLives]) -> &mut Self {
        for outcome in per_job.iter().flatten().flatten() {
            self.f64(outcome.score);
            for &m in &outcome.metabolism {
                self.f64(m);
            }
            self.u64(outcome.shocked_ticks);
            self.u64(u64::from(outcome.non_finite));
            for &m in &outcome.measures {
                self.f64(m);
            }
            for &t in &outcome.area_ticks {
                self.f64(t);
            }
        }
        self
    }

    /// The message.
    pub fn finish(&mut self) -> Vec<u8> {
        std::mem::take(&mut self.0)
    }
}

/// Words of one [`TrialOutcome`] on the wire.
pub const OUTCOME_WORDS: usize = 7 + MEASURE_COUNT + MAX_DESCRIBED_AREAS;

/// Reads a message.
pub struct Reader<'a> {
    bytes: &'a [u8],
    at: usize,
}

impl<'a> Reader<'a> {
    /// Reads `bytes` from the start.
    pub fn new(bytes: &'a [u8]) -> Self {
        Reader { bytes, at: 0 }
    }

    fn error(&self, what: impl Into<String>) -> WireError {
        WireError {
            len: self.bytes.len(),
            what: what.into(),
        }
    }

    /// The next word.
    pub fn u64(&mut self) -> Result<u64, WireError> {
        let end = self.at + 8;
        let word = self
            .bytes
            .get(self.at..end)
            .ok_or_else(|| self.error(format!("it ends at byte {}", self.bytes.len())))?;
        self.at = end;
        Ok(u64::from_le_bytes(word.try_into().expect("8 bytes")))
    }

    /// The next float, from its raw bits.
    pub fn f64(&mut self) -> Result<f64, WireError> {
        self.u64().map(f64::from_bits)
    }

    /// The next count, which must fit what is left of the message (`size` bytes each).
    fn count(&mut self, size: usize) -> Result<usize, WireError> {
        let n = self.u64()?;
        let left = (self.bytes.len() - self.at) as u64;
        if n.saturating_mul(size as u64) > left {
            return Err(self.error(format!("a count of {n} exceeds what is left")));
        }
        Ok(n as usize)
    }

    /// The next string.
    pub fn text(&mut self) -> Result<String, WireError> {
        let n = self.count(1)?;
        let bytes = &self.bytes[self.at..self.at + n];
        self.at += n;
        String::from_utf8(bytes.to_vec()).map_err(|_| self.error("a string is not UTF-8"))
    }

    /// The next genomes (see [`Writer::genomes`]).
    pub fn genomes(&mut self) -> Result<Vec<Genome>, WireError> {
        let n = self.count(24)?;
        let mut genomes = Vec::with_capacity(n);
        for _ in 0..n {
            let len = self.count(8)?;
            let parameters = (0..len).map(|_| self.f64()).collect::<Result<_, _>>()?;
            let has_step = self.u64()? != 0;
            let step = self.f64()?;
            genomes.push(Genome {
                parameters,
                step_size: has_step.then_some(step),
            });
        }
        Ok(genomes)
    }

    /// The next jobs' results, `shapes[j]` = (trials, genomes per trial) of job j.
    pub fn lives(&mut self, shapes: &[(usize, usize)]) -> Result<Vec<JobLives>, WireError> {
        let outcomes: usize = shapes.iter().map(|(t, k)| t * k).sum();
        if outcomes * OUTCOME_WORDS * 8 > self.bytes.len() - self.at {
            return Err(self.error(format!("it holds fewer than {outcomes} outcomes")));
        }
        let mut per_job = Vec::with_capacity(shapes.len());
        for &(trials, k) in shapes {
            let mut job = Vec::with_capacity(trials);
            for _ in 0..trials {
                let mut lives = Vec::with_capacity(k);
                for _ in 0..k {
                    lives.push(self.outcome()?);
                }
                job.push(lives);
            }
            per_job.push(job);
        }
        Ok(per_job)
    }

    fn outcome(&mut self) -> Result<TrialOutcome, WireError> {
        let score = self.f64()?;
        let mut metabolism = [0.0; 4];
        for m in &mut metabolism {
            *m = self.f64()?;
        }
        let shocked_ticks = self.u64()?;
        let non_finite = self.u64()? != 0;
        let mut measures = [0.0; MEASURE_COUNT];
        for m in &mut measures {
            *m = self.f64()?;
        }
        let mut area_ticks = [0.0; MAX_DESCRIBED_AREAS];
        for t in &mut area_ticks {
            *t = self.f64()?;
        }
        Ok(TrialOutcome {
            score,
            metabolism,
            shocked_ticks,
            non_finite,
            measures,
            area_ticks,
        })
    }

    /// Checks that the whole message was read.
    pub fn end(&self) -> Result<(), WireError> {
        if self.at != self.bytes.len() {
            return Err(self.error(format!(
                "{} bytes are left over",
                self.bytes.len() - self.at
            )));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn genomes_and_lives_come_back_bit_for_bit() {
        let genomes = vec![
            Genome::new(vec![0.1, -0.0, f64::MIN_POSITIVE, 1e300, f64::from_bits(1)]),
            Genome {
                parameters: vec![],
                step_size: Some(0.3),
            },
        ];
        let outcome = TrialOutcome {
            score: 0.1 + 0.2,
            metabolism: [1.0 / 3.0, -0.0, 2.5e-310, 7.0],
            shocked_ticks: 42,
            non_finite: true,
            measures: [std::f64::consts::PI; MEASURE_COUNT],
            area_ticks: [0.5, 7.0, -0.0],
        };
        let lives: Vec<JobLives> = vec![vec![vec![outcome; 2]; 3], vec![vec![outcome; 2]]];
        let bytes = Writer::new().genomes(&genomes).lives(&lives).finish();
        let mut r = Reader::new(&bytes);
        let back = r.genomes().unwrap();
        let back_lives = r.lives(&[(3, 2), (1, 2)]).unwrap();
        r.end().unwrap();
        for (a, b) in genomes.iter().zip(&back) {
            let bits = |g: &Genome| g.parameters.iter().map(|p| p.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(a), bits(b));
            assert_eq!(a.step_size.map(f64::to_bits), b.step_size.map(f64::to_bits));
        }
        assert_eq!(back_lives, lives);
        assert_eq!(
            back_lives[0][0][0].metabolism[1].to_bits(),
            (-0.0f64).to_bits()
        );
    }

    #[test]
    fn a_short_or_long_message_is_refused() {
        let bytes = Writer::new().text("hello").finish();
        assert!(Reader::new(&bytes[..bytes.len() - 1]).text().is_err());
        let mut long = bytes.clone();
        long.push(0);
        let mut r = Reader::new(&long);
        r.text().unwrap();
        assert!(r.end().is_err());
        // A count larger than the message cannot make the reader allocate it.
        let huge = Writer::new().u64(u64::MAX).finish();
        assert!(Reader::new(&huge).genomes().is_err());
    }
}
