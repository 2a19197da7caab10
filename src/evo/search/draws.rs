//! Many normal draws at once, in parallel, with the bits of drawing them one after another.
//!
//! A search's generation can need millions of [`gaussian`] draws (one per gene per
//! individual), and drawn one after another from one stream they were 6–17% of a generation
//! at 15,000 parameters. Every `gaussian` uses exactly two 64-bit words of its ChaCha stream,
//! so the k-th of a run of draws starts at a known word: chunks of the run are drawn on
//! rayon's threads from copies of the stream moved there (`set_word_pos`), each chunk in
//! order, and the results land by index. The values therefore do not depend on the number of
//! threads, and the stream is left where drawing them one by one would leave it.
//!
//! Where the number of words is not known in advance (the GA's variation: a mutated gene
//! takes two more words than one that is not), [`Words`] reads the stream's words from a
//! buffer that is filled ahead, batch by batch, in parallel in the same way: the words, and
//! so every draw made from them, are the stream's own.
//!
//! Draw order 2's ziggurat normals take a varying number of words, so there each individual
//! draws from its own stream instead ([`own_stream`]), and individuals are drawn in parallel.

use crate::seed::{gaussian, gaussian_ziggurat, Normals, Rng};
use rand_chacha::rand_core::{impls, Error, RngCore};
use rayon::prelude::*;
use std::cell::Cell;
use std::sync::{Arc, Mutex};

/// The stream's 32-bit words one [`gaussian`] uses: two `next_u64`.
const WORDS_PER_GAUSSIAN: u128 = 4;

/// Draws per parallel task: large enough that moving a stream copy (one ChaCha block) is
/// negligible, small enough that 15,000 genes spread over the threads.
const CHUNK: usize = 1024;

/// Fills `out` with normal draws from `rng`, exactly as `for x in out { *x = gaussian(rng) }`
/// would, and leaves `rng` where that loop would.
pub fn fill_gaussians(rng: &mut Rng, out: &mut [f64]) {
    let start = rng.get_word_pos();
    fill_gaussians_at(rng, start, out);
    rng.set_word_pos(start + WORDS_PER_GAUSSIAN * out.len() as u128);
}

/// `count` normal draws from `rng`, as [`fill_gaussians`].
pub fn gaussians(rng: &mut Rng, count: usize) -> Vec<f64> {
    let mut out = vec![0.0; count];
    fill_gaussians(rng, &mut out);
    out
}

/// Moves `rng` past the `count` normal draws it would make next and returns the 32-bit word
/// they start at, so that a caller can hand them out to be drawn later, in parallel, with
/// [`gaussians_from`] (the draws after them then come from the same words as before).
pub fn skip_gaussians(rng: &mut Rng, count: usize) -> u128 {
    let start = rng.get_word_pos();
    rng.set_word_pos(start + WORDS_PER_GAUSSIAN * count as u128);
    start
}

/// The `count` normal draws of `base`'s stream from 32-bit word `start` on (a position
/// [`skip_gaussians`] gave); `base` itself does not move.
pub fn gaussians_from(base: &Rng, start: u128, count: usize) -> Vec<f64> {
    let mut out = vec![0.0; count];
    fill_gaussians_at(base, start, &mut out);
    out
}

/// The `rows` vectors of `columns` normal draws each, as `normals` says:
///
/// - Box–Muller (draw order 1): what `rows` times `columns` calls of [`gaussian`] on `rng`
///   make, vector after vector (each vector itself drawn in parallel when long); `rng` is
///   left where those calls would leave it.
/// - the ziggurat (draw order 2): vector k from its own stream ([`own_gaussians`]), the
///   vectors in parallel; `rng` does not move.
pub fn gaussian_rows(
    normals: Normals,
    rng: &mut Rng,
    rows: usize,
    columns: usize,
) -> Vec<Vec<f64>> {
    if normals == Normals::Ziggurat {
        let base: &Rng = rng;
        return (0..rows)
            .into_par_iter()
            .map(|k| own_gaussians(base, k, columns))
            .collect();
    }
    let start = rng.get_word_pos();
    let base: &Rng = rng;
    let out = (0..rows)
        .into_par_iter()
        .map(|k| {
            let mut row = vec![0.0; columns];
            let at = start + WORDS_PER_GAUSSIAN * (k as u128) * (columns as u128);
            fill_gaussians_at(base, at, &mut row);
            row
        })
        .collect();
    rng.set_word_pos(start + WORDS_PER_GAUSSIAN * (rows as u128) * (columns as u128));
    out
}

