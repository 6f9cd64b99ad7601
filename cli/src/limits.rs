//! What the command line refuses before any work starts: numbers that are not finite, counts
//! that must be at least one, and the bounds on image size, samples and mesh size that keep
//! a typing slip (`--width 100000 --height 100000`, `--spp 4294967295`) from running for
//! ever or failing to allocate; and the memory bound the running work is held to
//! ([`super::progress::watch_memory`]). Each bound names the flag that raises it.

use anyhow::{Result, bail};
use clap::Args;
use strahl::method::usable_memory_bytes;
use strahl::scene::LoadOptions;

/// Most photons one light-model run may trace (`--photons` of `solve` and `validate`): 10¹²,
/// about three days on two cores; a run of more would not end in any useful time.
pub const MAX_PHOTONS: u64 = 1_000_000_000_000;

/// Most points per emitting surface and rays per sensor of `validate`'s ray tracers
/// (`--samples`): 2²⁴, sixteen times the default; the suite's largest case takes about a
/// minute per 2²⁰ on two cores.
pub const MAX_VALIDATE_SAMPLES: u32 = 1 << 24;

/// Most repetitions of `bench`'s query passes.
pub const MAX_REPEATS: u32 = 1000;

/// The bounds on how much work one command may ask for.
#[derive(Clone, Copy, Debug, Args)]
#[command(next_help_heading = "Limits")]
pub struct LimitArgs {
    /// Largest image, in pixels (width × height).
    #[arg(long, default_value_t = 1 << 26, value_parser = clap::value_parser!(u64).range(1..))]
    pub max_pixels: u64,
    /// Largest sample count per pixel or per point (--spp, --light-samples, --gather-rays,
    /// --first-hit-paths, --receiver-samples², --link-samples², --vis-rays per pair).
    #[arg(long, default_value_t = 1 << 16, value_parser = clap::value_parser!(u32).range(1..))]
    pub max_samples: u32,
    /// Radiosity: most patches the initial mesh may have.
    #[arg(long, default_value_t = 4_000_000, value_parser = clap::value_parser!(u64).range(1..))]
    pub max_patches: u64,
    /// Most texels one texture may have (16 bytes each in memory); larger images are refused
    /// before they are decoded.
    #[arg(long, default_value_t = strahl::scene::MAX_TEXELS, value_parser = clap::value_parser!(u64).range(1..))]
    pub max_texels: u64,
    /// The memory bound.
    #[command(flatten)]
    pub memory: MemoryArgs,
}

/// The memory bound alone, for the commands that take no images or meshes (`info`, `bench`,
/// `validate`).
#[derive(Clone, Copy, Debug, Args)]
#[command(next_help_heading = "Limits")]
pub struct MemoryArgs {
    /// Most resident memory the run may use, MiB (default: three quarters of the machine's
    /// memory). Over it, the work stops with a message instead of being killed.
    #[arg(long, value_name = "MIB", value_parser = clap::value_parser!(u64).range(1..))]
    pub max_memory: Option<u64>,
}

impl MemoryArgs {
    /// The memory bound, bytes: `--max-memory`, or three quarters of the machine's memory
    /// (`None` where the system does not say how much it has).
    pub fn bytes(&self) -> Option<u64> {
        match self.max_memory {
            Some(mib) => Some(mib.saturating_mul(1 << 20)),
            None => usable_memory_bytes().map(|bytes| bytes / 4 * 3),
        }
    }
}

impl LimitArgs {
    /// Refuses an image of `width × height` pixels beyond `--max-pixels`.
    pub fn check_image(&self, width: u32, height: u32) -> Result<()> {
        let pixels = u64::from(width) * u64::from(height);
        if pixels > self.max_pixels {
            bail!(
                "a {width}×{height} image has {pixels} pixels, more than --max-pixels {} \
                 (raise --max-pixels to render it)",
                self.max_pixels
            );
        }
        Ok(())
    }

    /// The memory bound, bytes (see [`MemoryArgs::bytes`]).
    pub fn memory_bytes(&self) -> Option<u64> {
        self.memory.bytes()
    }

    /// How scene files are to be read under these bounds.
    pub fn load_options(&self) -> LoadOptions {
        LoadOptions {
            max_texels: self.max_texels,
        }
    }

    /// Refuses `count` samples given by `flag` beyond `--max-samples`.
    pub fn check_samples(&self, flag: &str, count: u64) -> Result<()> {
        if count > u64::from(self.max_samples) {
            bail!(
                "{flag} {count} is more than --max-samples {} (raise --max-samples to allow it)",
                self.max_samples
            );
        }
        Ok(())
    }
}

/// A finite number (clap value parser for `f32` and `f64`): NaN and infinities are refused
/// with the value shown.
pub fn finite<T>(text: &str) -> Result<T, String>
where
    T: std::str::FromStr + Copy + Into<f64>,
    T::Err: std::fmt::Display,
{
    let x: T = text.parse().map_err(|e| format!("{e}"))?;
    if x.into().is_finite() {
        Ok(x)
    } else {
        Err(format!("must be a finite number, got {text}"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn limits() -> LimitArgs {
        LimitArgs {
            max_pixels: 100,
            max_samples: 8,
            max_patches: 10,
            max_texels: 16,
            memory: MemoryArgs {
                max_memory: Some(3),
            },
        }
    }

    #[test]
    fn bounds_name_the_flag_that_raises_them() {
        let l = limits();
        assert!(l.check_image(10, 10).is_ok());
        let e = l.check_image(100_000, 100_000).unwrap_err().to_string();
        assert!(
            e.contains("10000000000 pixels") && e.contains("--max-pixels"),
            "{e}"
        );
        assert!(l.check_samples("--spp", 8).is_ok());
        let e = l.check_samples("--spp", 9).unwrap_err().to_string();
        assert!(
            e.contains("--spp 9") && e.contains("--max-samples 8"),
            "{e}"
        );
    }

    #[test]
    fn memory_bound_is_the_flag_or_a_share_of_the_machine() {
        assert_eq!(limits().memory_bytes(), Some(3 << 20));
        let default = MemoryArgs { max_memory: None };
        if let (Some(bound), Some(machine)) = (default.bytes(), usable_memory_bytes()) {
            assert!(bound < machine && bound >= machine / 2);
        }
    }

    #[test]
    fn floats_must_be_finite() {
        assert_eq!(finite::<f32>("1.5"), Ok(1.5));
        assert!(finite::<f32>("nan").unwrap_err().contains("finite"));
        assert!(finite::<f64>("inf").unwrap_err().contains("finite"));
        assert!(finite::<f64>("x").is_err());
    }
}
