//! Runs split into batches: a run's samples (the light model's photons, a render's samples
//! per pixel) cut into `N` contiguous parts that run apart — other processes, a cluster's
//! job array, Dask workers — and whose fixed-point sums, added in any order, give the whole
//! run's bit for bit. What a merge checks of the parts is shared here: one scene, one
//! set of settings, one split, every batch once and whole.

use std::ops::Range;

/// One of `count` equal parts of a run's samples (`index` from 0).
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct Batch {
    /// Which part, from 0.
    pub index: u32,
    /// Parts in all.
    pub count: u32,
}

/// A batch that is not one of its count.
#[derive(Clone, Copy, Debug, thiserror::Error, PartialEq, Eq)]
#[error("batch {0} does not exist (batches are 0/N to N-1/N, N at least 1)")]
pub struct NoSuchBatch(pub Batch);

impl Batch {
    /// The samples of this batch of a run of `total` (sample indices
    /// `index·total/count .. (index + 1)·total/count`; the batches of a split cover
    /// `0..total` once). Refused when `index` is not below `count`.
    pub fn share(self, total: u64) -> Result<Range<u64>, NoSuchBatch> {
        if self.index >= self.count {
            return Err(NoSuchBatch(self));
        }
        let at = |k: u32| (u128::from(total) * u128::from(k) / u128::from(self.count)) as u64;
        Ok(at(self.index)..at(self.index + 1))
    }
}

impl std::str::FromStr for Batch {
    type Err = String;

    /// `I/N`: batch I (from 0) of N.
    fn from_str(text: &str) -> Result<Self, String> {
        let parsed = text
            .split_once('/')
            .and_then(|(i, n)| Some((i.trim().parse().ok()?, n.trim().parse().ok()?)));
        match parsed {
            Some((index, count)) if index < count => Ok(Batch { index, count }),
            _ => Err(format!(
                "'{text}' is not a batch I/N (I from 0 to N-1, e.g. 0/4 … 3/4)"
            )),
        }
    }
}

impl std::fmt::Display for Batch {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

/// Why batches cannot be merged.
#[derive(Clone, Debug, thiserror::Error, PartialEq, Eq)]
pub enum MergeError {
    /// No batch given.
    #[error("no batch to merge")]
    Nothing,
    /// A batch of another scene (or another version of its file).
    #[error("batch {0} is of another scene (its digest differs)")]
    OtherScene(Batch),
    /// A batch of other settings (sample count, seed, and what else changes the result).
    #[error("batch {0} has other settings (samples, seed or others) than the first")]
    OtherSettings(Batch),
    /// A batch of another split.
    #[error("batch {0} is not one of {1} batches like the first")]
    OtherBatching(Batch, u32),
    /// A batch given twice.
    #[error("batch {0} is given twice")]
    Twice(Batch),
    /// A batch missing.
    #[error("batch {0} is missing")]
    Missing(Batch),
    /// A batch stopped before all its samples were done.
    #[error("batch {0} was stopped before all its samples were done: run it again")]
    CutShort(Batch),
    /// A batch whose sums do not fit its own settings (a damaged or altered file).
    #[error("batch {0} is damaged: its sums do not match its settings")]
    Damaged(Batch),
}

/// What a merge checks of one batch's partial result.
#[derive(Debug)]
pub struct BatchPart<'a, S> {
    /// [`crate::scene::Scene::digest`] of the scene it ran on, in hex.
    pub scene_digest: &'a str,
    /// The run's settings (all its samples, not the batch's).
    pub settings: &'a S,
    /// Which batch.
    pub batch: Batch,
    /// Samples the batch did (photons, or samples per pixel).
    pub done: u64,
    /// Samples of the run (`settings`' photons or samples per pixel), of which the batch had
    /// its [`Batch::share`].
    pub total: u64,
}

/// Checks that `parts` make one run on the scene of digest `scene_digest`: each of the same
/// scene and settings as the first, of the same split, given once and done whole, and no
/// batch of the split missing. The first problem found (in the order of `parts`) is the
/// error.
pub fn check_batches<'a, S: PartialEq + 'a>(
    scene_digest: &str,
    parts: impl IntoIterator<Item = BatchPart<'a, S>>,
) -> Result<(), MergeError> {
    let mut parts = parts.into_iter().peekable();
    let (settings, count) = parts
        .peek()
        .map(|first| (first.settings, first.batch.count))
        .ok_or(MergeError::Nothing)?;
    let mut seen = vec![false; count as usize];
    for p in parts {
        if p.scene_digest != scene_digest {
            return Err(MergeError::OtherScene(p.batch));
        }
        if p.settings != settings {
            return Err(MergeError::OtherSettings(p.batch));
        }
        if p.batch.count != count || p.batch.index >= count {
            return Err(MergeError::OtherBatching(p.batch, count));
        }
        if std::mem::replace(&mut seen[p.batch.index as usize], true) {
            return Err(MergeError::Twice(p.batch));
        }
        let share = p
            .batch
            .share(p.total)
            .map_err(|_| MergeError::OtherBatching(p.batch, count))?;
        if p.done != share.end - share.start {
            return Err(MergeError::CutShort(p.batch));
        }
    }
    match seen.iter().position(|s| !s) {
        Some(missing) => Err(MergeError::Missing(Batch {
            index: missing as u32,
            count,
        })),
        None => Ok(()),
    }
}