/// Individual k's own stream in draw order 2: `base`'s key with ChaCha stream number k + 1,
/// from its first word (stream 0 is the generation's own, as [`crate::seed::stream`] makes
/// it). Each individual's draws then depend on nothing else, so individuals are drawn in
/// parallel with the same bits on any number of threads.
pub fn own_stream(base: &Rng, k: usize) -> Rng {
    let mut own = base.clone();
    own.set_stream(1 + k as u64);
    own.set_word_pos(0);
    own
}

/// `count` ziggurat normals from individual k's own stream ([`own_stream`]), in order.
pub fn own_gaussians(base: &Rng, k: usize, count: usize) -> Vec<f64> {
    let mut own = own_stream(base, k);
    (0..count).map(|_| gaussian_ziggurat(&mut own)).collect()
}

/// Fills `out` with the normal draws of `base`'s stream starting at 32-bit word `start`,
/// chunk by chunk in parallel (`base` itself does not move).
fn fill_gaussians_at(base: &Rng, start: u128, out: &mut [f64]) {
    out.par_chunks_mut(CHUNK)
        .enumerate()
        .for_each(|(k, chunk)| {
            let mut rng = base.clone();
            rng.set_word_pos(start + WORDS_PER_GAUSSIAN * (k * CHUNK) as u128);
            for x in chunk {
                *x = gaussian(&mut rng);
            }
        });
}

/// What a generation's noises are drawn for: the generation, the number of vectors, and any
/// values they are scaled by (PGPE's standard deviations, as bits; empty for CMA-ES).
pub type NoiseKey = (u64, usize, Vec<u64>);

/// The noises `ask` drew, kept for `tell`, which needs the same ones and would otherwise
/// draw them again (the draws are most of PGPE's and CMA-ES's cost). Looked up by their
/// [`NoiseKey`], so a state changed in between (a restore) draws afresh.
#[derive(Debug, Default)]
pub struct NoiseCache(Mutex<Kept>);

/// The noises a [`NoiseCache`] keeps, with what they were drawn for.
type Kept = Option<(NoiseKey, Arc<Vec<Vec<f64>>>)>;

impl Clone for NoiseCache {
    fn clone(&self) -> Self {
        NoiseCache(Mutex::new(self.lock().clone()))
    }
}

impl NoiseCache {
    fn lock(&self) -> std::sync::MutexGuard<'_, Kept> {
        // A panic elsewhere cannot leave a half-written entry: the entry is replaced whole.
        self.0
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner())
    }

    /// The noises for `key`: the kept ones if they are for `key`, or `draw()`'s, then kept.
    pub fn get_or_draw(
        &self,
        key: NoiseKey,
        draw: impl FnOnce() -> Vec<Vec<f64>>,
    ) -> Arc<Vec<Vec<f64>>> {
        if let Some((kept, noises)) = self.lock().as_ref() {
            if *kept == key {
                return Arc::clone(noises);
            }
        }
        let noises = Arc::new(draw());
        *self.lock() = Some((key, Arc::clone(&noises)));
        noises
    }

    /// The noises for `key` (kept, or drawn), forgetting them: `tell` uses them last.
    pub fn take_or_draw(
        &self,
        key: NoiseKey,
        draw: impl FnOnce() -> Vec<Vec<f64>>,
    ) -> Arc<Vec<Vec<f64>>> {
        match self.lock().take() {
            Some((kept, noises)) if kept == key => noises,
            _ => Arc::new(draw()),
        }
    }
}

/// 32-bit words per batch of [`Words`] (at least, and at most: 16 MB), and per parallel task
/// of a batch.
const BATCH: usize = 1 << 16;
const MAX_BATCH: usize = 1 << 22;
const BATCH_CHUNK: usize = 1 << 13;

/// A generator that gives exactly the words of a ChaCha stream from a given position, read
/// from a buffer filled ahead in parallel (see the module documentation). Draw from it with
/// the samplers of [`crate::seed`] as from the stream itself; [`Words::position`] says where
/// the stream would be, to hand the drawing back with `set_word_pos`.
pub struct Words {
    /// The stream (its own position is irrelevant: copies are moved).
    base: Rng,
    /// The stream position, in 32-bit words, of `buffer[0]`.
    start: u128,
    /// The words, valid up to `end` (the rest is room kept from an earlier fill).
    buffer: Vec<u32>,
    end: usize,
    /// The next word to give, as an index into `buffer`.
    next: usize,
    /// The stream position, in 32-bit words, that the expected use was counted from.
    origin: u128,
    /// About how many words will be used from `origin` on: a refill draws what is left of
    /// them (within limits), so that a large use takes few large batches, hence few waits
    /// for the threads.
    expected: usize,
}

