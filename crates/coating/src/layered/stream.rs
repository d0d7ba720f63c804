//! The random numbers of one walk: successive dimensions of one sample of an Owen-scrambled
//! Sobol sequence (B. Burley, "Practical hash-based Owen scrambling", JCGT 9(4), 2020, by the
//! `sobol_burley` crate, as the renderer's samples), walk `k` of an estimate taking sample `k`
//! of a sequence seeded by the estimate's stream. The walks of one estimate are then
//! stratified against each other in their first dimensions (the directions in through the
//! top, the first visit of the flake layer), where a pseudo-random stream would let them
//! cluster; past them the sequence is as good as independent numbers. Sequences hold 2¹⁶
//! samples; walks beyond take fresh seeds, 2¹⁶ at a time.

use glam::DVec2;

/// 32-bit finaliser of MurmurHash3 (Appleby), as the renderer mixes its seeds.
fn mix32(mut x: u32) -> u32 {
    x ^= x >> 16;
    x = x.wrapping_mul(0x85eb_ca6b);
    x ^= x >> 13;
    x = x.wrapping_mul(0xc2b2_ae35);
    x ^ (x >> 16)
}

/// One walk's stream.
pub(super) struct Stream {
    index: u32,
    seed: u32,
    dim: u32,
    four: [f32; 4],
}

impl Stream {
    /// The stream of walk `walk` of the estimate seeded `seed`.
    pub(super) fn new(walk: usize, seed: u64) -> Self {
        let block = (walk >> 16) as u64;
        let s = seed ^ block.wrapping_mul(0x9e37_79b9_7f4a_7c15);
        Stream {
            index: (walk & 0xffff) as u32,
            seed: mix32((s as u32) ^ mix32((s >> 32) as u32)),
            dim: 0,
            four: [0.0; 4],
        }
    }

    /// The next number, in [0, 1). Four dimensions are computed at once (the crate's
    /// `sample_4d`, the same values as one at a time); past the crate's 256 dimensions the
    /// sequence goes on with fresh seeds.
    pub(super) fn next(&mut self) -> f64 {
        let d = self.dim;
        self.dim += 1;
        if d.is_multiple_of(4) {
            let set = d / 4;
            let sets = sobol_burley::NUM_DIMENSION_SETS_4D;
            let seed = if set < sets {
                self.seed
            } else {
                mix32(self.seed ^ mix32(set / sets))
            };
            self.four = sobol_burley::sample_4d(self.index, set % sets, seed);
        }
        f64::from(self.four[(d % 4) as usize])
    }

    /// The next two numbers.
    pub(super) fn next2(&mut self) -> DVec2 {
        DVec2::new(self.next(), self.next())
    }
}