impl Words {
    /// The words of `rng`'s stream from where `rng` stands (`rng` does not move).
    pub fn new(rng: &Rng) -> Words {
        Words::expecting(rng, BATCH)
    }

    /// [`Words::new`] for a use of about `expected` 32-bit words: each batch holds what is
    /// left of them (within limits).
    pub fn expecting(rng: &Rng, expected: usize) -> Words {
        Words {
            base: rng.clone(),
            start: rng.get_word_pos(),
            // The last Words' room on this thread, if any: a fresh 16 MB each generation was
            // paid in page faults and zeroing.
            buffer: SPARE.take(),
            end: 0,
            next: 0,
            origin: rng.get_word_pos(),
            expected,
        }
    }

    /// The buffered words from the next one to give on, at least `min` of them (refilling
    /// when fewer are left): hot loops read them in place and then say how many they used
    /// with [`Words::advance`], which is exactly as drawing them one by one.
    #[inline]
    pub fn window(&mut self, min: usize) -> &[u32] {
        if self.end - self.next < min {
            self.refill(min);
        }
        &self.buffer[self.next..self.end]
    }

    /// Marks the next `used` words of [`Words::window`] as given.
    #[inline]
    pub fn advance(&mut self, used: usize) {
        debug_assert!(self.next + used <= self.end);
        self.next += used;
    }

    /// Where the stream would stand after the words given so far, in 32-bit words.
    pub fn position(&self) -> u128 {
        self.start + self.next as u128
    }

    /// Continues from stream position `position` (at or after [`Words::position`], where
    /// another generator on the same stream left off), keeping the buffer when it holds it.
    pub fn seek(&mut self, position: u128) {
        let end = self.start + self.end as u128;
        if position >= self.start && position <= end {
            self.next = (position - self.start) as usize;
        } else {
            self.start = position;
            self.end = 0;
            self.next = 0;
        }
    }

    /// Fills the buffer with the next batch of the stream's words from the current position,
    /// at least `min` of them.
    fn refill(&mut self, min: usize) {
        let position = self.position();
        self.start = position;
        self.next = 0;
        let used = usize::try_from(position.saturating_sub(self.origin)).unwrap_or(usize::MAX);
        let left = self.expected.saturating_sub(used);
        self.end = left.clamp(BATCH, MAX_BATCH).max(min);
        if self.buffer.len() < self.end {
            self.buffer.resize(self.end, 0);
        }
        let base = &self.base;
        self.buffer[..self.end]
            .par_chunks_mut(BATCH_CHUNK)
            .enumerate()
            .for_each(|(k, chunk)| {
                let mut rng = base.clone();
                rng.set_word_pos(position + (k * BATCH_CHUNK) as u128);
                // ChaCha's bytes are its words in little-endian order, word after word, so
                // filling bytes gives the words `next_u32` would, without a call per word.
                let mut bytes = [0u8; 4 * FILL];
                for part in chunk.chunks_mut(FILL) {
                    let bytes = &mut bytes[..4 * part.len()];
                    rng.fill_bytes(bytes);
                    for (w, b) in part.iter_mut().zip(bytes.chunks_exact(4)) {
                        *w = u32::from_le_bytes([b[0], b[1], b[2], b[3]]);
                    }
                }
            });
    }
}

/// 32-bit words a refill task converts from bytes at a time.
const FILL: usize = 1024;

thread_local! {
    /// The buffer of the last [`Words`] dropped on this thread, for the next to fill again.
    static SPARE: Cell<Vec<u32>> = const { Cell::new(Vec::new()) };
}

impl Drop for Words {
    fn drop(&mut self) {
        SPARE.set(std::mem::take(&mut self.buffer));
    }
}

impl RngCore for Words {
    fn next_u32(&mut self) -> u32 {
        if self.next >= self.end {
            self.refill(1);
        }
        let w = self.buffer[self.next];
        self.next += 1;
        w
    }

    #[inline]
    fn next_u64(&mut self) -> u64 {
        // As ChaCha's own next_u64: the lower word first.
        if self.next + 2 <= self.end {
            let lo = u64::from(self.buffer[self.next]);
            let hi = u64::from(self.buffer[self.next + 1]);
            self.next += 2;
            return (hi << 32) | lo;
        }
        let lo = u64::from(self.next_u32());
        let hi = u64::from(self.next_u32());
        (hi << 32) | lo
    }

    fn fill_bytes(&mut self, dest: &mut [u8]) {
        impls::fill_bytes_via_next(self, dest)
    }

    fn try_fill_bytes(&mut self, dest: &mut [u8]) -> Result<(), Error> {
        self.fill_bytes(dest);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::seed::{stream, unit, Generation, IndividualId, Purpose, Seed, TrialIndex};

    fn rng() -> Rng {
        stream(
            Seed(5),
            Purpose::Search,
            Generation(3),
            IndividualId(0),
            TrialIndex(0),
        )
    }

    #[test]
    fn parallel_draws_are_the_sequential_ones_and_leave_the_stream_in_place() {
        // Odd lengths and a start inside a ChaCha block (after one `unit`).
        for count in [0, 1, 7, CHUNK - 1, CHUNK, 3 * CHUNK + 5] {
            let mut one = rng();
            let mut many = rng();
            unit(&mut one);
            unit(&mut many);
            let expected: Vec<u64> = (0..count).map(|_| gaussian(&mut one).to_bits()).collect();
            let got: Vec<u64> = gaussians(&mut many, count)
                .iter()
                .map(|x| x.to_bits())
                .collect();
            assert_eq!(got, expected, "{count} draws");
            assert_eq!(unit(&mut many).to_bits(), unit(&mut one).to_bits());
        }
    }

    #[test]
    fn rows_are_the_sequential_draws_vector_after_vector() {
        for (rows, columns) in [(0, 5), (3, 0), (4, 3), (3, CHUNK + 17)] {
            let mut one = rng();
            let mut many = rng();
            let expected: Vec<Vec<u64>> = (0..rows)
                .map(|_| (0..columns).map(|_| gaussian(&mut one).to_bits()).collect())
                .collect();
            let got: Vec<Vec<u64>> = gaussian_rows(Normals::BoxMuller, &mut many, rows, columns)
                .iter()
                .map(|r| r.iter().map(|x| x.to_bits()).collect())
                .collect();
            assert_eq!(got, expected, "{rows} x {columns}");
            assert_eq!(unit(&mut many).to_bits(), unit(&mut one).to_bits());
        }
    }

    #[test]
    fn ziggurat_rows_come_from_each_rows_own_stream_on_any_thread_count() {
        let (rows, columns) = (5, 2 * CHUNK + 3);
        let expected: Vec<Vec<u64>> = (0..rows)
            .map(|k| {
                let mut own = rng();
                own.set_stream(1 + k as u64);
                own.set_word_pos(0);
                (0..columns)
                    .map(|_| gaussian_ziggurat(&mut own).to_bits())
                    .collect()
            })
            .collect();
        for threads in [1, 3] {
            let mut r = rng();
            let got = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap()
                .install(|| gaussian_rows(Normals::Ziggurat, &mut r, rows, columns));
            let got: Vec<Vec<u64>> = got
                .iter()
                .map(|r| r.iter().map(|x| x.to_bits()).collect())
                .collect();
            assert_eq!(got, expected, "{threads} threads");
            assert_eq!(r.get_word_pos(), 0, "the generation's stream is not used");
        }
        // Another row's stream is another stream.
        assert_ne!(expected[0], expected[1]);
    }

    #[test]
    fn words_are_the_stream_words_across_batches_and_seeks() {
        let mut one = rng();
        let mut words = Words::new(&one);
        // Odd word counts (next_u32) so that a u64 straddles a batch boundary.
        for step in 0..(3 * BATCH / 2) {
            if step % 1000 == 7 {
                assert_eq!(words.next_u32(), one.next_u32(), "step {step}");
            }
            assert_eq!(words.next_u64(), one.next_u64(), "step {step}");
            assert_eq!(words.position(), one.get_word_pos());
        }
        // Another generator draws a few words; the buffer continues after them.
        one.set_word_pos(words.position());
        unit(&mut one);
        words.seek(one.get_word_pos());
        assert_eq!(words.next_u64(), one.next_u64());
        // A jump past the buffer starts a new one.
        one.set_word_pos(words.position() + 10 * BATCH as u128 + 1);
        words.seek(one.get_word_pos());
        assert_eq!(words.next_u64(), one.next_u64());
        let mut bytes = [0u8; 13];
        let mut expected = [0u8; 13];
        words.fill_bytes(&mut bytes);
        impls::fill_bytes_via_next(&mut one, &mut expected);
        assert_eq!(bytes, expected);
    }

    #[test]
    fn the_thread_count_changes_nothing() {
        let draw = |threads| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap()
                .install(|| gaussians(&mut rng(), 5 * CHUNK + 3))
        };
        let one: Vec<u64> = draw(1).iter().map(|x| x.to_bits()).collect();
        let three: Vec<u64> = draw(3).iter().map(|x| x.to_bits()).collect();
        assert_eq!(one, three);
    }
}
